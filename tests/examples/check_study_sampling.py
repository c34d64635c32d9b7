"""The sampling study's pieces against references nobody here wrote, and its errors:

  check_study_sampling.py FLEXCOMP_STUDY EXAMPLES_DIR WORK_DIR BUILD_DIR

- distributions: inverse CDFs against table values (standard normal 97.5 %
  quantile 1.959963984540054, Abramowitz & Stegun 26.2), the lognormal median
  e^mu, truncation symmetric about the mean;
- designs: a Latin hypercube and a Sobol' design of 16 points put one point in
  each of the 16 strata of every coordinate; the same seed gives the same bits;
- Spearman's rank correlation: the textbook example (IQ against hours of TV,
  rho = -29/165; Wikipedia "Spearman's rank correlation coefficient") and,
  with ties, scipy.stats.spearmanr (an independent implementation);
- metrics on the pendulum latched at the bottom (the rod released from
  horizontal, its hinge locked when it hangs): latch time against the closed
  form t = (sqrt(pi)/2) Gamma(1/4)/Gamma(3/4) / sqrt(k), k = m g L / I_hinge,
  latch rate sqrt(k), energy dissipated by the lock m g L/2 (all the kinetic
  energy), the peak hinge reaction against the rod's closed form at the
  recorded angles; the same pendulum on a stop (limits) with restitution;
- minimum distance and failure-index location read from a synthetic results
  file (their datasets as docs/file-formats.md defines them);
- located errors: an unknown path (file, line, did-you-mean), impossible
  distribution parameters; a sample that makes the scene invalid (negative
  stiffness) is a rejected case with mbs-run's message, and the study goes on;
  a case stopped by --case-timeout is failed with the run's own status;
- body samples on the hinged panel: fe-prep builds one body file per distinct
  body YAML (a ply angle drawn from two values: two files for six cases), the
  90-degree one equal to the example's own panel (same frequencies), and the
  scaled spring torque table scales the latch rate as energy says it must.
"""
import copy
import csv
import importlib.machinery
import importlib.util
import math
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from example_checks import check, finish  # noqa: E402

study_path, examples, work, build = (os.path.abspath(x) for x in sys.argv[1:5])
example = os.path.join(examples, "pendulum")
loader = importlib.machinery.SourceFileLoader("flexcomp_study", study_path)
spec = importlib.util.spec_from_loader("flexcomp_study", loader)
fs = importlib.util.module_from_spec(spec)
loader.exec_module(fs)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

# ---- distributions
d = fs.parse_dist("normal(0, 1)", "t")
check(abs(d.ppf(0.975) - 1.959963984540054) < 1e-12, f"normal 97.5 % quantile {d.ppf(0.975)!r}")
d = fs.parse_dist("lognormal(0.5, 0.2)", "t")
check(abs(d.ppf(0.5) - math.exp(0.5)) < 1e-14, "lognormal median e^mu")
d = fs.parse_dist("truncated(normal(10, 2), 8, 12)", "t")
check(abs(d.ppf(0.5) - 10) < 1e-12 and abs(d.ppf(0.25) + d.ppf(0.75) - 20) < 1e-9
      and 8 <= d.ppf(1e-15) and d.ppf(1 - 1e-15) <= 12, "truncated normal symmetric and inside its bounds")
d = fs.parse_dist("uniform(-1, 3)", "t")
check(d.ppf(0.25) == 0.0, "uniform quantile")
for bad, why in (("normal(1, -2)", "sigma must be positive"), ("uniform(3, 1)", "a must be below b"),
                 ("truncated(normal(0, 1), 2, 1)", "lo must be below hi"),
                 ("truncated(normal(0, 1), 50, 60)", "no probability"), ("lognormel(0, 1)", "did you mean 'lognormal'"),
                 ("normal(0)", "takes 2 parameters")):
    try:
        fs.parse_dist(bad, "--sample x")
        check(False, f"{bad} refused")
    except fs.StudyError as e:
        check(why in str(e), f"{bad}: {e}")

# ---- designs
for design in ("lhs", "sobol"):
    u = fs.design_points(design, 16, 3, 7)
    strata = [sorted((u[:, j] * 16).astype(int)) for j in range(3)]
    check(all(s == list(range(16)) for s in strata), f"{design}: one point per stratum in every coordinate")
    check(np.array_equal(u, fs.design_points(design, 16, 3, 7)), f"{design}: same seed, same bits")
    check(not np.array_equal(u, fs.design_points(design, 16, 3, 8)), f"{design}: another seed, other points")

for design in ("random", "sobol"):
    check(np.array_equal(fs.design_points(design, 8, 3, 5), fs.design_points(design, 16, 3, 5)[:8]),
          f"{design}: more samples keep the first cases' points (a resumed study only runs the new ones)")

# ---- Spearman
iq = [106, 100, 86, 101, 99, 103, 97, 113, 112, 110]
tv = [7, 27, 2, 50, 28, 29, 20, 12, 6, 17]
check(abs(fs.spearman(iq, tv) - (-29 / 165)) < 1e-14, f"Spearman textbook example {fs.spearman(iq, tv)!r}")
try:
    from scipy.stats import spearmanr
    x = [1, 2, 2, 3, 5, 5, 5, 8, 9, 9]
    y = [3, 1, 4, 1, 5, 9, 2, 6, 5, 3]
    check(abs(fs.spearman(x, y) - spearmanr(x, y)[0]) < 1e-12, "Spearman with ties equals scipy's")
except ImportError:
    print("note: scipy absent, the ties comparison is not run")

# ---- metrics on the latched pendulum
with open(os.path.join(example, "pendulum.yaml")) as f:
    base = yaml.safe_load(f)
m, L, dia, g = 1.0, 1.0, 0.02, 9.81
I_hinge = m * (L * L / 12 + dia * dia / 16) + m * (L / 2) ** 2   # solid rod: m (L^2/12 + r^2/4), r = dia/2
k = m * g * L / I_hinge


def pendulum(latch):
    s = copy.deepcopy(base)
    s["forces"] = [f for f in s["forces"] if f.get("type") == "gravity"]
    s["simulation"] = {"t_end": 1.0, "output_step": 0.005, "rtol": 1e-10}
    if latch == "lock":
        s["events"] = [{"joint": "hinge", "angle": math.pi / 2, "direction": "rising", "lock": ["hinge"]}]
    else:
        s.pop("events")
        s["joints"][0]["limits"] = {"max": math.pi / 2, "restitution": 0.5}
    return s


mbs_run = os.path.join(build, "mbs-run", "mbs-run")
t_closed = math.sqrt(math.pi) / 2 * math.gamma(0.25) / math.gamma(0.75) / math.sqrt(k)
for latch in ("lock", "stop"):
    s = pendulum(latch)
    path = os.path.join(work, f"pendulum-{latch}.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(s, f)
    res = os.path.join(work, f"pendulum-{latch}.h5")
    subprocess.run([mbs_run, path, "-o", res, "-q"], check=True, stdout=subprocess.DEVNULL)
    names = fs.metric_names(s)
    check({"latch_time:hinge", "latch_rate:hinge", "overshoot:hinge", "peak_reaction_force:hinge",
           "energy_dissipated"} <= set(names), f"{latch}: the scene's metrics {names}")
    mt = fs.compute_metrics(res, s, names)
    # The event and the stop are located to machine precision in time (docs/mbs-run.md), the
    # run at rtol 1e-10: 1e-7 relative leaves room for the tolerance's accumulated error.
    check(abs(mt["latch_time:hinge"] / t_closed - 1) < 1e-7,
          f"{latch}: latch time {mt['latch_time:hinge']!r} s, closed form {t_closed!r} s")
    if latch == "lock":
        # The rate at a lock comes from the angle rows: the derivative of the cubic through the
        # last four rows (h = 0.005 s) extrapolated to the latch; its error is at most
        # max|theta''''| / 24 * |w'(t_latch)| with w the nodes' product, |w'| <= 4 (5h)^3 and
        # theta'''' = -(k/2)(cos(theta) theta'^2 + sin(theta) theta''), |.| <= k^2 near the bottom.
        bound = k * k / 24 * 4 * (5 * 0.005) ** 3
        dissipated = m * g * L / 2
    else:
        bound = 1e-7 * math.sqrt(k)     # the stop's own record of the rate before impact
        dissipated = (1 - 0.5 ** 2) * m * g * L / 2
    check(abs(mt["latch_rate:hinge"] - math.sqrt(k)) < bound,
          f"{latch}: latch rate {mt['latch_rate:hinge']!r} rad/s, closed form {math.sqrt(k)!r} (bound {bound:.1e})")
    if latch == "lock":
        check(abs(mt["energy_dissipated"] / dissipated - 1) < 1e-6,
              f"lock: energy dissipated {mt['energy_dissipated']!r} J, m g L/2 = {dissipated!r} J")
        check(abs(mt["overshoot:hinge"]) < 1e-9, f"lock: no overshoot past the latch ({mt['overshoot:hinge']:.2e} rad)")
    else:
        # The first impact's loss (1 - e^2) of the kinetic energy m g L / 2; later bounces add theirs.
        with h5py.File(res) as f:
            first = float(f["joints/hinge/limit_impacts"][0, 4])
        check(abs(first / dissipated - 1) < 1e-6, f"stop: first impact dissipates {first!r} J, (1-e^2) m g L/2")
        check(mt["energy_dissipated"] >= first * (1 - 1e-9), "stop: dissipated energy at least the first impact's")
        check(mt["overshoot:hinge"] < 1e-8, f"stop: the angle stays behind the stop ({mt['overshoot:hinge']:.2e} rad)")
    # Peak hinge reaction before the latch: the rod's closed form at each recorded angle
    # (radial m w^2 L/2 + m g sin, tangential m g cos - m alpha L/2).
    with h5py.File(res) as f:
        th = f["joints/hinge/angle"][:]
        tt = f["time"][:]
    before = (tt < mt["latch_time:hinge"]) & (th > 0)
    th = th[before]
    w2, al = k * np.sin(th), k / 2 * np.cos(th)
    closed = np.hypot(m * w2 * L / 2 + m * g * np.sin(th), m * g * np.cos(th) - m * al * L / 2).max()
    check(mt["peak_reaction_force:hinge"] >= closed * (1 - 1e-6),
          f"{latch}: peak reaction {mt['peak_reaction_force:hinge']:.6f} N, closed form before the latch {closed:.6f} N")
    if latch == "lock":
        # After the lock the rod hangs still: m g; the peak is the swing's, reached in the last row
        # before the latch (2.5 m g at the bottom itself).
        check(abs(mt["peak_reaction_force:hinge"] / closed - 1) < 1e-6, "lock: the peak reaction is the swing's")
    # mbs-run's own summary carries the same metrics as root and joint attributes, folded over
    # the same output rows: equal to the study's to rounding (the attributes are the run's
    # doubles, the study's the datasets' copies of them).
    with h5py.File(res) as f:
        own = {"energy_dissipated": float(f.attrs["energy_dissipated"]),
               "overshoot:hinge": float(f["joints/hinge/angle"].attrs["overshoot"]),
               "max_angle:hinge": float(f["joints/hinge/angle"].attrs["max"]),
               "min_angle:hinge": float(f["joints/hinge/angle"].attrs["min"]),
               "peak_reaction_force:hinge": float(f["joints/hinge/reaction_force"].attrs["peak"])}
        own_max = (float(f.attrs["overshoot_max"]), str(fs.text(f.attrs["overshoot_max_joint"])))
    theirs = fs.compute_metrics(res, s, list(own))
    for key, v in own.items():
        check(abs(v - theirs[key]) <= 1e-14 * max(1.0, abs(v)),
              f"{latch}: mbs-run's {key} {v!r}, the study's {theirs[key]!r}")
    check(own_max == (own["overshoot:hinge"], "hinge"), f"{latch}: overshoot_max {own_max}")

# ---- distances and failure index from a synthetic results file
syn = os.path.join(work, "synthetic.h5")
with h5py.File(syn, "w") as f:
    f["time"] = np.linspace(0, 1, 5)
    f["distances/a-b"] = [0.3, 0.2, 0.05, 0.1, 0.4]
    fi = np.zeros((3, 4))
    fi[2, 1] = 0.8
    f["bodies/p/failure_index_peak"] = fi
    f["bodies/q/failure_index"] = np.full((5, 2, 2), 0.1)
    f["energy/dissipated"] = [0, 1, 2, 3, 4.5]
    f.attrs["steps"] = 10
mt = fs.compute_metrics(syn, {}, ["min_distance:a-b", "peak_failure_index", "peak_failure_index:q", "energy_dissipated"])
check(mt["min_distance:a-b"] == 0.05 and mt["peak_failure_index"] == 0.8 and mt["peak_failure_index at"] == "p element 2 ply 1"
      and mt["peak_failure_index:q"] == 0.1 and mt["energy_dissipated"] == 4.5, f"synthetic results: {mt}")

# ---- the tool's located errors and a rejected case
shutil.copy(os.path.join(example, "pendulum.yaml"), work)
scene = os.path.join(work, "pendulum.yaml")


def tool(*args):
    return subprocess.run([sys.executable, study_path, scene, "--out", os.path.join(work, "s"), "--tools", build,
                           "--t-end", "0.8", *args], capture_output=True, text=True)


p = tool("--sample", "forces.cacth.stiffness=normal(200, 20)")
check(p.returncode != 0 and "pendulum.yaml:" in p.stderr and "did you mean 'catch'" in p.stderr,
      f"unknown path located: {p.stderr.strip()}")
p = tool("--sample", "forces.catch.stifness=normal(200, 20)")
check(p.returncode != 0 and "pendulum.yaml:16" in p.stderr and "did you mean 'stiffness'" in p.stderr,
      f"unknown key located at the entry's line: {p.stderr.strip()}")
p = tool("--sample", "forces.catch.stiffness=normal(200, -20)")
check(p.returncode != 0 and "sigma must be positive" in p.stderr, f"impossible parameters: {p.stderr.strip()}")
p = tool("--sample", "joints.hinge.bodies=normal(1, 1)")
check(p.returncode != 0 and "not a number" in p.stderr, f"not a number: {p.stderr.strip()}")
# Found by the format fuzzer (docs/robustness.md, "Format fuzzing", seed 2811): a
# negative seed and a lognormal whose draws overflow were Python tracebacks, 1e8 samples
# ran for minutes planning; each is now a refusal naming the option, with no plan left.
for args, want in ((("--seed", "-1"), "--seed -1: give a non-negative integer"),
                   (("--sample", "forces.catch.stiffness=lognormal(800, 1)"), "overflows a double"),
                   (("--sample", "forces.catch.stiffness=normal(1e308, 1e308)"), "draws would overflow"),
                   (("--samples", "100000000"), "at most 1,000,000 cases")):
    a = args if args[0] == "--sample" else ("--sample", "forces.catch.stiffness=normal(200, 20)") + args
    p = tool(*a, "--emit-makefile", os.path.join(work, "mk"))
    check(p.returncode == 1 and want in p.stderr and "Traceback" not in p.stderr
          and not os.path.exists(os.path.join(work, "s", "study.json")), f"{args} refused: {p.stderr.strip()[-300:]}")
p = tool("--sample", "forces.catch.stiffness=normal(100, 120)", "--samples", "8", "--seed", "3",
         "--executor", "serial", "--metric", "max_angle:*", "--metric", "energy_dissipated")
check(p.returncode == 0, f"the study goes on past rejected cases: {p.stderr.strip()[-400:]}")
with open(os.path.join(work, "s", "cases.csv")) as f:
    rows = list(csv.DictReader(f))
neg = [r for r in rows if float(r["forces.catch.stiffness"]) < 0]
check(len(rows) == 8 and neg and all(r["status"] == "rejected" and "stiffness" in r["message"] for r in neg),
      f"negative stiffness rejected with mbs-run's message: {[(r['forces.catch.stiffness'], r['status'], r['message']) for r in rows]}")
check(all(r["status"] == "completed" for r in rows if float(r["forces.catch.stiffness"]) >= 0), "the others completed")
summary = open(os.path.join(work, "s", "summary.md")).read()
check(f"{len(neg)} rejected" in summary, "the summary counts the rejected cases")

# A case that runs too long is stopped (--case-timeout: SIGTERM) and listed as failed with
# the status mbs-run wrote; the rows it ran are kept and measured.
p = subprocess.run([sys.executable, study_path, scene, "--out", os.path.join(work, "slow"), "--tools", build,
                    "--t-end", "1e6", "--case-timeout", "1", "--sample", "forces.catch.damping=uniform(4, 6)",
                    "--samples", "2", "--executor", "local", "--metric", "max_angle:hinge"], capture_output=True, text=True)
with open(os.path.join(work, "slow", "cases.csv")) as f:
    slow = list(csv.DictReader(f))
check(p.returncode == 0 and all(r["status"] == "failed" and r["message"] == "interrupted by SIGTERM"
                                and float(r["max_angle:hinge"]) > 1.5 for r in slow),
      f"--case-timeout: cases stopped, failed, their rows measured: {[(r['status'], r['message']) for r in slow]}")
check("interrupted by SIGTERM" in open(os.path.join(work, "slow", "summary.md")).read(), "the summary lists why")

# ---- body samples: the hinged panel, a ply angle of two values and the spring torque scaled
hp = os.path.join(work, "hinged-panel")
shutil.copytree(os.path.join(examples, "hinged-panel"), hp, ignore=shutil.ignore_patterns("out"))
fe_prep = os.path.join(build, "fe-prep", "fe-prep")
os.makedirs(os.path.join(hp, "out"))
subprocess.run([fe_prep, "panel.yaml", "-o", "out/panel.h5", "-q"], cwd=hp, check=True, stdout=subprocess.DEVNULL)
out = os.path.join(hp, "mc")
p = subprocess.run([sys.executable, study_path, "scene.yaml", "--out", out, "--tools", build, "--t-end", "1.6",
                    "--body-yaml", "panel=panel.yaml", "--sample", "body:panel:laminates.crossply.1.angle_deg=choice(80, 90)",
                    "--sample", "forces.spring.torque.value*=uniform(0.8, 1.2)", "--samples", "6", "--seed", "2",
                    "--executor", "local", "--metric", "latch_*", "--metric", "peak_reaction_*"],
                   cwd=hp, capture_output=True, text=True)
check(p.returncode == 0, "hinged-panel body study ran" + ("" if p.returncode == 0 else p.stderr[-600:]))
with open(os.path.join(out, "cases.csv")) as f:
    rows = list(csv.DictReader(f))
angles = {float(r["body:panel:laminates.crossply.1.angle_deg"]) for r in rows}
built = sorted(x for x in os.listdir(os.path.join(out, "bodies")) if x.endswith(".h5"))
check(len(rows) == 6 and len(angles) == 2 and len(built) == 2, f"one body file per distinct ply angle: {built}")
check(all(r["status"] == "completed" for r in rows), "every case completed")
files = {}
for r in rows:
    sc = yaml.safe_load(open(os.path.join(out, "cases", f"{int(r['case']):05d}", "scene.yaml")))
    files.setdefault(float(r["body:panel:laminates.crossply.1.angle_deg"]), set()).add(sc["bodies"][1]["flexible"]["file"])
check(all(len(v) == 1 for v in files.values()) and len(set().union(*files.values())) == 2, "cases of one angle share its file")
with h5py.File(os.path.join(hp, "out", "panel.h5")) as f0, h5py.File(next(iter(files[90.0]))) as f1:
    fa, fb = f0["modes/frequencies_hz"][:], f1["modes/frequencies_hz"][:]
check(np.array_equal(fa, fb), f"the 90-degree body has the example's frequencies {fa} Hz")
# A rigid panel latching after a spring torque scaled by s gains s times the work: the rate
# at the latch scales like sqrt(s) when the modes hold little energy (the 1 % damped 4 Hz
# panel holds a few per cent): the rank correlation of the scale with the rate is high.
sc = [float(r["forces.spring.torque.value*"]) for r in rows]
rate = [abs(float(r["latch_rate:hinge"])) for r in rows]
check(fs.spearman(sc, rate) > 0.8, f"latch rate rises with the spring torque (Spearman {fs.spearman(sc, rate):.2f})")
check(all(0.5 < float(r["latch_time:hinge"]) < 1.6 for r in rows), "every case latches")
finish()
