#!/usr/bin/python3
"""The sampling study's own cost per case against the runs it drives (docs/benchmarks.md,
"Sampling studies"):

  bench_study_overhead.py BUILD_DIR [N=1000] [JOBS=2] [WORK=/tmp/flexcomp-study-bench]

Runs N cases of the pendulum example (examples/pendulum, t_end 3 s; the catch spring's
stiffness and damping and the rod's mass sampled) with --executor local, then reports
- CPU of the study's own process (planning, writing each case's scene, waiting,
  reading each results file for the metrics, aggregation), per case, against the
  CPU of mbs-run (and of the process start) in the children, per case;
- micro-timings of the per-case steps on one case: loading the scene and writing
  the case's YAML, computing every metric from the results file (HDF5), and the
  aggregation (cases.csv, summary.md, histograms) per case;
- wall time (inflated on a loaded machine: CPU is the comparable figure).
"""
import importlib.machinery
import importlib.util
import os
import resource
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, "..", ".."))
build = os.path.abspath(sys.argv[1])
n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
jobs = int(sys.argv[3]) if len(sys.argv) > 3 else 2
work = sys.argv[4] if len(sys.argv) > 4 else "/tmp/flexcomp-study-bench"
loader = importlib.machinery.SourceFileLoader("flexcomp_study", os.path.join(root, "tools", "flexcomp-study"))
spec = importlib.util.spec_from_loader("flexcomp_study", loader)
fs = importlib.util.module_from_spec(spec)
loader.exec_module(fs)

shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
shutil.copy(os.path.join(root, "examples", "pendulum", "pendulum.yaml"), work)
out = os.path.join(work, "study")


def cpu(who):
    r = resource.getrusage(who)
    return r.ru_utime + r.ru_stime


args = [os.path.join(work, "pendulum.yaml"), "--out", out, "--tools", build, "--samples", str(n), "--seed", "1",
        "--design", "lhs", "--sample", "forces.catch.stiffness=normal(200, 20)",
        "--sample", "forces.catch.damping=uniform(3, 7)", "--sample", "bodies.rod.rod.mass=normal(1, 0.02)"]
t0, s0, c0 = time.perf_counter(), cpu(resource.RUSAGE_SELF), cpu(resource.RUSAGE_CHILDREN)
ap_args = fs.argparse.Namespace(scene=args[0], out=out, tools=build, samples=n, seed=1, design="lhs",
                                sample=[x for x in args if "=" in x], metric=[], body_yaml=[], t_end=None, jobs=jobs)
fs.find_tools(ap_args, False)
plan = fs.plan_sampling(ap_args)
t1, s1 = time.perf_counter(), cpu(resource.RUSAGE_SELF)
fs.run_cases(out, n, "local", jobs, progress=False)
t2, s2, c2 = time.perf_counter(), cpu(resource.RUSAGE_SELF), cpu(resource.RUSAGE_CHILDREN)
rows, _ = fs.aggregate(out)
t3, s3 = time.perf_counter(), cpu(resource.RUSAGE_SELF)
done = sum(r["status"] == "completed" for r in rows)

# Per-case steps, on case 0, repeated for a stable CPU figure.
reps = 200
case = os.path.join(out, "cases", "00000")
scene = fs.load_yaml(plan["scene"])
u0 = cpu(resource.RUSAGE_SELF)
for _ in range(reps):   # what run_case does to the scene
    s = fs.load_yaml(plan["scene"])
    fs.set_in(s, plan["factors"][0]["keys"], 123.0)
    fs.write_atomic(os.path.join(work, "scene-bench.yaml"), fs.yaml.dump(s, Dumper=fs.DUMPER, sort_keys=False))
u1 = cpu(resource.RUSAGE_SELF)
for _ in range(reps):
    fs.compute_metrics(os.path.join(case, "results.h5"), scene, plan["metrics"])
u2 = cpu(resource.RUSAGE_SELF)

print(f"{n} pendulum cases (t_end 3 s), {jobs} threads: {done} completed")
print(f"  wall: plan {t1 - t0:.2f} s, cases {t2 - t1:.1f} s, aggregation {t3 - t2:.2f} s")
print(f"  CPU of the children (mbs-run and its start, fe-prep): {c2 - c0:.1f} s = {(c2 - c0) / n * 1e3:.1f} ms per case")
print(f"  CPU of the study's process: plan {s1 - s0:.2f} s, cases {s2 - s1:.1f} s = {(s2 - s1) / n * 1e3:.1f} ms per case, "
      f"aggregation {s3 - s2:.2f} s = {(s3 - s2) / n * 1e3:.2f} ms per case")
print(f"  per case, on one case: scene YAML read, changed and written {(u1 - u0) / reps * 1e3:.2f} ms CPU; "
      f"metrics from the results file (HDF5) {(u2 - u1) / reps * 1e3:.2f} ms CPU")
