"""The same sampling study of the pendulum example (20 cases, t_end 0.8 s) run
serially, by mpi4py under `mpirun -n 2`, and through the emitted Makefile with
make -j2, gives the same cases.csv; a second run reuses every finished case;
the emitted Slurm scripts are checked and submitted to a private Slurm started
for the test on this machine (munged, slurmctld and slurmd with their own ports
and state, when Debian's slurmctld, slurmd, slurm-client and munge are
installed and the test runs as root); otherwise the test says why the
submission is skipped and runs each array task as Slurm would:

  check_study_executors.py FLEXCOMP_STUDY PENDULUM_EXAMPLE_DIR WORK_DIR BUILD_DIR

cases.csv is compared byte for byte except its `cpu_seconds` column: CPU time
is measured, not computed, and differs from run to run; every sampled input and
every metric must be identical to the bit (each case is one deterministic
mbs-run; the inputs come from the seed, written with repr's round trip).
"""
import csv
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from example_checks import check, finish  # noqa: E402

study, example, work, build = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
shutil.copy(os.path.join(example, "pendulum.yaml"), work)
scene = os.path.join(work, "pendulum.yaml")
samples = ["--sample", "forces.catch.stiffness=normal(200, 20)", "--sample", "forces.catch.damping=uniform(3, 7)",
           "--sample", "bodies.rod.rod.mass=truncated(lognormal(0, 0.1), 0.85, 1.15)",
           "--sample", "forces.gravity.g.2=normal(-9.81, 0.02)",
           "--samples", "20", "--seed", "11", "--design", "lhs", "--t-end", "0.8", "--tools", build]
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def table(out):
    with open(os.path.join(out, "cases.csv")) as f:
        rows = list(csv.reader(f))
    col = rows[0].index("cpu_seconds")
    return [r[:col] + r[col + 1:] for r in rows]


def run(cmd, what):
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    check(p.returncode == 0, f"{what} ran" + ("" if p.returncode == 0 else f": {p.stderr[-800:]}"))
    return p


serial = os.path.join(work, "serial")
run([sys.executable, study, scene, "--out", serial, "--executor", "serial", *samples], "serial")
ref = table(serial)
check(len(ref) == 21 and all(r[ref[0].index("status")] == "completed" for r in ref[1:]),
      f"20 cases completed ({len(ref) - 1} rows)")
check(len({r[1] for r in ref[1:]}) == 20, "20 distinct samples")

# Resumed: the finished cases are reused (their records untouched).
rec = os.path.join(serial, "cases", "00007", "case.json")
before = os.stat(rec).st_mtime_ns
run([sys.executable, study, scene, "--out", serial, "--executor", "serial", *samples], "serial again")
check(os.stat(rec).st_mtime_ns == before and table(serial) == ref, "a second run reuses the finished cases")

mpirun = shutil.which("mpirun")
if mpirun:
    out = os.path.join(work, "mpi")
    run([mpirun, "-n", "2", sys.executable, "-m", "mpi4py.futures", study, scene, "--out", out,
         "--executor", "mpi", *samples], "mpirun -n 2 python3 -m mpi4py.futures")
    check(table(out) == ref, "mpirun -n 2 (mpi4py.futures pool) gives the serial table")
    out = os.path.join(work, "mpi-plain")
    run([mpirun, "-n", "2", sys.executable, study, scene, "--out", out, "--executor", "mpi", *samples],
        "mpirun -n 2 flexcomp-study --executor mpi")
    check(table(out) == ref, "plain mpirun -n 2 (MPICommExecutor) gives the serial table")
    # An input error on rank 0 must release the other ranks, not leave them waiting.
    try:
        p = subprocess.run([mpirun, "-n", "2", sys.executable, study, scene, "--out", os.path.join(work, "mpi-bad"),
                            "--executor", "mpi", "--tools", build, "--sample", "forces.cach.stiffness=normal(1, 1)"],
                           capture_output=True, text=True, env=env, timeout=120)
        check(p.returncode != 0 and "did you mean 'catch'" in p.stderr, "a bad path under mpirun: the error, every rank ends")
    except subprocess.TimeoutExpired:
        check(False, "a bad path under mpirun: the ranks hung")
else:
    check(False, "mpirun not found (Debian openmpi-bin)")

out = os.path.join(work, "make")
mk = os.path.join(work, "make-study")
run([sys.executable, study, scene, "--out", out, "--emit-makefile", mk, *samples], "--emit-makefile")
check(not os.path.exists(os.path.join(out, "cases.csv")), "emitting the Makefile runs nothing")
run(["make", "-f", os.path.join(mk, "Makefile"), "-j2", "--no-print-directory"], "make -j2")
check(table(out) == ref, "the Makefile gives the serial table")
p = run(["make", "-f", os.path.join(mk, "Makefile"), "-q"], "make -q")
check(p.returncode == 0, "the Makefile's study is then up to date")

out = os.path.join(work, "slurm")
sl = os.path.join(work, "slurm-study")
run([sys.executable, study, scene, "--out", out, "--emit-slurm", sl, *samples], "--emit-slurm")
script = open(os.path.join(sl, "cases.sbatch")).read()
check(re.search(r"^#SBATCH --array=0-19\b", script, re.M) is not None, "the job array has one task per case")
for f in ("cases.sbatch", "aggregate.sbatch", "submit.sh"):
    check(subprocess.run(["bash", "-n", os.path.join(sl, f)]).returncode == 0, f"{f} is valid bash")
check("--dependency=afterany:" in open(os.path.join(sl, "submit.sh")).read(), "the aggregation waits for the array")


def free_port():
    import socket
    with socket.socket() as so:
        so.bind(("127.0.0.1", 0))
        return so.getsockname()[1]


def start_slurm(d):
    """A private Slurm on this machine (Debian slurmctld, slurmd, munge): munged, slurmctld and
    slurmd in D with their own ports, sockets and state. Returns (environment, pids) or the
    reason it cannot."""
    need = [x for x in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol") if not shutil.which(x)]
    if need:
        return None, f"not installed: {', '.join(need)} (Debian slurmctld slurmd slurm-client munge)"
    if os.geteuid() != 0:
        return None, "slurmd must run as root to start jobs"
    if not os.path.exists("/etc/munge/munge.key"):
        return None, "no /etc/munge/munge.key"
    host = subprocess.run(["hostname", "-s"], capture_output=True, text=True).stdout.strip()
    for sub in ("state", "spool", "munge"):
        os.makedirs(os.path.join(d, sub), exist_ok=True)
    sock = os.path.join(d, "munge", "munge.socket")
    conf = os.path.join(d, "slurm.conf")
    with open(conf, "w") as f:
        f.write("\n".join([
            "ClusterName=flexcomp-study-test", f"SlurmctldHost={host}",
            f"SlurmctldPort={free_port()}", f"SlurmdPort={free_port()}",
            "AuthType=auth/munge", f"AuthInfo=socket={sock}",
            f"StateSaveLocation={d}/state", f"SlurmdSpoolDir={d}/spool",
            f"SlurmctldPidFile={d}/slurmctld.pid", f"SlurmdPidFile={d}/slurmd.pid",
            f"SlurmctldLogFile={d}/slurmctld.log", f"SlurmdLogFile={d}/slurmd.log",
            "SlurmUser=root", "ProctrackType=proctrack/linuxproc", "TaskPlugin=task/none",
            "SchedulerType=sched/builtin", "SelectType=select/cons_tres", "SelectTypeParameters=CR_CPU",
            "ReturnToService=2", "MpiDefault=none", "JobAcctGatherType=jobacct_gather/none",
            f"NodeName={host} CPUs={os.cpu_count() or 1} State=UNKNOWN",
            "PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP", ""]))
    senv = dict(env, SLURM_CONF=conf)
    pids = []
    m = subprocess.run(["munged", "-f", f"--socket={sock}", f"--pid-file={d}/munge/munged.pid",
                        f"--log-file={d}/munge/munged.log", f"--seed-file={d}/munge/seed"], capture_output=True, text=True)
    if m.returncode:
        return None, f"munged did not start: {m.stderr.strip()}"
    for _ in range(50):
        if os.path.exists(f"{d}/munge/munged.pid") and open(f"{d}/munge/munged.pid").read().strip():
            break
        time.sleep(0.1)
    pids.append(int(open(f"{d}/munge/munged.pid").read()))
    log = open(os.path.join(d, "daemons.out"), "w")
    pids.append(subprocess.Popen(["slurmctld", "-D", "-i", "-f", conf], stdout=log, stderr=log, env=senv).pid)
    time.sleep(2)
    pids.append(subprocess.Popen(["slurmd", "-D", "-f", conf], stdout=log, stderr=log, env=senv).pid)
    for _ in range(30):
        s = subprocess.run(["sinfo", "-h", "-o", "%T"], capture_output=True, text=True, env=senv)
        if s.returncode == 0 and s.stdout.strip() == "idle":
            return (senv, pids), None
        time.sleep(1)
    stop_slurm(pids)
    return None, f"the node did not come up (see {d}/slurmctld.log, slurmd.log)"


def stop_slurm(pids):
    for pid in reversed(pids):
        try:
            os.kill(pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
    time.sleep(1)


import tempfile  # noqa: E402
daemons = tempfile.mkdtemp(prefix="flexcomp-slurm-")   # short: munge's socket path must fit a sockaddr_un
started, why = start_slurm(daemons)
if started:
    senv, pids = started
    try:
        p = subprocess.run(["bash", os.path.join(sl, "submit.sh")], capture_output=True, text=True, env=senv)
        check(p.returncode == 0, "submit.sh submitted the array and the aggregation" + ("" if p.returncode == 0 else p.stderr))
        job = p.stdout.strip().splitlines()[-1] if p.stdout.strip() else ""
        for _ in range(600):
            q = subprocess.run(["squeue", "-h"], capture_output=True, text=True, env=senv)
            if q.returncode == 0 and not q.stdout.strip():
                break
            time.sleep(1)
        check(os.path.exists(os.path.join(out, "cases.csv")) and table(out) == ref,
              f"Slurm (a local controller, job {job}): the array and the aggregation give the serial table")
    finally:
        stop_slurm(pids)
        shutil.rmtree(daemons, ignore_errors=True)
else:
    # No Slurm here: the array's tasks run as Slurm would run them, one process per
    # task with SLURM_ARRAY_TASK_ID set, then the aggregation job.
    print(f"note: SKIPPED the submission to Slurm ({why}); each array task is run by bash with "
          "SLURM_ARRAY_TASK_ID instead")
    for k in range(20):
        subprocess.run(["bash", os.path.join(sl, "cases.sbatch")], env=dict(env, SLURM_ARRAY_TASK_ID=str(k)), check=True)
    subprocess.run(["bash", os.path.join(sl, "aggregate.sbatch")], env=env, check=True)
    check(table(out) == ref, "the Slurm array's tasks give the serial table")
finish()
