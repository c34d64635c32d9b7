#!/usr/bin/python3
"""Figures 8, 9, 12 and 13 of Neto, Ambrosio & Leal (CMAME 2006) from mbs-run results files.

  /usr/bin/python3 plot_results.py --run FILE.h5:LABEL [--run ...] --figure NAME [--figure ...] [--outdir DIR]

Each figure draws every run given, in order:
  fig8    actuator (R3) angle, phase 1        (paper: rigid and flexible)
  fig9    panel 3 angular velocity about the hinge axis, phase 1 (rigid and flexible)
  fig12   actuator angle, phase 1              (paper: isotropic and lay-up 2)
  fig13   actuator angle, phase 1              (paper: lay-up 1 and lay-up 2)
  phase2  R1, R3 angles and panel 2's angular velocity over the whole run, every run on one figure
  twist   torsion of panel 3 (needs --body LABEL=panel3.h5 for each flexible run)
and a summary table of every run is printed (alignment time, oscillation after it,
impacts on the hinge-2/3 stop, smallest truss-panel distance).

The older form  plot_results.py RESULTS.h5 [OUTDIR] [--label NAME] [--compare FILE:LABEL ...]
still writes fig8, fig9 and phase2. Uses Debian's python3-h5py and
python3-matplotlib (run with /usr/bin/python3).
"""
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PAPER_ALIGNMENT_S = 5.5  # Neto et al. 2006, sec. 4.4 (rigid model)
PAPER_FIG10_S = (5.72, 6.08, 6.48)  # Fig. 10 instants (isotropic model)

FILES = {
    "fig8": ("sar_fig8_actuator_angle.png", "actuator angle, rigid and flexible (paper Fig. 8)"),
    "fig9": ("sar_fig9_panel3_omega.png", "panel 3 angular velocity (paper Fig. 9)"),
    "fig12": ("sar_fig12_isotropic_layup2.png", "actuator angle, isotropic and lay-up 2 (paper Fig. 12)"),
    "fig13": ("sar_fig13_layup1_layup2.png", "actuator angle, lay-up 1 and lay-up 2 (paper Fig. 13)"),
    "phase2": ("sar_phase2.png", "phases 1 and 2"),
    "twist": ("sar_panel3_twist.png", "torsion of panel 3"),
}


class Run:
    def __init__(self, path, label, phase1_end):
        with h5py.File(path, "r") as f:
            self.t = f["time"][:]
            self.r3 = f["joints/R3/angle"][:]
            self.r1 = f["joints/R1/angle"][:]
            # The hinge axes are global Y in this model (the paper's z axis).
            self.w3 = f["bodies/B3/angular_velocity"][:, 1]
            self.w2 = f["bodies/B2/angular_velocity"][:, 1]
            self.modal3 = f["bodies/B3/modal_coordinates"][:] if "bodies/B3/modal_coordinates" in f else None
            # Stops (reconstruction v2): impacts on hinge 2/3's coplanar stop
            # and R1's deployed stop; contact monitor distances.
            self.h23_impacts = f["joints/H23/limit_impacts"][:] if "joints/H23/limit_impacts" in f else np.zeros((0, 5))
            self.r1_impacts = f["joints/R1/limit_impacts"][:] if "joints/R1/limit_impacts" in f else np.zeros((0, 5))
            self.h23 = f["joints/H23/angle"][:] if "joints/H23/angle" in f else None
            self.distances = {k: f["distances/" + k][:] for k in f["distances"]} if "distances" in f else {}
            status = f.attrs["status"]
            self.status = status.decode() if isinstance(status, bytes) else status
            self.cpu = float(f.attrs.get("cpu_seconds", np.nan))
        self.label = label
        self.p1 = self.t <= phase1_end + 1e-9

    def alignment(self):
        """Time of the knee's closest approach to straight: its first zero
        (v1 geometry, linear interpolation between samples) or, in v2 where the
        knee never straightens, its first local minimum below 0.2 rad
        (parabola through the three samples), whichever comes first (a knee that
        turns back at a minimum and crosses zero only later, after the stop's
        impacts, reached its closest approach at the minimum); None if neither
        in phase 1."""
        t, r = self.t[self.p1], self.r3[self.p1]
        found = []
        s = np.nonzero(np.sign(r[:-1]) * np.sign(r[1:]) <= 0)[0]
        if len(s):
            k = s[0]
            found.append(t[k] + (t[k + 1] - t[k]) * r[k] / (r[k] - r[k + 1]) if r[k] != r[k + 1] else t[k])
        m = np.nonzero((r[1:-1] < r[:-2]) & (r[1:-1] <= r[2:]) & (r[1:-1] < 0.2))[0]
        if len(m):
            k = m[0] + 1
            den = r[k - 1] - 2 * r[k] + r[k + 1]
            found.append(t[k] + 0.5 * (t[k] - t[k - 1]) * (r[k - 1] - r[k + 1]) / den if den > 0 else t[k])
        return min(found) if found else None

    def after_alignment(self):
        """Peak-to-peak of R3 and largest |omega3| between alignment and the end of phase 1."""
        ta = self.alignment()
        if ta is None:
            return np.nan, np.nan
        k = self.p1 & (self.t >= ta)
        return np.ptp(self.r3[k]), np.max(np.abs(self.w3[k]))


def panel_twist(run, body_file):
    """Twist of panel 3 [rad]: difference of the out-of-plane displacement
    gradients across the width at the two ends, (dz(+x) - dz(-x)) / width, from
    the mode shapes at the four corner nodes of the body file."""
    with h5py.File(body_file, "r") as b:
        x = b["mesh/nodes"][:]
        phi = b["modes/shapes"][:]
    n_modes = run.modal3.shape[1]
    lx, ly = x[:, 0].max(), x[:, 1].max()
    corner = [int(np.argmin((x[:, 0] - sx * lx) ** 2 + (x[:, 1] - sy * ly) ** 2))
              for sx, sy in ((1, 1), (1, -1), (-1, 1), (-1, -1))]
    # Transverse (z) translation of each corner node in each mode; /modes/shapes
    # is (modes, nodes, 6) (docs/body-file.md).
    dz = np.array([phi[:n_modes, c, 2] for c in corner])
    w = run.modal3 @ dz.T  # (time, 4 corners)
    width = 2 * ly
    return ((w[:, 0] - w[:, 1]) - (w[:, 2] - w[:, 3])) / width


def finish(fig, ax, outdir, name, title):
    ax.set_title("SAR antenna, " + title, fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = os.path.join(outdir, FILES[name][0])
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def angle_figure(runs, outdir, name, mark_fig10=False):
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for i, r in enumerate(runs):
        ta = r.alignment()
        tag = f"alignment {ta:.2f} s" if ta is not None else "no alignment"
        ax.plot(r.t[r.p1], r.r3[r.p1], color=f"C{i}", lw=1.0, label=f"{r.label} ({tag})")
        if ta is not None:
            ax.plot([ta], [np.interp(ta, r.t, r.r3)], "o", color=f"C{i}", ms=4)
        for imp in r.h23_impacts:
            if imp[0] <= 10.0:
                ax.axvline(imp[0], color=f"C{i}", lw=0.5, ls="-.")
    ax.axvline(PAPER_ALIGNMENT_S, color="gray", ls="--", lw=0.8, label="paper: alignment at 5.5 s")
    if mark_fig10:
        for tt in PAPER_FIG10_S:
            ax.axvline(tt, color="gray", ls=":", lw=0.7)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("actuator (R3) angle [rad]")
    return finish(fig, ax, outdir, name, "phase 1: " + FILES[name][1])


def omega_figure(runs, outdir):
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for i, r in enumerate(runs):
        ax.plot(r.t[r.p1], r.w3[r.p1], color=f"C{i}", lw=0.8, label=r.label)
    ax.axvline(PAPER_ALIGNMENT_S, color="gray", ls="--", lw=0.8, label="paper: alignment at 5.5 s")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("panel 3 angular velocity about the hinge axis [rad/s]")
    return finish(fig, ax, outdir, "fig9", "phase 1: " + FILES["fig9"][1])


def phase2_figure(runs, outdir):
    """Both phases of every run: R1 (actuator B) and R3 (actuator A) above, panel 2's rate below."""
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.4, 6.0), sharex=True)
    for i, run in enumerate(runs):
        ax1.plot(run.t, run.r1, color=f"C{i}", label=f"{run.label}: R1 (actuator B)")
        ax1.plot(run.t, run.r3, color=f"C{i}", ls="--", lw=0.8, label=f"{run.label}: R3 (actuator A)")
        ax2.plot(run.t, run.w2, color=f"C{i}", lw=0.8, label=run.label)
    ax1.set_ylabel("joint angle [rad]")
    ax1.legend(fontsize=7)
    ax1.grid(alpha=0.3)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("panel 2 angular velocity about Y [rad/s]")
    return finish(fig, ax2, outdir, "phase2", "phases 1 and 2: " + ", ".join(r.label for r in runs))


def twist_figure(runs, bodies, outdir):
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for i, r in enumerate(runs):
        if r.label not in bodies or r.modal3 is None or r.modal3.shape[1] == 0:
            continue
        tw = panel_twist(r, bodies[r.label])
        ax.plot(r.t[r.p1], 1e3 * tw[r.p1], color=f"C{i}", lw=0.8, label=r.label)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("panel 3 twist across its width [mrad]")
    return finish(fig, ax, outdir, "twist", "phase 1: " + FILES["twist"][1])


def summary(runs):
    print(f"{'run':<22} {'alignment [s]':>13} {'R3 min [rad]':>12} {'R3 p-p after [rad]':>19} {'max|w3| after':>14} "
          f"{'R3(10 s) [rad]':>15} {'H23 impacts (t, rate-, rate+)':>34} {'R1 stop [s]':>11} {'cpu [s]':>8}  status")
    for r in runs:
        ta = r.alignment()
        pp, wm = r.after_alignment()
        k10 = np.argmin(np.abs(r.t - 10.0))
        rmin = np.interp(ta, r.t, r.r3) if ta is not None else np.nan
        imps = "; ".join(f"{i[0]:.3f} {i[1]:.3f} {i[2]:.3f}" for i in r.h23_impacts[:2]) or "-"
        if len(r.h23_impacts) > 2:
            imps += f" (+{len(r.h23_impacts) - 2})"
        r1 = f"{r.r1_impacts[0][0]:.3f}" if len(r.r1_impacts) else "-"
        print(f"{r.label:<22} {('%.3f' % ta) if ta is not None else '-':>13} {rmin:>12.4f} {pp:>19.4f} {wm:>14.3f} "
              f"{r.r3[k10]:>15.4f} {imps:>34} {r1:>11} {r.cpu:>8.2f}  {r.status}")
    for r in runs:
        if r.distances:
            closest = ", ".join(f"{k} {1e3 * d.min():.1f} mm at {r.t[np.argmin(d)]:.2f} s"
                                for k, d in sorted(r.distances.items(), key=lambda kv: kv[1].min())[:3])
            print(f"{r.label}: smallest truss-panel distances (axis to mid-plane): {closest}")


def parse_spec(spec):
    path, sep, label = spec.partition(":")
    return path, (label if sep else os.path.splitext(os.path.basename(path))[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", nargs="?", help="(older form) the first results file")
    ap.add_argument("outdir_pos", nargs="?", metavar="outdir", help="(older form) output folder")
    ap.add_argument("--outdir", help="output folder (default .)")
    ap.add_argument("--label", default="rigid (this reconstruction)", help="(older form) label of RESULTS")
    ap.add_argument("--compare", action="append", default=[], help="(older form) FILE:LABEL")
    ap.add_argument("--run", action="append", default=[], help="a results file, as FILE:LABEL")
    ap.add_argument("--figure", action="append", default=[], choices=sorted(FILES) + ["all"])
    ap.add_argument("--body", action="append", default=[],
                    help="LABEL=panel3 body file, for the twist figure")
    ap.add_argument("--phase1-end", type=float, default=10.0)
    a = ap.parse_args()

    specs = ([(a.results, a.label)] if a.results else []) + [parse_spec(s) for s in a.compare + a.run]
    if not specs:
        ap.error("no results file: give --run FILE:LABEL")
    outdir = a.outdir or a.outdir_pos or "."
    figures = a.figure or (["fig8", "fig9", "phase2"] if a.results else ["all"])
    if "all" in figures:
        figures = ["fig8", "fig9", "fig12", "fig13", "phase2"] + (["twist"] if a.body else [])
    os.makedirs(outdir, exist_ok=True)
    try:
        runs = [Run(p, l, a.phase1_end) for p, l in specs]
    except (OSError, KeyError) as e:
        sys.exit(f"plot_results.py: cannot read a results file: {e}")
    bodies = dict(b.split("=", 1) for b in a.body)

    for name in figures:
        if name in ("fig8", "fig12", "fig13"):
            path = angle_figure(runs, outdir, name, mark_fig10=(name == "fig8"))
        elif name == "fig9":
            path = omega_figure(runs, outdir)
        elif name == "phase2":
            path = phase2_figure(runs, outdir)
        else:
            path = twist_figure(runs, bodies, outdir)
        print(f"wrote {path}")
    summary(runs)


if __name__ == "__main__":
    main()
