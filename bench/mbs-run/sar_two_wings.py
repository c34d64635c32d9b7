#!/usr/bin/python3
"""The full SAR antenna, both wings: 23 moving-and-fixed bodies, against one wing (docs/benchmarks.md,
"Many flexible bodies").

The example's scenes (examples/sar-antenna/sar-*.yaml) model one wing of the antenna: the satellite
with the central panel (B1, fixed) and eleven moving bodies (two panels, nine trusses). The
second wing is the same mechanism on the satellite's other side: every body of the first wing turned
by 180 degrees about the satellite's y axis (the hinge-line direction), so the two wings are
point-symmetric through that axis, stow on either face of the central panel and deploy to either
side. The second wing's joints attach to a copy of B1 turned the same way (`W2_B1`, fixed, at the
same place: a fixed body adds no unknowns), so every joint point, axis, contact plane and initial
angle of the wing is the first wing's, in its own bodies' frames; names get the prefix `W2_`. The
event at the phase switch acts on both wings, each latch event is repeated for the second wing,
and every output (distances, margins, stresses) is repeated.

Both wings move independently (the satellite is held), so the two-wing run must reproduce the
one-wing run's motion in each wing (checked: the largest difference of the joint angles of the
two wings' corresponding joints is printed) at twice the unknowns; its CPU per simulated second
against the one wing's gives the cost's exponent in the number of moving bodies (11 -> 22).

Usage: bench/mbs-run/sar_two_wings.py BUILD_DIR [--scene examples/sar-antenna/sar-layup2.yaml]
                                      [--t-end 30] [--write-only OUT.yaml] [--keep]
                                      [--integrator dopri5]
The scene's bodies (out/bodies/ of examples/sar-antenna, `make bodies`) must exist; the scenes are
written and run beside the example's scene, so its relative body paths hold.
"""
import argparse
import copy
import math
import os
import subprocess
import sys

import h5py
import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(os.path.dirname(HERE))
PREFIX = "W2_"
TURN = np.array([0.0, 0.0, 1.0, 0.0])   # unit quaternion (w, x, y, z) of 180 degrees about y


def quat_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])


def turned(v):
    """A point or vector in the satellite frame, turned 180 degrees about y."""
    return [-float(v[0]), float(v[1]), -float(v[2])]


def rename(name):
    return PREFIX + name


def rename_all(names):
    return [rename(n) for n in names]


def second_wing(scene):
    """The scene with the second wing added (the first wing's bodies, joints, forces and outputs repeated)."""
    out = copy.deepcopy(scene)
    bodies = scene["bodies"]
    for b in bodies:
        c = copy.deepcopy(b)
        c["name"] = rename(b["name"])
        c["position"] = turned(b.get("position", [0.0, 0.0, 0.0]))
        c["orientation"] = [float(x) for x in quat_mul(TURN, np.array(b.get("orientation", [1.0, 0.0, 0.0, 0.0])))]
        out["bodies"].append(c)
    for j in scene["joints"]:
        c = copy.deepcopy(j)
        c["name"] = rename(j["name"])
        c["bodies"] = rename_all(j["bodies"])
        out["joints"].append(c)
    for f in scene.get("forces", []):
        if f.get("type") == "gravity":
            raise SystemExit("sar_two_wings.py: the scene has gravity, which the turned wing would feel turned; "
                             "the SAR deploys in orbit (no gravity)")
        c = copy.deepcopy(f)
        c["name"] = rename(f["name"])
        if "joint" in c:
            c["joint"] = rename(c["joint"])
        if "bodies" in c:
            c["bodies"] = rename_all(c["bodies"])
        out["forces"].append(c)
    events = []
    for e in scene.get("events", []):
        c = copy.deepcopy(e)
        if "time" in e:   # the phase switch: both wings at once
            for key in ("lock", "enable", "release", "disable", "unlock"):
                if key in c:
                    c[key] = list(e[key]) + rename_all(e[key])
            events.append(c)
        else:             # a latch: one per wing
            events.append(c)
            d = copy.deepcopy(e)
            d["joint"] = rename(e["joint"])
            for key in ("lock", "enable", "release", "disable", "unlock"):
                if key in d:
                    d[key] = rename_all(e[key])
            events.append(d)
    out["events"] = events
    outputs = out.get("outputs", {})
    o = scene.get("outputs", {})
    if "distances" in o:
        outputs["distances"] = list(o["distances"]) + [rename_all(p) for p in o["distances"]]
    if "stresses" in o:
        outputs["stresses"] = list(o["stresses"]) + rename_all(o["stresses"])
    if "margins" in o:
        m = copy.deepcopy(o["margins"])
        beams = []
        for b in o["margins"].get("beams", []):
            c = copy.deepcopy(b)
            c["body"] = rename(b["body"])
            if "joints" in c:
                c["joints"] = rename_all(b["joints"])
            beams.append(c)
        m["beams"] = list(o["margins"].get("beams", [])) + beams
        if "joints" in m:
            m["joints"] = list(o["margins"]["joints"]) + rename_all(o["margins"]["joints"])
        outputs["margins"] = m
    return out


def run(build, scene_path, result):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    rss_file = result + ".rss"
    p = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", rss_file, os.path.join(build, "mbs-run", "mbs-run"),
                        os.path.basename(scene_path), "-o", result, "-q"], cwd=os.path.dirname(scene_path),
                       capture_output=True, text=True, env=env)
    if p.returncode != 0 or not os.path.exists(result):
        sys.exit(f"mbs-run failed on {scene_path}: {p.stderr.strip()[-400:]}")
    with open(rss_file) as f:
        rss_mb = int(f.read().split()[-1]) / 1024.0
    os.remove(rss_file)
    with h5py.File(result) as f:
        a = f.attrs
        return {"cpu": float(a["cpu_seconds"]), "steps": int(a["steps"]), "evals": int(a["rhs_evaluations"]),
                "t": float(a["t_reached"]), "rss": rss_mb, "integrator": text(a["integrator"]),
                "status": text(a["status"])}


def text(attr):
    return attr.decode() if isinstance(attr, bytes) else str(attr)


def joint_angles(result):
    """The results file's joint angles by joint name (docs/file-formats.md: /joints/NAME/angle)."""
    with h5py.File(result) as f:
        return {n: np.asarray(g["angle"]) for n, g in f["joints"].items() if "angle" in g}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("--scene", default=os.path.join(SRC, "examples", "sar-antenna", "sar-layup2.yaml"))
    ap.add_argument("--t-end", type=float)
    ap.add_argument("--write-only")
    ap.add_argument("--keep", action="store_true", help="keep the two scenes and their results files")
    ap.add_argument("--integrator", help="the same integrator for both runs (default: the scene's)")
    a = ap.parse_args()
    with open(a.scene) as f:
        scene = yaml.safe_load(f)
    if a.t_end:
        scene["simulation"]["t_end"] = a.t_end
    if a.integrator:
        scene["simulation"]["integrator"] = a.integrator
    two = second_wing(scene)
    if a.write_only:
        with open(a.write_only, "w") as f:
            yaml.safe_dump(two, f, sort_keys=False)
        return
    base = os.path.splitext(os.path.abspath(a.scene))[0]
    one_path, two_path = base + "-bench-one-wing.yaml", base + "-bench-two-wings.yaml"
    for path, s in ((one_path, scene), (two_path, two)):
        with open(path, "w") as f:
            yaml.safe_dump(s, f, sort_keys=False)
    try:
        rows = []
        for label, path in (("one wing", one_path), ("two wings", two_path)):
            res = os.path.splitext(path)[0] + ".h5"
            r = run(os.path.abspath(a.build), path, res)
            moving = sum(1 for b in yaml.safe_load(open(path))["bodies"] if not b.get("fixed"))
            rows.append((label, moving, r, res))
        print("| model | moving bodies | CPU s | steps | rhs evals | CPU s per simulated s | us per evaluation | "
              "peak RSS MB | integrators | status |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for label, moving, r, _ in rows:
            print(f"| {label} | {moving} | {r['cpu']:.1f} | {r['steps']} | {r['evals']} | {r['cpu'] / r['t']:.3g} | "
                  f"{1e6 * r['cpu'] / r['evals']:.0f} | {r['rss']:.0f} | {r['integrator']} | {r['status']} |")
        (_, n1, r1, _), (_, n2, r2, res2) = rows
        expo = math.log((r2["cpu"] / r2["t"]) / (r1["cpu"] / r1["t"])) / math.log(n2 / n1)
        per_eval = math.log((r2["cpu"] / r2["evals"]) / (r1["cpu"] / r1["evals"])) / math.log(n2 / n1)
        print(f"\nCPU per simulated second ~ N^{expo:.2f}, per evaluation ~ N^{per_eval:.2f} "
              f"(moving bodies {n1} -> {n2})")
        ang = joint_angles(res2)
        worst = max((float(np.max(np.abs(ang[n] - ang[rename(n)]))), n) for n in ang if rename(n) in ang)
        print(f"largest difference between the wings' joint angles: {worst[0]:.3g} rad ({worst[1]})")
    finally:
        for path in (one_path, two_path) if not a.keep else ():
            for p in (path, os.path.splitext(path)[0] + ".h5"):
                if os.path.exists(p):
                    os.remove(p)


if __name__ == "__main__":
    main()
