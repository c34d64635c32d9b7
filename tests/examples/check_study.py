"""Runs flexcomp-study on the flexible-beam example's output folder (test
example_flexible_beam) and checks what it wrote:

  check_study.py FLEXCOMP_STUDY EXAMPLE_WORK_DIR BUILD_DIR

- every run of the one-factor-at-a-time sweep plus the reference is in
  summary.csv, the reference's own error is exactly zero;
- convergence under refinement: the beam refined from 10 to 40 elements comes
  closer to the reference (40 elements, most modes, tightest rtol);
- nothing is written outside --out (the example folder's files are unchanged).
"""
import csv
import os
import subprocess
import sys

from example_checks import check, finish

study, work, build = sys.argv[1:4]
out = os.path.join(work, "study")
before = {f: os.path.getmtime(os.path.join(work, f)) for f in os.listdir(work) if f != "study"}
cmd = [sys.executable, study, "scene.yaml", "--out", out, "--tools", build, "--jobs", "2", "--t-end", "0.3",
       "--vary", "rtol=1e-4,1e-7", "--vary", "modes:beam=2,6", "--vary", "mesh:beam=10,40",
       "--body-yaml", "beam=beam.yaml", "--channel", "bodies/beam/modal_coordinates"]
subprocess.run(cmd, cwd=work, check=True)

with open(os.path.join(out, "summary.csv")) as f:
    rows = {r["run"]: r for r in csv.DictReader(f)}
expected = {"base", "rtol=0.0001", "rtol=1e-07", "modes-beam=2", "modes-beam=6", "mesh-beam=10", "mesh-beam=40",
            "mesh-beam=40_modes-beam=6_rtol=1e-07"}
check(set(rows) == expected, f"runs {sorted(rows)}")
key = "bodies/beam/modal_coordinates max"
ref = rows.get("mesh-beam=40_modes-beam=6_rtol=1e-07", {})
check(ref.get(key) is not None and float(ref[key]) == 0.0, "the reference's error is zero")
if {"mesh-beam=10", "mesh-beam=40"} <= set(rows):
    e10, e40 = float(rows["mesh-beam=10"][key]), float(rows["mesh-beam=40"][key])
    check(e40 < e10, f"refinement converges: 10 elements {e10:.2e}, 40 elements {e40:.2e}")
check(all(os.path.exists(os.path.join(out, f)) for f in ("study.md", "summary.csv")), "study.md and summary.csv written")
after = {f: os.path.getmtime(os.path.join(work, f)) for f in os.listdir(work) if f != "study"}
check(after == before, "nothing written outside --out")
finish()
