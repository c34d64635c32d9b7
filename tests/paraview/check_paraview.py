"""Loads fe-prep's BODY.xdmf and mbs-run's animation R.pvd with ParaView itself
(run with pvpython) and checks them against the HDF5 files they come from:

  pvpython check_paraview.py BODY.h5 BODY.xdmf RESULTS.h5 R.pvd EVERY FLEX_BODY_NAME

- BODY.xdmf, in each of ParaView's XDMF readers (the legacy "XDMF Reader" and
  the Xdmf3 readers "Xdmf3ReaderS" and "Xdmf3ReaderT", which OpenDataFile picks),
  from the working directory given, from another directory with an absolute
  path, and from the file's own directory (the legacy reader with the bare file
  name; the Xdmf3 readers as ./BODY.xdmf, see docs/file-formats.md): point and
  cell counts of /mesh, one vector field per mode and per mode rotation named
  mode_NN_F.FFHz[_rotation], and their values equal to /modes/shapes (exactly:
  the file points into it), and the nodal mass equal to /mass/nodal[:, 0].
- R.pvd: one time step per EVERY-th output time at the output times, one block
  per body named after it, the flexible body's point count, and at a frame
  after the latch the field `displacement` of the tip node equal to
  A(p) sum_j w_j phi_j computed here from the results and body files (the
  modal result), and the points equal to r + A s0 (undeformed, moved).
Exit status 0 when every check holds, 1 otherwise (each failure printed).
"""
import os
import sys

import h5py
import numpy as np
from paraview import servermanager as sm
from paraview.simple import PVDReader, UpdatePipeline, XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT
from vtk.numpy_interface import dataset_adapter as dsa

body_h5, body_xdmf, results_h5, pvd, every, flex_name = sys.argv[1:7]
every = int(every)
body_h5, body_xdmf, results_h5, pvd = (os.path.abspath(p) for p in (body_h5, body_xdmf, results_h5, pvd))
given_xdmf = sys.argv[2]
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def rotation(p):
    e0, e = p[0], np.asarray(p[1:])
    s = np.array([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
    return (2 * e0 * e0 - 1) * np.eye(3) + 2 * (np.outer(e, e) + e0 * s)


with h5py.File(body_h5, "r") as f:
    nodes = f["mesh/nodes"][:]
    n_cells = sum(f["mesh/" + k].shape[0] for k in ("triangles", "beams") if "mesh/" + k in f)
    shapes = f["modes/shapes"][:]
    freqs = f["modes/frequencies_hz"][:]

# ---- the body file's XDMF ----------------------------------------------------
def open_xdmf(reader, path):
    if reader == "XDMFReader":
        r = XDMFReader(FileNames=[path])
        r.PointArrayStatus = r.GetProperty("PointArrayInfo")[::2]
    else:
        r = {"Xdmf3ReaderS": Xdmf3ReaderS, "Xdmf3ReaderT": Xdmf3ReaderT}[reader](FileName=[path])
    r.UpdatePipeline()
    d = sm.Fetch(r)
    if d.IsA("vtkMultiBlockDataSet"):
        d = d.GetBlock(0)
    return d


def check_xdmf(reader, path, where):
    tag = f"xdmf {reader} ({where}, {path})"
    d = open_xdmf(reader, path)
    check(d is not None and d.GetNumberOfPoints() == len(nodes),
          f"{tag}: {d.GetNumberOfPoints() if d else 0} points, body file {len(nodes)}")
    if d is None or d.GetNumberOfPoints() != len(nodes):
        return
    check(d.GetNumberOfCells() == n_cells, f"{tag}: {d.GetNumberOfCells()} cells, body file {n_cells}")
    w = dsa.WrapDataObject(d)
    check(np.allclose(np.array(w.Points), nodes, rtol=0, atol=0), f"{tag}: points are /mesh/nodes")
    names = [d.GetPointData().GetArrayName(i) for i in range(d.GetPointData().GetNumberOfArrays())]
    check(len(names) == 1 + 2 * len(freqs), f"{tag}: {len(names)} fields, expected {1 + 2 * len(freqs)}")
    if "nodal_mass" in names:
        check(np.array_equal(np.array(w.PointData["nodal_mass"]).ravel(), nodal_mass[:, 0]),
              f"{tag}: nodal_mass = /mass/nodal[:, 0]")
    else:
        check(False, f"{tag}: field nodal_mass")
    for j, fr in enumerate(freqs):
        mode = [n for n in names if n.startswith(f"mode_{j + 1:02d}_") and n.endswith("Hz")]
        rot = [n for n in names if n.startswith(f"mode_{j + 1:02d}_") and n.endswith("Hz_rotation")]
        check(len(mode) == 1 and len(rot) == 1, f"{tag}: mode {j + 1} fields {mode + rot}")
        if mode and rot:
            label = float(mode[0][len(f"mode_{j + 1:02d}_"):-2])
            check(abs(label - fr) <= 5e-4 * fr, f"{tag}: {mode[0]} names {fr:.6g} Hz")
            u, th = np.array(w.PointData[mode[0]]), np.array(w.PointData[rot[0]])
            check(u.shape == (len(nodes), 3) and np.array_equal(u, shapes[j, :, :3]), f"{tag}: {mode[0]} = /modes/shapes[{j}, :, 0:3]")
            check(th.shape == (len(nodes), 3) and np.array_equal(th, shapes[j, :, 3:]), f"{tag}: {rot[0]} = /modes/shapes[{j}, :, 3:6]")


with h5py.File(body_h5, "r") as f:
    nodal_mass = f["mass/nodal"][:]
readers = ["XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT"]
start = os.getcwd()
for reader in readers:
    check_xdmf(reader, given_xdmf, "as given")
os.chdir("/")  # any other working directory, the path absolute
for reader in readers:
    check_xdmf(reader, body_xdmf, "from /")
os.chdir(os.path.dirname(body_xdmf))  # the file's own directory
bare = os.path.basename(body_xdmf)
check_xdmf("XDMFReader", bare, "its directory, bare name")
for reader in readers[1:]:
    check_xdmf(reader, "./" + bare, "its directory")
os.chdir(start)

# ---- the animation ------------------------------------------------------------
with h5py.File(results_h5, "r") as f:
    t = f["time"][:]
    bodies = list(f["bodies"].keys())
    g = f["bodies"][flex_name]
    pos, ori, modal = g["position"][:], g["orientation"][:], g["modal_coordinates"][:]
frames = list(range(0, len(t), every))
a = PVDReader(FileName=pvd)
steps = list(a.TimestepValues)
check(len(steps) == len(frames), f"pvd: {len(steps)} time steps, expected {len(frames)}")
check(np.allclose(steps, t[frames], rtol=0, atol=1e-12), "pvd: time steps are the output times")
# A frame late in the run (after the latch, where the modes ring), and the node
# farthest from the frame origin (the panel's free edge).
k = frames[-1] if len(frames) < 4 else frames[(3 * len(frames)) // 4]
a.UpdatePipeline(t[k])
mb = sm.Fetch(a)
blocks = {}
it = mb.NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    blocks[it.GetCurrentMetaData().Get(mb.NAME())] = it.GetCurrentDataObject()
    it.GoToNextItem()
check(sorted(blocks) == sorted(bodies), f"pvd: blocks {sorted(blocks)}, bodies {sorted(bodies)}")
fb = dsa.WrapDataObject(blocks[flex_name])
check(fb.GetNumberOfPoints() == len(nodes), f"pvd: {flex_name} has {fb.GetNumberOfPoints()} points")
A = rotation(ori[k] / np.linalg.norm(ori[k]))
u_expected = (np.tensordot(modal[k], shapes[: modal.shape[1], :, :3], axes=1)) @ A.T
x_expected = pos[k] + nodes @ A.T
tip = int(np.argmax(np.linalg.norm(u_expected, axis=1)))  # the largest elastic displacement
u = np.array(fb.PointData["displacement"])
umax = np.abs(u_expected).max()
check(umax > 0, f"pvd: t = {t[k]:.4g} s, largest elastic displacement {umax:.3e} m")
# Both sides are the same double-precision sums up to order: rounding only.
check(np.allclose(u[tip], u_expected[tip], rtol=1e-12, atol=1e-15 * max(umax, 1e-300)),
      f"pvd: displacement at node {tip} {u[tip]} vs modal result {u_expected[tip]}")
check(np.allclose(u, u_expected, rtol=1e-12, atol=1e-12 * umax), "pvd: displacement at every node")
check(np.allclose(np.array(fb.Points), x_expected, rtol=0, atol=1e-12), "pvd: points = r + A s0 (undeformed, moved)")
for name, blk in blocks.items():
    if name != flex_name:
        check(blk.GetNumberOfPoints() > 0, f"pvd: rigid body {name} drawn with {blk.GetNumberOfPoints()} points")
print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
