#!/usr/bin/python3
"""Does the flexible SAR antenna (reconstruction v2) follow the same path after
the knee's minimum whatever the discretisation? ("robustness")

Runs phase 1 (0-10 s) of a scene (default sar-isotropic.yaml) varying one
factor at a time around the scene as committed: the integrator tolerance, the
number of panel modes, and the panel mesh (panel body files with 24 modes on the
scene's mesh and at `--triangles`, built with fe-prep). For each run it prints the knee's
minimum (time, angle), the impacts on the hinge-2/3 stop (time, rate before
and after), the R3 and H23 angles at 8 and 10 s, and the largest difference
of R3 from the committed scene's run over the whole phase.

  /usr/bin/python3 robustness.py --build ../../build [--scene sar-isotropic.yaml] [--triangles 200]

Needs the body files of `make bodies`; writes out/robustness/.
"""
import argparse
import os
import re
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def run(args, name, text):
    out = os.path.join(HERE, "out", "robustness")
    os.makedirs(out, exist_ok=True)
    scene = os.path.join(HERE, f".robustness-{name}.yaml")  # beside the original: relative body paths hold
    with open(scene, "w") as f:
        f.write(text)
    res = os.path.join(out, name + ".h5")
    try:
        subprocess.run([args.mbs_run, scene, "-o", res, "-q", "--t-end", "10"], check=True, cwd=HERE,
                       stdout=subprocess.DEVNULL)
    finally:
        os.remove(scene)
    with h5py.File(res, "r") as f:
        d = dict(t=f["time"][:], r3=f["joints/R3/angle"][:], h23=f["joints/H23/angle"][:],
                 imp=f["joints/H23/limit_impacts"][:], cpu=float(f.attrs["cpu_seconds"]),
                 status=f.attrs["status"])
    return d


def knee_min(d):
    r, t = d["r3"], d["t"]
    m = np.nonzero((r[1:-1] < r[:-2]) & (r[1:-1] <= r[2:]) & (r[1:-1] < 0.2))[0]
    if len(m) == 0:
        return np.nan, np.nan
    k = m[0] + 1
    return t[k], r[k]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(HERE, "..", "..", "build"))
    ap.add_argument("--scene", default="sar-isotropic.yaml")
    ap.add_argument("--triangles", type=int, default=200)
    args = ap.parse_args()
    args.build = os.path.abspath(args.build)
    args.mbs_run = os.path.join(args.build, "mbs-run", "mbs-run")
    fe_prep = os.path.join(args.build, "fe-prep", "fe-prep")
    base = open(os.path.join(HERE, args.scene)).read()
    rtol0 = float(re.search(r"rtol: ([0-9.eE+-]+)", base).group(1))
    variants = [("committed", base)]
    for rtol in (1e-3, 1e-5, 1e-6):
        if rtol != rtol0:
            variants.append((f"rtol {rtol:g}", re.sub(r"rtol: [0-9.eE+-]+", f"rtol: {rtol:g}", base)))
    variants.append(("8 panel modes", base.replace("modes: 14,", "modes: 8,")))
    # Panel body files with 24 modes: the scene's mesh, and a finer one (--triangles).
    panels = sorted(set(re.findall(r"out/bodies/(panel\d_\w+)\.h5", base)))

    def panel_files(tri):
        text = base.replace("modes: 14,", "modes: 24,")
        for p in panels:
            src = open(os.path.join(HERE, "bodies", p + ".yaml")).read()
            if tri:
                src = re.sub(r"mesh: \{triangles: \d+\}", f"mesh: {{triangles: {tri}}}", src)
            src = re.sub(r"modes: \d+", "modes: 24", src)
            tag = f"{p}_{tri or 'scene'}_24"
            ymlp = os.path.join(HERE, "bodies", f".{tag}.yaml")
            h5p = os.path.join(HERE, "out", "robustness", tag + ".h5")
            os.makedirs(os.path.dirname(h5p), exist_ok=True)
            with open(ymlp, "w") as f:
                f.write(src)
            try:
                if not os.path.exists(h5p):
                    subprocess.run([fe_prep, ymlp, "-o", h5p, "-q"], check=True, cwd=os.path.join(HERE, "bodies"),
                                   stdout=subprocess.DEVNULL)
            finally:
                os.remove(ymlp)
            text = text.replace(f"out/bodies/{p}.h5", f"out/robustness/{tag}.h5")
        return text

    variants.append(("24 panel modes", panel_files(None)))
    variants.append((f"{args.triangles} tri, 24 m", panel_files(args.triangles)))
    runs = [(name, run(args, re.sub(r"\W+", "_", name), text)) for name, text in variants]
    ref = runs[0][1]
    print(f"scene {args.scene}, phase 1; R3 difference from the committed scene's run over 0-10 s")
    print(f"{'run':<16} {'knee min [s]':>12} {'[rad]':>7} {'H23 impacts: t, rate-, rate+':>44} "
          f"{'R3(8 s)':>8} {'R3(10 s)':>9} {'H23(10 s)':>9} {'max|dR3|':>9} {'cpu':>6}")
    for name, d in runs:
        tk, rk = knee_min(d)
        imps = "; ".join(f"{i[0]:.3f} {i[1]:.3f} {i[2]:.3f}" for i in d["imp"][:2])
        if len(d["imp"]) > 2:
            imps += f" (+{len(d['imp']) - 2})"
        n = min(len(d["t"]), len(ref["t"]))
        dr = np.max(np.abs(d["r3"][:n] - ref["r3"][:n]))
        k8, k10 = np.argmin(np.abs(d["t"] - 8)), np.argmin(np.abs(d["t"] - 10))
        print(f"{name:<16} {tk:>12.3f} {rk:>7.4f} {imps:>44} {d['r3'][k8]:>8.4f} {d['r3'][k10]:>9.4f} "
              f"{d['h23'][k10]:>9.4f} {dr:>9.2e} {d['cpu']:>6.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
