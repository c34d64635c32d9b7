"""The SAR antenna's lay-up 2 panels from Nastran decks against the YAML route
(check_sar_deck.py SAR_EXAMPLE_DIR WORK_DIR BUILD_DIR; docs/sar-antenna.md,
"The panels from Nastran decks").

In a copy of the example, with its own Makefile:
  1. the committed decks (bodies/panel{2,3}_layup2.bdf and _deck.yaml) are what
     make_decks.py writes from the YAML route's bodies today, byte for byte (a
     changed YAML panel or lay-up must be followed by `make decks`);
  2. the deck bodies equal the YAML bodies: same mesh, so every body-file
     quantity (frequencies, nodal and interface shapes, the inertia invariants,
     the strain modes) within 2 x 1e-10 / (the smallest relative gap between
     neighbouring eigenvalues) of its largest entry (3.0e-9 and 8.8e-9 for the
     hinge-gap panels). Nodes, masses and rigid inertia are the same numbers; the
     modes differ by the eigen-solver's convergence (fe-prep's tolerance 1e-10 on
     the residual, which bounds a shape's error by itself over the gap), measured
     1.1e-11 (frequencies) and 4.8e-11 (a rotary modal invariant) on the gap-free
     panels, 1.1e-10 and 2.1e-10 (modal invariants) on the hinge-gap panels;
  3. the lay-up 2 scene over its first T_END s (phase 1: actuator A unfolding
     panel 3 with the knee, panels vibrating) from each route: joint angles
     within the run's rtol (a state change of 1e-10 in the bodies moves the
     adaptive steps' error estimates by as much, so the two runs must agree far
     within the tolerance the integrator guarantees), energies within rtol of
     the largest energy. Over these 2 s nothing the run decides depends on
     measured CPU time (the `auto` policy's first integrator trial comes at
     the 10 s release), so the two runs take the same steps and differ only by
     the bodies' 5e-11: measured 3.6e-11 rad and 2.3e-11 of the largest energy,
     checked also against 1e-8 (200 times the bodies' difference, room for the
     dynamics' sensitivity over 2 s). The whole 30 s run is `make deck` and its
     figures are in docs/sar-antenna.md.
"""
import filecmp
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import yaml

from example_checks import check, finish

T_END = 2.0

src, work, build = (os.path.abspath(a) for a in sys.argv[1:4])
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
for name in ("Makefile", "sar-layup2.yaml", "make_decks.py", "compare_deck_run.py"):
    shutil.copy(os.path.join(src, name), work)
for sub in ("bodies", "sections"):
    shutil.copytree(os.path.join(src, sub), os.path.join(work, sub))
sys.path.insert(0, work)
import compare_deck_run  # noqa: E402  (the example's own comparison)

env = dict(os.environ, PATH=os.pathsep.join([f"{build}/section-prep", f"{build}/fe-prep", f"{build}/mbs-run",
                                             os.environ["PATH"]]))
panels = ["panel2_layup2", "panel3_layup2"]
trusses = [f"out/bodies/truss_B{k}_im6.h5" for k in range(4, 13)]
targets = [f"out/bodies/{p}.h5" for p in panels] + [f"out/bodies/{p}_deck.h5" for p in panels] + trusses
subprocess.run(["make", "-C", work, "--no-print-directory", f"BIN={build}"] + targets, env=env, check=True,
               stdout=subprocess.DEVNULL)

# 1. The committed decks are make_decks.py's output for today's YAML bodies.
os.makedirs(os.path.join(work, "regen"))
for p in panels:
    subprocess.run([sys.executable, os.path.join(work, "make_decks.py"), "deck", os.path.join(work, "bodies", p + ".yaml"),
                    os.path.join(work, "out", "bodies", p + ".h5"), os.path.join(work, "regen", p + ".bdf"),
                    os.path.join(work, "regen", p + "_deck.yaml")], check=True)
    for name in (p + ".bdf", p + "_deck.yaml"):
        check(filecmp.cmp(os.path.join(work, "regen", name), os.path.join(src, "bodies", name), shallow=False),
              f"bodies/{name} is what make_decks.py writes from the YAML route (else: make decks)")

# 2. The two routes' bodies.
for p in panels:
    d = compare_deck_run.body_differences(os.path.join(work, "out", "bodies", p + ".h5"),
                                          os.path.join(work, "out", "bodies", p + "_deck.h5"))
    key, worst = max(d.items(), key=lambda kv: kv[1])
    # The bound: the two routes number the same mesh's DOFs differently, so their eigen-solves converge
    # differently within fe-prep's tolerance, 1e-10 on the relative residual. A shape's error is then at
    # most that over the eigenvalue's relative gap to its neighbour (Davis-Kahan), twice it for the
    # invariants that are quadratic in the shapes.
    with h5py.File(os.path.join(work, "out", "bodies", p + ".h5"), "r") as f:
        lam = f["modes/eigenvalues"][()]
    lam = np.sort(lam[lam > 1e-6 * lam.max()])
    bound = 2e-10 / float(np.min(np.diff(lam) / lam[1:]))
    check(worst <= bound, f"{p}: deck body = YAML body, largest difference {worst:.2e} ({key}), "
                          f"bound {bound:.1e} (2 x 1e-10 / the smallest relative eigenvalue gap)")

# 3. The lay-up 2 scene's first T_END s from each route.
scene = yaml.safe_load(open(os.path.join(work, "sar-layup2.yaml")))
scene["simulation"]["t_end"] = T_END
scene.pop("outputs", None)
short = os.path.join(work, "sar-layup2-short.yaml")
with open(short, "w") as f:
    yaml.safe_dump(scene, f, default_flow_style=None, sort_keys=False)
short_deck = os.path.join(work, "sar-layup2-short-deck.yaml")
subprocess.run([sys.executable, os.path.join(work, "make_decks.py"), "scene", short, "-o", short_deck], check=True)
results = {}
for name, path in (("yaml", short), ("deck", short_deck)):
    results[name] = os.path.join(work, f"{name}.h5")
    subprocess.run(["mbs-run", path, "-o", results[name], "-q"], env=env, check=True, cwd=work,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
d = compare_deck_run.run_differences(results["yaml"], results["deck"])
rtol = d.pop("rtol")
for key, v in d.items():
    print(f"  {key:50s} {v if isinstance(v, tuple) else f'{v:.3e}'}")
    if key.startswith("joints") or key.startswith("energy"):
        check(v <= rtol, f"{key}: the deck run differs by {v:.2e}, bound the run's rtol {rtol:g}")
        check(v <= 1e-8, f"{key}: {v:.2e}, bound 1e-8 (same steps, bodies 5e-11 apart)")
steps = d["steps (yaml, deck)"]
check(steps[0] == steps[1], f"the same steps on both routes: {steps}")
finish()
