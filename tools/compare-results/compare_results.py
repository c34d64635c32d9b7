#!/usr/bin/python3
"""Runs a fixed set of scenes with one build and compares the files they write
with those of another build, bit for bit: the proof that a refactoring left
the results unchanged.

    compare_results.py run BUILD OUTDIR        # run the set with BUILD's tools into OUTDIR
    compare_results.py compare BASE NEW        # compare two OUTDIRs; exit 1 on any difference
    compare_results.py check BUILD BASE OUTDIR # run, then compare with BASE
    compare_results.py run BUILD OUTDIR 'feprep_*' sar_rigid_v1   # only the cases named (patterns)

BUILD is a CMake build tree holding section-prep/section-prep, fe-prep/fe-prep and
mbs-run/mbs-run. Every case runs in a folder of its own under OUTDIR/cases with its
inputs copied there and named by relative paths, so no path recorded in an output
depends on OUTDIR. The set (CASES below) takes about two minutes of CPU: the test
scenes of tests/data/mbs-run and tests/data/sar (short --t-end where a scene is long),
the teaching examples end to end (section-prep -> fe-prep -> mbs-run with CSV and
animation), the SAR example's rigid scene and a short flexible SAR run on the paper's
bodies, both formulations of the tree scenes, the three integrators, scenes whose input is wrong (their error messages and did-you-mean
hints are compared too), and fe-prep's bodies of every kind of build (FEPREP_CASES,
about 15 s of CPU). identical.sh runs the set with two builds and compares them.

What is compared:
  * every HDF5 file: the tree of groups and datasets, each dataset's type, shape and
    bytes, each attribute's type and bytes; except the attributes in VOLATILE_ATTRIBUTES;
  * every other file a case writes (CSV, .pvd, .vtu, .xdmf), byte for byte;
  * each command's exit code, its stderr, and its stdout with the figures in
    VOLATILE_STDOUT masked.
Not compared, because they legitimately change from run to run of one binary
(found by comparing two runs of one build, `compare` of two `run`s):
  * the root attribute `created` of every file (the time it was written);
  * the results' root attribute `cpu_seconds` (the CPU time the run took);
  * fe-prep's root attribute `inputs_sha256` (it hashes the input files, among them the
    section file section-prep wrote, whose `created` time is part of its bytes; every
    dataset and the other attributes of the body are compared);
  * CPU and wall times in text: mbs-run's "CPU ... s, real-time factor ...", fe-prep's
    stage timings ("0.083 s  (CPU 0.009 s, peak RSS 87 MB)"), and the CPU seconds the
    automatic integrator switch measured in its trial ("dopri5 0.0245 s CPU"), in the
    printed summary and in the results' `integrator_switches` attribute. The trial's
    decision itself rests on those measured CPU times (run/switch_trial.h): on a loaded
    machine it could go the other way, and the run's results with it; the compare
    then reports the difference (the set's one trial, the flexible beam, is far from
    the threshold: imex about 4 times cheaper, "dopri5 kept" for accuracy).
A `compare` of two runs of the same build is the check that this list is complete.
"""
import filecmp
import fnmatch
import os
import re
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

VOLATILE_ATTRIBUTES = {("/", "cpu_seconds"), ("/", "created")}
VOLATILE_FEPREP_ATTRIBUTES = {("/", "inputs_sha256")}
VOLATILE_TEXT = [(re.compile(r"CPU [0-9.]+ s, real-time factor [0-9.eE+-]+"), "CPU <masked> s, real-time factor <masked>"),
                 (re.compile(r"[0-9.]+ s  \(CPU [0-9.]+ s, peak RSS [0-9]+ MB\)( MUMPS factor [0-9]+ MB)?"), "<masked> s  (CPU <masked> s, peak RSS <masked> MB)"),
                 (re.compile(r"write +peak RSS [0-9]+ MB"), "write peak RSS <masked> MB"),
                 (re.compile(r"[0-9.eE+-]+ s CPU"), "<masked> s CPU")]


def mask(text):
    for rx, repl in VOLATILE_TEXT:
        text = rx.sub(repl, text)
    return text

SAR = "examples/sar-antenna"
SAR_TRUSSES = ["truss_B4", "truss_B5", "truss_B6", "truss_B7", "truss_B8", "truss_B9", "truss_B10", "truss_B11",
               "truss_B12"]
SAR_SECTIONS = {"truss_B4": "truss_d20", "truss_B7": "truss_d7", "truss_B8": "truss_d7"}  # else truss_d6


def _sar_flexible_steps():
    steps = []
    for s in ["truss_d6", "truss_d7", "truss_d20"]:
        steps.append(("section-prep", ["sections/%s.yaml" % s, "-o", "out/sections/%s.h5" % s, "-q"]))
    for b in ["panel2_iso", "panel3_iso"] + SAR_TRUSSES:
        steps.append(("fe-prep", ["bodies/%s.yaml" % b, "-o", "out/bodies/%s.h5" % b, "-q"]))
    steps.append(("mbs-run", ["sar-isotropic.yaml", "-o", "out/results/sar-isotropic.h5", "--t-end", "1.0",
                              "--csv", "out/results/sar-isotropic.csv", "--animation",
                              "out/paraview/sar-isotropic.pvd", "--animation-every", "10", "-q"]))
    for method in ["trbdf2", "imex"]:
        steps.append(("mbs-run", ["sar-isotropic.yaml", "-o", "out/results/sar-isotropic-%s.h5" % method,
                                  "--t-end", "0.2", "--integrator", method, "-q"]))
    return steps


def _scene_variant(src, dst, text):
    """A copy of the scene `src` with `text` appended (YAML: a later key overrides nothing,
    so variants replace the whole simulation: line)."""
    return ("variant", (src, dst, text))


# Each case: the files and folders copied into its folder (repository paths -> names
# there), then its steps: (tool, arguments) run in that folder, in order.
CASES = {
    # tests/data/mbs-run: the fuzzing reproductions (a status, not a crash) and the long pendulum.
    "conflicting_constraints": ({"tests/data/mbs-run/conflicting_constraints.yaml": "scene.yaml"},
                                [("mbs-run", ["scene.yaml", "-o", "r.h5", "-q"])]),
    "hang_huge_length": ({"tests/data/mbs-run/hang_huge_length.yaml": "scene.yaml"},
                         [("mbs-run", ["scene.yaml", "-o", "r.h5", "-q"])]),
    "double_pendulum_tiny_step": ({"tests/data/mbs-run/double_pendulum_tiny_step.yaml": "scene.yaml"},
                                  [("mbs-run", ["scene.yaml", "-o", "r.h5", "-q", "--t-end", "2e-4",
                                                "--csv", "r.csv"])]),
    "pendulum_long": ({"tests/data/mbs-run/pendulum_long.yaml": "scene.yaml"},
                      [("mbs-run", ["scene.yaml", "-o", "r.h5", "-q", "--t-end", "3"]),
                       ("mbs-run", ["scene.yaml", "-o", "r-trbdf2.h5", "-q", "--t-end", "1", "--integrator",
                                    "trbdf2"]),
                       ("mbs-run", ["scene.yaml", "-o", "r-imex.h5", "-q", "--t-end", "1", "--integrator",
                                    "imex"]),
                       _scene_variant("scene.yaml", "constrained.yaml",
                                      "simulation: {t_end: 3, output_step: 0.01, rtol: 1.0e-8, "
                                      "formulation: constrained}\n"),
                       ("mbs-run", ["constrained.yaml", "-o", "r-constrained.h5", "-q"])]),
    "double_pendulum_formulations": ({"tests/data/mbs-run/double_pendulum_tiny_step.yaml": "scene.yaml"},
                                     [_scene_variant("scene.yaml", "tree.yaml",
                                                     "simulation: {t_end: 2, output_step: 0.01, rtol: 1.0e-6, "
                                                     "formulation: tree}\n"),
                                      ("mbs-run", ["tree.yaml", "-o", "tree.h5", "-q"]),
                                      _scene_variant("scene.yaml", "constrained.yaml",
                                                     "simulation: {t_end: 2, output_step: 0.01, rtol: 1.0e-6, "
                                                     "formulation: constrained}\n"),
                                      ("mbs-run", ["constrained.yaml", "-o", "constrained.h5", "-q"])]),
    "tree_3d_formulations": ({"tests/data/mbs-run/tree_3d.yaml": "scene.yaml"},
                             [("mbs-run", ["scene.yaml", "-o", "tree.h5", "-q"]),
                              _scene_variant("scene.yaml", "constrained.yaml",
                                             "simulation: {t_end: 1.0, output_step: 0.01, rtol: 1.0e-8, "
                                             "formulation: constrained}\n"),
                              ("mbs-run", ["constrained.yaml", "-o", "constrained.h5", "-q"])]),
    # tests/data/sar: the rigid SAR reconstructions (closed loops, events, stops), whole runs.
    "sar_rigid_v1": ({"tests/data/sar/sar-rigid-scene-v1.yaml": "scene.yaml"},
                     [("mbs-run", ["scene.yaml", "-o", "r.h5", "-q", "--csv", "r.csv"])]),
    "sar_rigid_v2": ({"tests/data/sar/sar-rigid-scene-v2.yaml": "scene.yaml"},
                     [("mbs-run", ["scene.yaml", "-o", "r.h5", "-q"])]),
    # The teaching examples, end to end.
    "example_pendulum": ({"examples/pendulum/pendulum.yaml": "pendulum.yaml"},
                         [("mbs-run", ["pendulum.yaml", "-o", "out/pendulum.h5", "--animation", "out/pendulum.pvd",
                                       "-q", "--csv", "out/pendulum.csv"])]),
    "example_flexible_beam": ({"examples/flexible-beam/tube.yaml": "tube.yaml",
                               "examples/flexible-beam/beam.yaml": "beam.yaml",
                               "examples/flexible-beam/scene.yaml": "scene.yaml"},
                              [("section-prep", ["tube.yaml", "-o", "out/tube.h5", "-q"]),
                               ("fe-prep", ["beam.yaml", "-o", "out/beam.h5", "-q"]),
                               ("mbs-run", ["scene.yaml", "-o", "out/beam-run.h5", "--animation",
                                            "out/beam-run.pvd", "--animation-every", "5", "-q"])]),
    "example_hinged_panel": ({"examples/hinged-panel/panel.yaml": "panel.yaml",
                              "examples/hinged-panel/scene.yaml": "scene.yaml"},
                             [("fe-prep", ["panel.yaml", "-o", "out/panel.h5", "-q"]),
                              ("mbs-run", ["scene.yaml", "-o", "out/hinged-panel.h5", "--animation",
                                           "out/hinged-panel.pvd", "-q"])]),
    # The SAR example: the rigid scene whole, the isotropic flexible one for its first second.
    "sar_example_rigid": ({SAR + "/sar-rigid.yaml": "sar-rigid.yaml"},
                          [("mbs-run", ["sar-rigid.yaml", "-o", "out/results/sar-rigid.h5", "-q", "--csv",
                                        "out/results/sar-rigid.csv", "--animation", "out/paraview/sar-rigid.pvd",
                                        "--animation-every", "10"])]),
    "sar_example_isotropic": ({SAR + "/sar-isotropic.yaml": "sar-isotropic.yaml", SAR + "/bodies": "bodies",
                               SAR + "/sections": "sections"},
                              _sar_flexible_steps()),
    # Wrong input: the messages (file, line, key, did-you-mean) are part of the behaviour.
    "bad_inputs": ({"tests/data/mbs-run/conflicting_constraints.yaml": "scene.yaml",
                    "examples/hinged-panel/panel.yaml": "panel.yaml",
                    "examples/flexible-beam/tube.yaml": "tube.yaml",
                    "examples/flexible-beam/beam.yaml": "beam.yaml"},
                   [("sed", ["s/t_end:/t_ned:/", "scene.yaml", "bad-key.yaml"]),
                    ("mbs-run", ["bad-key.yaml", "-o", "a.h5", "-q"]),
                    ("sed", ["s/bodies: \\[ground, a\\]/bodies: [grund, a]/", "scene.yaml", "bad-body.yaml"]),
                    ("mbs-run", ["bad-body.yaml", "-o", "b.h5", "-q"]),
                    ("sed", ["s/type: revolute/type: revolut/", "scene.yaml", "bad-type.yaml"]),
                    ("mbs-run", ["bad-type.yaml", "-o", "c.h5", "-q"]),
                    ("sed", ["s/type: gravity/type: gravty/", "scene.yaml", "bad-force.yaml"]),
                    ("mbs-run", ["bad-force.yaml", "-o", "d.h5", "-q"]),
                    ("sed", ["s/thickness:/thicknes:/", "panel.yaml", "bad-panel.yaml"]),
                    ("fe-prep", ["bad-panel.yaml", "-o", "e.h5", "-q"]),
                    ("sed", ["s/elements: 20/elemnts: 20/", "beam.yaml", "bad-beam.yaml"]),
                    ("fe-prep", ["bad-beam.yaml", "-o", "f.h5", "-q"]),
                    ("sed", ["0,/type: orthotropic/s//type: orthotropc/", "tube.yaml", "bad-material.yaml"]),
                    ("section-prep", ["bad-material.yaml", "-o", "g.h5", "-q"])]),
}


# fe-prep's bodies, one case per kind of build (buildFlexBody's paths): free-free and
# held shells and beams, point, rigid and distributing interfaces, Craig-Bampton with
# `keep:`, static correction (held and with inertia relief), `static_error`, geometric
# stiffness, moment lumping, laminates, imported CalculiX matrices, Nastran decks and
# gmsh mesh-file regions. Each runs in a few seconds; the YAMLs written inline follow
# the tests' (tests/fe-prep).
def _write(dst, text):
    return ("write", (dst, text))


_ISO = "materials:\n  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}\n"
_STEEL = "materials:\n  steel: {type: isotropic, E: 210.0e9, nu: 0.3, rho: 7850}\n"
_HALF = (_STEEL + "body:\n  name: half\n  beam: {length: 1.0, elements: 10, section: {shape: solid_circle, "
         "diameter: 0.02, material: steel}}\n  interfaces: {a: [-0.5, 0, 0], b: [0.5, 0, 0]}\n")
_PANEL = _ISO + "body:\n  name: panel\n  shell: {rectangle: {length: 1.0, width: 0.65}, material: cfrp_iso, thickness: 0.002, mesh: {size: 0.05}}\n"
_IMPORT = "tests/data/import/"
_FEPREP = "tests/data/fe-prep/"


def _feprep(yaml, out):
    return ("fe-prep", [yaml, "-o", out, "-q"])


FEPREP_CASES = {
    "feprep_data_bodies": ({_FEPREP + "spinning_rod.yaml": "rod.yaml", _FEPREP + "spinning_strip.yaml": "strip.yaml",
                            _FEPREP + "steel_bar_pendulum.yaml": "bar.yaml"},
                           [_feprep("rod.yaml", "rod.h5"), _feprep("strip.yaml", "strip.h5"),
                            _feprep("bar.yaml", "bar.h5")]),
    "feprep_craig_bampton": ({}, [
        _write("half.yaml", _HALF + "  reference: {clamp: [a, b]}\n  reduction: craig_bampton\n  modes: 2\n"),
        _feprep("half.yaml", "half.h5"),
        _write("keep.yaml", _HALF + "  reference: {clamp: [a, b]}\n  reduction: craig_bampton\n  modes: {keep: [1, 3, 5]}\n"),
        _feprep("keep.yaml", "keep.h5"),
        _write("free.yaml", _HALF + "  reference: free\n  modes: {keep: [2, 4]}\n  mass: consistent\n"),
        _feprep("free.yaml", "free.h5"),
        _write("pins.yaml", _PANEL + "  interfaces:\n"
               "    P0: {point: [-0.4, -0.25, 0.0], coupling: distributing, nodes: {within: 0.08}}\n"
               "    P1: {point: [-0.4, 0.25, 0.0], coupling: distributing, nodes: {within: 0.08}}\n"
               "    R: {point: [0.5, 0.0, 0.05], coupling: rigid, nodes: {within: 0.08}}\n"
               "    T: [0.5, 0.3, 0.0]\n"
               "  reference: {pin: [P0, P1], clamp: [R, T]}\n  reduction: craig_bampton\n  modes: 6\n  mass: lumped\n"),
        _feprep("pins.yaml", "pins.h5")]),
    "feprep_static_correction": ({}, [
        _write("relief.yaml", _PANEL + "  interfaces:\n"
               "    H1: {point: [-0.5, -0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}\n"
               "    T: {point: [0.5, 0.0, 0.07], coupling: distributing, nodes: {within: 0.1}}\n"
               "  reference: free\n  modes: {count: 4, static_correction: [T]}\n"),
        _feprep("relief.yaml", "relief.h5"),
        _write("held.yaml", _PANEL + "  interfaces:\n"
               "    H1: {point: [-0.5, -0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}\n"
               "    H2: {point: [-0.5, 0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}\n"
               "    T: {point: [0.5, 0.0, 0.07], coupling: rigid, nodes: {within: 0.1}}\n"
               "  reference: {clamp: [H1, H2]}\n  modes: {count: 4, static_correction: true}\n  mass: lumped_moments\n"),
        _feprep("held.yaml", "held.h5"),
        _write("error.yaml", _STEEL + "body:\n  name: cantilever\n  beam: {length: 2.0, elements: 40, section: "
               "{shape: solid_circle, diameter: 0.02, material: steel}}\n  interfaces: {root: [-1.0, 0, 0], tip: [1.0, 0, 0]}\n"
               "  reference: {clamp: [root]}\n  modes: {static_error: 0.004}\n"),
        _feprep("error.yaml", "error.h5")]),
    "feprep_sar_panels": ({SAR + "/bodies": "bodies"},
                          [_feprep("bodies/panel2_iso.yaml", "panel2_iso.h5"),
                           _feprep("bodies/panel3_layup2.yaml", "panel3_layup2.h5")]),
    "feprep_imported": ({_IMPORT + f: f for f in ["fitting_matrices.sti", "fitting_matrices.mas", "fitting_matrices.dof",
                                                  "fitting_mesh.inp", "bar_matrices.sti", "bar_matrices.mas",
                                                  "bar_matrices.dof", "bar_mesh.inp"]}, [
        _write("fitting.yaml", "body:\n  name: fitting\n  matrices: {format: calculix, stiffness: fitting_matrices.sti, "
               "mass: fitting_matrices.mas, dofs: fitting_matrices.dof, model: fitting_mesh.inp}\n  units: mm-t-s\n"
               "  interfaces:\n    pin: {point: [0.0, 0.0, 0.030], coupling: rigid, nodes: {edge: LUGTOP}}\n"
               "  reference: free\n  modes: 4\n"),
        _feprep("fitting.yaml", "fitting.h5"),
        _write("bar.yaml", "body:\n  name: bar\n  matrices: {format: calculix, stiffness: bar_matrices.sti, mass: "
               "bar_matrices.mas, dofs: bar_matrices.dof, model: bar_mesh.inp}\n  units: mm-t-s\n  modes: 6\n"),
        _feprep("bar.yaml", "bar.h5")]),
    "feprep_mesh_files": ({"examples/stiffened-panel/panel.yaml": "panel.yaml",
                           "examples/stiffened-panel/panel.geo": "panel.geo",
                           "examples/stiffened-panel/panel.bdf": "panel.bdf",
                           "examples/stiffened-panel/panel_deck.yaml": "panel_deck.yaml",
                           _FEPREP + "nastran/panel_small.bdf": "panel_small.bdf",
                           _FEPREP + "nastran/panel_grids_small.inc": "panel_grids_small.inc",
                           _FEPREP + "nastran/panel_free.bdf": "panel_free.bdf"},
                          [_feprep("panel.yaml", "panel.h5"), _feprep("panel_deck.yaml", "panel_deck.h5"),
                           _write("small.yaml", "body:\n  name: small\n  mesh: {file: panel_small.bdf}\n  units: m-kg-s\n  interfaces:\n"
                                  "    hinge: {rbe: 9100}\n    fitting: {grid: 153}\n  reference: {clamp: [hinge]}\n  modes: 6\n"),
                           _feprep("small.yaml", "small.h5"),
                           _write("free.yaml", "body:\n  name: free\n  mesh: {file: panel_free.bdf}\n  units: m-kg-s\n  modes: 6\n"),
                           _feprep("free.yaml", "free.h5")]),
}
CASES.update(FEPREP_CASES)

TOOLS = {"section-prep": "section-prep/section-prep", "fe-prep": "fe-prep/fe-prep", "mbs-run": "mbs-run/mbs-run"}


def run(build, outdir, only=None):
    build = os.path.abspath(build)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    total_cpu = 0.0
    for name, (inputs, steps) in CASES.items():
        if only and not any(fnmatch.fnmatch(name, o) for o in only):
            continue
        case = os.path.join(outdir, "cases", name)
        if os.path.exists(case):
            shutil.rmtree(case)
        os.makedirs(case)
        for src, dst in inputs.items():
            s = os.path.join(REPO, src)
            (shutil.copytree if os.path.isdir(s) else shutil.copy)(s, os.path.join(case, dst))
        log = os.path.join(outdir, "logs", name)
        os.makedirs(log, exist_ok=True)
        cpu0 = os.times()
        for k, (tool, args) in enumerate(steps):
            if tool == "variant":
                src, dst, text = args
                with open(os.path.join(case, src)) as f:
                    body = f.read()
                body = "\n".join(l for l in body.splitlines() if not l.startswith("simulation:")) + "\n"
                with open(os.path.join(case, dst), "w") as f:
                    f.write(body + text)
                continue
            if tool == "write":
                dst, text = args
                with open(os.path.join(case, dst), "w") as f:
                    f.write(text)
                continue
            if tool == "sed":
                expr, src, dst = args
                with open(os.path.join(case, dst), "w") as f:
                    subprocess.run(["sed", expr, src], cwd=case, stdout=f, check=True)
                continue
            for d in args:  # output folders the tools expect to exist
                if "/" in d and d.startswith("out/"):
                    os.makedirs(os.path.join(case, os.path.dirname(d)), exist_ok=True)
            p = subprocess.run([os.path.join(build, TOOLS[tool])] + args, cwd=case, env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            out, err = mask(p.stdout.decode(errors="replace")), mask(p.stderr.decode(errors="replace"))
            with open(os.path.join(log, "%02d-%s.txt" % (k, tool)), "w") as f:
                f.write("$ %s %s\nexit %d\n--- stdout\n%s--- stderr\n%s" %
                        (tool, " ".join(args), p.returncode, out, err))
        cpu1 = os.times()
        cpu = (cpu1.children_user - cpu0.children_user) + (cpu1.children_system - cpu0.children_system)
        total_cpu += cpu
        print("%-30s %6.1f s CPU" % (name, cpu), flush=True)
    print("%-30s %6.1f s CPU" % ("all", total_cpu))


def _h5_differences(a, b):
    diffs = []

    volatile = set(VOLATILE_ATTRIBUTES)
    with h5py.File(a, "r") as fa:
        if fa.attrs.get("tool") in (b"fe-prep", "fe-prep"):
            volatile |= VOLATILE_FEPREP_ATTRIBUTES

    def attrs(pa, pb, path):
        ka, kb = set(pa.attrs.keys()), set(pb.attrs.keys())
        for k in sorted(ka ^ kb):
            diffs.append("%s: attribute %s only in %s" % (path, k, "base" if k in ka else "new"))
        for k in sorted(ka & kb):
            if (path, k) in volatile:
                continue
            va, vb = pa.attrs.get_id(k), pb.attrs.get_id(k)
            x, y = np.asarray(pa.attrs[k]), np.asarray(pb.attrs[k])
            if x.dtype.kind in "SO" and x.shape == () and y.dtype.kind in "SO" and y.shape == ():
                # Strings: compared with their CPU figures masked (a string's length is its type).
                if mask(_text(x[()])) != mask(_text(y[()])):
                    diffs.append("%s: attribute %s: %r != %r" % (path, k, pa.attrs[k], pb.attrs[k]))
                continue
            if va.dtype != vb.dtype or va.shape != vb.shape or not _same_bits(x, y):
                diffs.append("%s: attribute %s: %r != %r" % (path, k, pa.attrs[k], pb.attrs[k]))

    def walk(ga, gb, path):
        attrs(ga, gb, path)
        ka, kb = set(ga.keys()), set(gb.keys())
        for k in sorted(ka ^ kb):
            diffs.append("%s: %s only in %s" % (path, k, "base" if k in ka else "new"))
        for k in sorted(ka & kb):
            p = path.rstrip("/") + "/" + k
            oa, ob = ga[k], gb[k]
            if isinstance(oa, h5py.Group) != isinstance(ob, h5py.Group):
                diffs.append("%s: group in one, dataset in the other" % p)
            elif isinstance(oa, h5py.Group):
                walk(oa, ob, p)
            else:
                attrs(oa, ob, p)
                if oa.dtype != ob.dtype or oa.shape != ob.shape:
                    diffs.append("%s: %s%s != %s%s" % (p, oa.dtype, oa.shape, ob.dtype, ob.shape))
                elif not _same_bits(oa[()], ob[()]):
                    x, y = np.asarray(oa[()]), np.asarray(ob[()])
                    where = ""
                    if x.dtype.kind == "f":
                        d = x != y
                        where = " (%d of %d values differ, largest |difference| %.3g)" % (
                            int(np.count_nonzero(d)), x.size, float(np.nanmax(np.abs(x - y))))
                    diffs.append("%s: values differ%s" % (p, where))

    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        walk(fa, fb, "/")
    return diffs


def _text(v):
    return v.decode(errors="replace") if isinstance(v, bytes) else str(v)


def _same_bits(x, y):
    x, y = np.asarray(x), np.asarray(y)
    if x.dtype.kind == "O" or y.dtype.kind == "O":
        return x.shape == y.shape and all(u == v for u, v in zip(x.ravel(), y.ravel()))
    return x.shape == y.shape and x.tobytes() == y.tobytes()


def compare(base, new):
    n_files, problems = 0, []
    for root in ["cases", "logs"]:
        ra, rb = os.path.join(base, root), os.path.join(new, root)
        fa = {os.path.relpath(os.path.join(d, f), ra) for d, _, fs in os.walk(ra) for f in fs}
        fb = {os.path.relpath(os.path.join(d, f), rb) for d, _, fs in os.walk(rb) for f in fs}
        for f in sorted(fa ^ fb):
            problems.append("%s/%s: only in %s" % (root, f, "base" if f in fa else "new"))
        for f in sorted(fa & fb):
            n_files += 1
            pa, pb = os.path.join(ra, f), os.path.join(rb, f)
            if f.endswith(".h5"):
                problems += ["%s/%s %s" % (root, f, d) for d in _h5_differences(pa, pb)]
            elif not filecmp.cmp(pa, pb, shallow=False):
                problems.append("%s/%s: bytes differ" % (root, f))
    for p in problems:
        print("DIFFERENT " + p)
    print("%d files compared (%s vs %s): %s" % (n_files, base, new,
                                                "%d differences" % len(problems) if problems else "identical"))
    return 1 if problems else 0


def main(argv):
    if len(argv) >= 3 and argv[0] == "run":
        run(argv[1], argv[2], argv[3:])
        return 0
    if len(argv) == 3 and argv[0] == "compare":
        return compare(argv[1], argv[2])
    if len(argv) == 4 and argv[0] == "check":
        run(argv[1], argv[3])
        return compare(argv[2], argv[3])
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
