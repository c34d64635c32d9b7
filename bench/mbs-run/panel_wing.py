#!/usr/bin/python3
"""A wing of N flexible composite panels in a chain (docs/benchmarks.md, "Many flexible bodies").

Each panel is the hinged-panel example's 1.0 x 0.6 m carbon/epoxy cross-ply plate (fe-prep,
pinned at its root edge for its modes), MODES modes, 1 % modal damping. Panel 1 hangs from the
fixed base on a hinge, panel k from panel k-1's free edge; every hinge carries a torsion spring
(5 N m/rad) with a damper (0.05 N m s/rad) and stops at +-1.2 rad (restitution 0.3), the
latches of a deployable. The wing starts flat and horizontal and falls under gravity.

For each N it runs mbs-run for T_END simulated seconds with each linear solver asked for and
prints one markdown row: N, solver, CPU s (mbs-run's own figure: on a shared machine CPU, not
wall time, is the figure), steps, right-hand-side evaluations, CPU per simulated second, CPU per
evaluation per body, status; then the exponent of a least-squares fit of log(CPU per simulated
second) on log N per solver (linear cost: 1).

With --stresses every panel is a stress body (`outputs: {stresses: [P1 .. PN]}`: ply stresses
and Tsai-Wu indices of every triangle at every output row, streamed to the results file) and
the panel's material carries the SAR lay-ups' IM6/SC1081 strengths; --triangles sets each
panel's mesh (the stress field's size) and --rows the output rows. Each row then also gives
mbs-run's peak resident memory (/usr/bin/time) and the results file's size: the memory budget
of a many-body stress run (docs/benchmarks.md, "Many flexible bodies").

Usage: bench/mbs-run/panel_wing.py BUILD_DIR [--n 2 4 8 16 32 64] [--modes 8] [--t-end 0.2]
                                   [--solvers auto schur sparse_schur sparse] [--rtol 1e-4]
                                   [--stresses] [--triangles 60] [--rows 20]
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(os.path.dirname(HERE))


def panel_yaml(modes, triangles=None, strengths=False):
    with open(os.path.join(SRC, "examples", "hinged-panel", "panel.yaml")) as f:
        spec = yaml.safe_load(f)
    if strengths:   # IM6/SC1081, as the SAR lay-ups (examples/sar-antenna/bodies)
        for m in spec["materials"].values():
            m["strength"] = {"Xt": 2.0e9, "Xc": 1.2e9, "Yt": 50e6, "Yc": 200e6, "S12": 80e6}
    b = spec["body"]
    if triangles:
        b["shell"]["mesh"] = {"triangles": triangles}
    b["interfaces"] = {"root_a": [-0.5, 0.3, 0.0], "root_b": [-0.5, -0.3, 0.0], "root": [-0.5, 0.0, 0.0],
                       "tip": [0.5, 0.0, 0.0]}
    b["reference"] = {"pin": ["root_a", "root_b"]}
    b["modes"] = modes
    return spec


def wing_scene(n, body_file, t_end, rtol, solver, stresses=False, rows=20):
    bodies = [{"name": "base", "rigid": {"mass": 10.0, "inertia": [[0.02, 0, 0], [0, 0.02, 0], [0, 0, 0.02]]},
               "fixed": True}]
    joints, forces = [], [{"name": "gravity", "type": "gravity", "g": [0.0, 0.0, -9.81]}]
    for k in range(n):
        name = f"P{k + 1}"
        bodies.append({"name": name, "flexible": {"file": body_file, "modes": "all", "damping_ratio": 0.01},
                       "position": [0.5 + k * 1.0, 0.0, 0.0]})
        parent, point = ("base", [0.0, 0.0, 0.0]) if k == 0 else (f"P{k}", "tip")
        joints.append({"name": f"H{k + 1}", "type": "revolute", "bodies": [parent, name], "points": [point, "root"],
                       "axes": [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
                       "limits": {"min": -1.2, "max": 1.2, "restitution": 0.3}})
        forces.append({"name": f"S{k + 1}", "type": "rotational_spring_damper", "joint": f"H{k + 1}", "damping": 0.05,
                       "torque": {"angle": [-1.0, 1.0], "value": [5.0, -5.0]}})
    scene = {"bodies": bodies, "joints": joints, "forces": forces,
             "simulation": {"t_end": t_end, "output_step": t_end / rows, "rtol": rtol, "linear_solver": solver}}
    if stresses:
        scene["outputs"] = {"stresses": [f"P{k + 1}" for k in range(n)]}
    return scene


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("--n", type=int, nargs="+", default=[2, 4, 8, 16, 32, 64])
    ap.add_argument("--modes", type=int, default=8)
    ap.add_argument("--t-end", type=float, default=0.2)
    ap.add_argument("--rtol", type=float, default=1e-4)
    ap.add_argument("--solvers", nargs="+", default=["auto"])
    ap.add_argument("--stresses", action="store_true")
    ap.add_argument("--triangles", type=int)
    ap.add_argument("--rows", type=int, default=20)
    a = ap.parse_args()
    a.build = os.path.abspath(a.build)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(work, "panel.yaml"), "w") as f:
            yaml.safe_dump(panel_yaml(a.modes, a.triangles, a.stresses), f)
        subprocess.run([os.path.join(a.build, "fe-prep", "fe-prep"), "panel.yaml", "-o", "panel.h5", "-q"], cwd=work,
                       check=True, env=env, stdout=subprocess.DEVNULL)
        print("| N | linear solver | CPU s | steps | rhs evals | CPU s per simulated s | us per eval per body | "
              "peak RSS MB | results MB | status |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        fits = {}
        for solver in a.solvers:
            for n in a.n:
                scene = os.path.join(work, f"wing{n}.yaml")
                with open(scene, "w") as f:
                    yaml.safe_dump(wing_scene(n, "panel.h5", a.t_end, a.rtol, solver, a.stresses, a.rows), f)
                res = os.path.join(work, f"wing{n}.h5")
                rss_file = os.path.join(work, "rss.txt")
                p = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", rss_file,
                                    os.path.join(a.build, "mbs-run", "mbs-run"), scene, "-o", res, "-q"], cwd=work,
                                   capture_output=True, text=True, env=env)
                if not os.path.exists(res):
                    print(f"| {n} | {solver} | | | | | | | | failed: {p.stderr.strip()[-200:]} |")
                    continue
                with open(rss_file) as f:
                    rss_mb = int(f.read().split()[-1]) / 1024.0
                file_mb = os.path.getsize(res) / 1e6
                with h5py.File(res) as f:
                    cpu, steps = float(f.attrs["cpu_seconds"]), int(f.attrs["steps"])
                    evals, status = int(f.attrs["rhs_evaluations"]), f.attrs["status"]
                    t = float(f.attrs["t_reached"])
                status = status.decode() if isinstance(status, bytes) else str(status)
                per_s = cpu / t if t > 0 else math.nan
                fits.setdefault(solver, []).append((n, per_s))
                print(f"| {n} | {solver} | {cpu:.3g} | {steps} | {evals} | {per_s:.3g} | "
                      f"{1e6 * cpu / max(evals, 1) / n:.3g} | {rss_mb:.0f} | {file_mb:.1f} | {status} |")
                sys.stdout.flush()
        for solver, pts in fits.items():
            if len(pts) >= 2:
                x, y = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
                print(f"\n{solver}: CPU per simulated second ~ N^{np.polyfit(x, y, 1)[0]:.2f} over N = "
                      f"{', '.join(str(p[0]) for p in pts)}")


if __name__ == "__main__":
    main()
