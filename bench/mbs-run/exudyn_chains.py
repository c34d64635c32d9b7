#!/usr/bin/env python3
"""rigid chains side by side with Exudyn's kinematic tree + DOPRI5.

Not part of the build or CI: it needs an Exudyn build (see docs/benchmarks.md,
"Rigid chains", for how it was built here from the Exudyn 1.11 sources with
Debian's pybind11) and bench_chains from this repository's build.

The same chain in both tools: N rods of 0.1 m, 0.1 kg, 10 mm diameter
(bench/mbs-run/chain_scene.h), joints at the rod ends, released at rest from
the horizontal under g = 9.81 m/s^2. mbs-run: 6 coordinates per rod, 5
constraint rows per revolute joint about y, gravity -z (bench_chains tip ...).
Exudyn: ObjectKinematicTree, N relative joint angles (RevoluteZ, gravity -y),
explicit DOPRI5 with automatic step size; the rod's centroidal inertia is the
same (the axial one only enters an idle spin). Both run at rtol r with
atol = 1e-3 r (mbs-run's default), the longest step t_end (mbs-run: ten output
steps; Exudyn: endTime / numberOfSteps). Each run's accuracy is the distance
of the free end at t_end from a converged reference (mbs-run at rtol 1e-10,
itself checked against the minimal-coordinate chain in
tests/mbs-run/test_chain_reference.cpp; Exudyn at rtol 1e-10 agrees with it
to 4e-12 m at N = 10, and from N = 50 its step control stalls at its minimum
step at rtol 1e-9 and below, the rounding of its dense N x N mass-matrix solve
being above atol); CPU is process time of the solve.

Usage: exudyn_chains.py --exudyn DIR --bench PATH [--sizes 10 50 200] [--rtols ...] [--t-end T]
                        [--ref-rtol R] [--per-eval] [--formulation auto|tree|constrained] [--timeout S]
  DIR: the folder holding the `exudyn` package with exudynCPPfast*.so in it.
"""
import argparse
import math
import subprocess
import sys
import time

L, M, D, G = 0.1, 0.1, 0.01, 9.81
I_AXIAL = 0.5 * M * (D / 2) ** 2
I_TRANS = M * (3 * (D / 2) ** 2 + L * L) / 12


def mbs_run(bench, n, t_end, rtol, formulation="auto"):
    line = subprocess.run([bench, "tip", str(n), repr(t_end), repr(rtol), formulation], capture_output=True,
                          text=True, check=False).stdout
    head, _, status = line.partition(" status ")
    w = head.split()
    return {"cpu": float(w[1]), "steps": int(w[3]), "evals": int(w[5]), "tip": (float(w[7]), float(w[8])),
            "status": status.strip()}


def exudyn_chain(exu, n):
    import numpy as np
    from exudyn.itemInterface import NodeGenericODE2, ObjectKinematicTree
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                       initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
    mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, jointTypes=[exu.JointType.RevoluteZ] * n, linkParents=list(range(-1, n - 1)),
        jointTransformations=exu.Matrix3DList([np.eye(3)] * n),
        jointOffsets=exu.Vector3DList([[0.0, 0.0, 0.0]] + [[L, 0.0, 0.0]] * (n - 1)),
        linkInertiasCOM=exu.Matrix3DList([np.diag([I_AXIAL, I_TRANS, I_TRANS])] * n),
        linkCOMs=exu.Vector3DList([[L / 2, 0.0, 0.0]] * n), linkMasses=[M] * n, gravity=[0.0, -G, 0.0]))
    mbs.Assemble()
    return SC, mbs, node


def exudyn_eval_ms(exu, n):
    """CPU of one evaluation of Exudyn's kinematic tree: the difference of
    1 + k and 1 fixed RK4 steps (4 k evaluations), which removes the set-up;
    k = 2e5 / N^2 (at least 2) keeps the timed part near 0.1-1 s."""
    SC, mbs, node = exudyn_chain(exu, n)
    k = max(2, int(2e5 / n**2))
    cpu = []
    for steps in (1, 1 + k):
        ss = exu.SimulationSettings()
        ti = ss.timeIntegration
        ti.endTime = 1e-5 * steps
        ti.numberOfSteps = steps
        ti.automaticStepSize = False
        ti.verboseMode = 0
        ti.explicitIntegration.computeEndOfStepAccelerations = False
        ss.solutionSettings.writeSolutionToFile = False
        ss.displayComputationTime = False
        ss.parallel.numberOfThreads = 1
        c0 = time.process_time()
        mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.RK44)
        cpu.append(time.process_time() - c0)
    return 1e3 * (cpu[1] - cpu[0]) / (4 * k)


def exudyn_run(exu, n, t_end, rtol):
    import numpy as np
    SC, mbs, node = exudyn_chain(exu, n)
    ss = exu.SimulationSettings()
    ti = ss.timeIntegration
    ti.endTime = t_end
    ti.numberOfSteps = 1  # longest step t_end, as mbs-run's ten output steps here
    ti.automaticStepSize = True
    ti.initialStepSize = 1e-4  # its default, the longest step, sends the first step to minimumStepSize
    ti.relativeTolerance = rtol
    ti.absoluteTolerance = 1e-3 * rtol
    ti.verboseMode = 0
    ti.explicitIntegration.computeEndOfStepAccelerations = False  # would double the evaluations
    ss.solutionSettings.writeSolutionToFile = False
    ss.solutionSettings.sensorsWritePeriod = t_end
    ss.displayComputationTime = False
    ss.displayStatistics = False
    ss.parallel.numberOfThreads = 1
    c0 = time.process_time()
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.DOPRI5)
    cpu = time.process_time() - c0
    q = mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)
    phi = np.cumsum(q)
    tip = (float(L * np.cos(phi).sum()), float(L * np.sin(phi).sum()))
    steps = "-"
    try:
        it = mbs.sys["dynamicSolver"].it
        steps = it.currentStepIndex
    except Exception:
        pass
    return {"cpu": cpu, "tip": tip, "steps": steps}


def _child(exu_dir, n, t_end, rtol, queue):
    sys.path.insert(0, exu_dir)
    sys.exudynFast = True
    import exudyn as exu
    queue.put(exudyn_run(exu, n, t_end, rtol))


def exudyn_timed(exu_dir, n, t_end, rtol, timeout):
    """exudyn_run in a child process; None when it has no answer within
    timeout s (from N = 200 at rtol 1e-6 its step control reaches its minimum
    step, 1e-8 s, and crawls on)."""
    import multiprocessing as mp
    q = mp.Queue()
    p = mp.Process(target=_child, args=(exu_dir, n, t_end, rtol, q))
    p.start()
    try:
        return q.get(timeout=timeout)
    except Exception:
        return None
    finally:
        p.terminate()
        p.join()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exudyn", required=True)
    ap.add_argument("--bench", required=True)
    ap.add_argument("--sizes", type=int, nargs="*", default=[10, 50, 200])
    ap.add_argument("--rtols", type=float, nargs="*", default=[1e-4, 1e-6, 1e-8])
    ap.add_argument("--t-end", type=float, default=0.0, help="span [s]; default 1 s up to N = 50, 0.5 s above")
    ap.add_argument("--ref-rtol", type=float, default=1e-10, help="rtol of mbs-run's reference run")
    ap.add_argument("--per-eval", action="store_true", help="only Exudyn's CPU per evaluation for each N")
    ap.add_argument("--formulation", default="auto", choices=["auto", "tree", "constrained"],
                    help="mbs-run's formulation (auto: joint coordinates for these chains)")
    ap.add_argument("--timeout", type=float, default=120.0, help="Exudyn's longest run [s wall]")
    a = ap.parse_args()
    sys.path.insert(0, a.exudyn)
    sys.exudynFast = True  # the build without range checks, the fastest
    import exudyn as exu
    print(f"Exudyn {exu.config.Version()}; mbs-run {a.bench}\n")
    if a.per_eval:
        for n in a.sizes:
            print(f"N = {n}: Exudyn {exudyn_eval_ms(exu, n):.3f} ms per evaluation", flush=True)
        return
    print("| N | t_end [s] | rtol | mbs-run CPU s / sim s | mbs-run free-end error [m] | mbs-run steps | "
          "Exudyn CPU s / sim s | Exudyn free-end error [m] | Exudyn / mbs-run CPU |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n in a.sizes:
        t_end = a.t_end if a.t_end > 0 else 1.0 if n <= 50 else 0.5
        ref = mbs_run(a.bench, n, t_end, a.ref_rtol, a.formulation)
        print(f"| {n} | {t_end} | reference {a.ref_rtol:.0e} ({ref['status'][:40]}) | {ref['cpu'] / t_end:.3g} | - | "
              f"{ref['steps']} | | | |", flush=True)
        for rtol in a.rtols:
            r = mbs_run(a.bench, n, t_end, rtol, a.formulation)
            timeout = max(a.timeout, 30.0 * r["cpu"])
            e = exudyn_timed(a.exudyn, n, t_end, rtol, timeout)
            exu_cols = (f"{e['cpu'] / t_end:.3g} | {math.dist(e['tip'], ref['tip']):.1e} | {e['cpu'] / r['cpu']:.2f}"
                        if e else f"no answer in {timeout:.0f} s (wall) | - | > {timeout / r['cpu']:.0f}")
            note = "" if r["status"] == "completed" else f" ({r['status'][:40]})"
            print(f"| {n} | {t_end} | {rtol:.0e} | {r['cpu'] / t_end:.3g} | {math.dist(r['tip'], ref['tip']):.1e} | "
                  f"{r['steps']}{note} | {exu_cols} |", flush=True)


if __name__ == "__main__":
    main()
