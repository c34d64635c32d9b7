#!/usr/bin/python3
"""Figures 8 and 9 of Neto, Ambrosio & Leal (CMAME 2006) from an mbs-run results file.

  /usr/bin/python3 plot_results.py RESULTS.h5 [OUTDIR] [--label NAME] [--compare OTHER.h5:LABEL ...]

Writes OUTDIR/sar_fig8_actuator_angle.png (R3 angle, phase 1),
OUTDIR/sar_fig9_panel3_omega.png (panel 3 angular velocity about the hinge
axis, phase 1) and OUTDIR/sar_phase2.png (R1 angle and panel angular
velocities over the whole run). Uses Debian's python3-h5py and
python3-matplotlib (run with /usr/bin/python3).
"""
import argparse
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PAPER_ALIGNMENT_S = 5.5  # Neto et al. 2006, sec. 4.4


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("outdir", nargs="?", default=".")
    ap.add_argument("--label", default="rigid (this reconstruction)")
    ap.add_argument("--phase1-end", type=float, default=10.0)
    ap.add_argument("--compare", action="append", default=[],
                    help="another results file drawn on Figures 8 and 9, as FILE:LABEL")
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    others = []
    for spec in a.compare:
        path, _, label = spec.partition(":")
        with h5py.File(path, "r") as g:
            tt = g["time"][:]
            keep = tt <= a.phase1_end + 1e-9
            others.append((label or path, tt[keep], g["joints/R3/angle"][:][keep],
                           g["bodies/B3/angular_velocity"][:, 1][keep]))

    with h5py.File(a.results, "r") as f:
        t = f["time"][:]
        r3 = f["joints/R3/angle"][:]
        r1 = f["joints/R1/angle"][:]
        # The hinge axes are global Y in this model (the paper's z axis).
        w3 = f["bodies/B3/angular_velocity"][:, 1]
        w2 = f["bodies/B2/angular_velocity"][:, 1]
        status = f.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else status
    p1 = t <= a.phase1_end + 1e-9
    k = np.argmin(np.abs(np.where(p1, r3, np.inf)))

    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.plot(t[p1], r3[p1], label=a.label)
    for label, tt, rr, _ in others:
        kk = np.argmin(np.abs(rr))
        ax.plot(tt, rr, label=f"{label} (alignment {tt[kk]:.2f} s)")
    ax.axvline(PAPER_ALIGNMENT_S, color="gray", ls="--", lw=0.8, label="paper: alignment at 5.5 s")
    ax.plot([t[k]], [r3[k]], "o", color="C3", label=f"alignment ({a.label}): {t[k]:.2f} s")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("actuator (R3) angle [rad]")
    ax.set_title("SAR antenna, phase 1: actuator angle (paper Fig. 8)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(a.outdir, "sar_fig8_actuator_angle.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.plot(t[p1], w3[p1], label=a.label)
    for label, tt, _, ww in others:
        ax.plot(tt, ww, label=label, lw=0.8)
    ax.axvline(PAPER_ALIGNMENT_S, color="gray", ls="--", lw=0.8, label="paper: alignment at 5.5 s")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("panel 3 angular velocity about the hinge axis [rad/s]")
    ax.set_title("SAR antenna, phase 1: panel 3 angular velocity (paper Fig. 9)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(a.outdir, "sar_fig9_panel3_omega.png"), dpi=120)

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.4, 6.0), sharex=True)
    ax1.plot(t, r1, label="R1 (actuator B)")
    ax1.plot(t, r3, label="R3 (actuator A)")
    ax1.set_ylabel("joint angle [rad]")
    ax1.legend()
    ax1.grid(alpha=0.3)
    ax2.plot(t, w2, label="panel 2")
    ax2.plot(t, w3, label="panel 3")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("angular velocity about Y [rad/s]")
    ax2.legend()
    ax2.grid(alpha=0.3)
    ax1.set_title(f"SAR antenna, phases 1 and 2 ({status})")
    fig.tight_layout()
    fig.savefig(os.path.join(a.outdir, "sar_phase2.png"), dpi=120)
    print(f"alignment of B7/B8 (|R3| min in phase 1): {r3[k]:.4f} rad at t = {t[k]:.2f} s; "
          f"figures in {a.outdir}")


if __name__ == "__main__":
    main()
