"""Loads mbs-run's animation R.pvd of a run with a beam body in outputs.stresses
with ParaView itself and checks the beam's cell field failure_index:

  pvpython check_beam_paraview.py RESULTS.h5 R.pvd BEAM_BODY

in ParaView's PVD reader (every frame) and its XML PolyData reader (each
frame's .vtp of the beam), it must equal, per beam element (line), the largest
Tsai-Wu index over the element's three stations and every section element in
RESULTS.h5's /bodies/BEAM/failure_index (n_out, 3 n_elements, n_section_elements)
at that frame's time, to the last bit (the same doubles). Exit 1 on a mismatch.
"""
import glob
import os
import sys

import h5py
import numpy as np
from paraview import servermanager as sm
from paraview.simple import PVDReader, XMLPolyDataReader
from vtk.numpy_interface import dataset_adapter as dsa

results_h5, pvd, beam = sys.argv[1:4]
results_h5, pvd = os.path.abspath(results_h5), os.path.abspath(pvd)
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


with h5py.File(results_h5, "r") as f:
    t = f["time"][:]
    fi = f["bodies"][beam]["failure_index"][:]
n_el = fi.shape[1] // 3
expected = fi.reshape(len(t), n_el, 3 * fi.shape[2]).max(axis=2)  # (n_out, n_el)
check(expected.max() > 0, f"results: the beam's largest index {expected.max():.3e} > 0")

a = PVDReader(FileName=pvd)
steps = list(a.TimestepValues)
check(len(steps) == len(t), f"pvd: {len(steps)} time steps for {len(t)} output rows")
for k, tk in enumerate(steps):
    a.UpdatePipeline(tk)
    mb = sm.Fetch(a)
    it = mb.NewIterator()
    it.InitTraversal()
    blk = None
    while not it.IsDoneWithTraversal():
        if it.GetCurrentMetaData().Get(mb.NAME()) == beam:
            blk = it.GetCurrentDataObject()
        it.GoToNextItem()
    check(blk is not None, f"pvd: t = {tk:.4g} s has a block {beam}")
    if blk is None:
        continue
    w = dsa.WrapDataObject(blk)
    check(blk.GetNumberOfLines() == n_el, f"pvd: t = {tk:.4g} s, {blk.GetNumberOfLines()} lines for {n_el} beam elements")
    got = np.array(w.CellData["failure_index"])
    check(np.array_equal(got, expected[k]), f"pvd: t = {tk:.4g} s, failure_index per element {got} = results {expected[k]}")

# The XML PolyData reader on each frame's .vtp of the beam.
frames = sorted(glob.glob(os.path.join(os.path.dirname(pvd), os.path.basename(pvd)[:-4], f"*_{beam}.vtp")))
check(len(frames) == len(t), f"vtp: {len(frames)} frames of {beam}")
for k, path in enumerate(frames):
    r = XMLPolyDataReader(FileName=[path])
    r.UpdatePipeline()
    w = dsa.WrapDataObject(sm.Fetch(r))
    got = np.array(w.CellData["failure_index"])
    check(np.array_equal(got, expected[k]), f"vtp: {os.path.basename(path)} failure_index = results row {k}")
print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
