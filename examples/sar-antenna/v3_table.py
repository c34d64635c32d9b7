#!/usr/bin/python3
"""The SAR page's model table (docs/sar-antenna.md, "Results"), written from the results files.

  v3_table.py --run FILE:LABEL [--run FILE:LABEL ...] [--rigid LABEL] [--phase1-end 10]
              [--statements] [--body LABEL=PANEL3_BODY_FILE ...] [--doc FILE --block NAME]

One markdown row per run: the knee's closest approach to straight in phase 1 (plot_results.py's
definition), the first impact on hinge 2/3's coplanar stop (time, rate before -> after, how many
impacts follow within 0.1 s), the H23 and R1 latches (time, arrival rate; /margins/latches), the
phase-2 duration (R1 latch - phase-1 end) against the run labelled --rigid, the V-coupler legs'
largest compression in each phase against their Euler load (/margins/beams/B11, B12), the kinetic
and strain energies at the phase switch, the energy balance, the contact monitor's smallest
clearance up to 0.2 s before the R1 latch (where panels 1 and 2 meet at the hinge line: the
monitor's idealisation), the largest contact force, the peak Tsai-Wu index (when the run recovered
stresses), CPU seconds, steps and the integrator. Every figure is read from the file: rerun the
scenes and this script, and the table follows.

With --doc and --block the table replaces the lines between `<!-- v3_table NAME -->` and
`<!-- /v3_table NAME -->` in FILE (docs/sar-antenna.md) instead of going to standard output.

With --insert MD the block receives that markdown file as it is (stress_report.py's tables).

With --statements it writes instead the figures the page's point-by-point comparison with the paper
quotes, one row per run: the first stop impulse, the largest change of panel 3's rate between two
output rows in phase 1, the hinge joints' (S8, S12) peak reaction in phase 1, the kinetic energy at
the knee's minimum and what the phase-1 impacts dissipate, the strain energy's phase-1 peak, R3 at
the paper's Fig. 10 instants (5.72, 6.08, 6.48 s), R3's mean rate over 7.5-8 s (Fig. 13), panel 3's
largest twist before and after the knee's minimum (with --body, plot_results.py's definition) and
the largest change of panel 3's rate between rows in phase 2 after 11.5 s (Fig. 15).
Uses Debian's python3-h5py and numpy (run with /usr/bin/python3).
"""
import argparse

import h5py
import numpy as np

from deploy_summary import latches, smallest_clearance, text
from plot_results import Run, panel_twist

LEGS = ("B11", "B12")


def legs(f, t, phase):
    """Largest compression of either leg in the rows `phase`, its ratio to the Euler load, leg, time."""
    best = (0.0, 0.0, "-", 0.0)
    for leg in LEGS:
        key = f"margins/beams/{leg}/axial_compression"
        if key not in f:
            continue
        s = f[key][()][phase]
        k = int(np.argmax(s))
        if s[k] > best[0]:
            best = (s[k], s[k] / f[key].attrs["euler_load"], leg, t[phase][k])
    return best


def row(path, label, phase1_end, rigid_phase2):
    run = Run(path, label, phase1_end)
    with h5py.File(path, "r") as f:
        a = f.attrs
        t = f["time"][()]
        cells = [label]
        ta = run.alignment()
        cells.append(f"{np.interp(ta, run.t, run.r3):.4f} rad, {ta:.3f} s" if ta is not None else "-")
        imp = run.h23_impacts
        if len(imp):
            n = int(np.sum(imp[:, 0] <= imp[0, 0] + 0.1))
            cells.append(f"{imp[0, 0]:.4f} s, {imp[0, 1]:.3f} -> {imp[0, 2]:+.3f} rad/s ({n} impact{'s' * (n > 1)})")
        else:
            cells.append("-")
        lat = latches(f)
        cells.append(f"{lat['H23'][0]:.4f} s, {lat['H23'][2]:.3f} rad/s" if "H23" in lat else "none")
        phase2 = None
        if "R1" in lat:
            cells.append(f"{lat['R1'][0]:.3f} s, {lat['R1'][2]:.4f} rad/s")
            phase2 = lat["R1"][0] - phase1_end
            rel = f" ({100 * (phase2 / rigid_phase2 - 1):+.1f} %)" if rigid_phase2 and label and phase2 != rigid_phase2 else ""
            cells.append(f"{phase2:.2f} s{rel}")
        else:
            cells += ["**not latched**", "-"]
        p1 = t <= phase1_end + 1e-9
        l1, l2 = legs(f, t, p1), legs(f, t, ~p1)
        cells.append(f"{l1[0]:.1f} N ({l1[1]:.2f}, {l1[2]}, {l1[3]:.2f} s) / {l2[0]:.1f} N ({l2[1]:.2f}, {l2[2]}, {l2[3]:.2f} s)")
        k10 = int(np.argmin(np.abs(t - phase1_end)))
        cells.append(f"{f['energy/kinetic'][k10]:.2f} J, {f['energy/strain'][k10]:.2f} J")
        # mbs-run's scale for the balance: the largest kinetic, potential or dissipated energy.
        scale = max(np.abs(f["energy/kinetic"][()]).max(), np.abs(f["energy/potential"][()]).max(),
                    f["energy/dissipated"][()].max())
        err = a["energy_balance_error"]
        cells.append(f"{err:.1e} J ({err / scale:.1e})")
        clearance = smallest_clearance(f, lat)
        cells.append(f"{1e3 * clearance[0]:.1f} mm ({clearance[1]}, {clearance[2]:.2f} s)" if clearance else "-")
        cf = [(f[f"contacts/{c}/force"].attrs["peak"], c, f[f"contacts/{c}/force"].attrs["peak_time"])
              for c in f["contacts"]] if "contacts" in f else []
        top = max(cf) if cf else None
        cells.append(f"{top[0]:.1f} N ({top[1]}, {top[2]:.2f} s)" if top and top[0] > 0 else "0")
        fi = a.get("peak_failure_index")
        cells.append(f"{fi:.3f} ({text(a['peak_failure_index_body'])}, {a['peak_failure_index_time']:.2f} s)"
                     if fi is not None else "-")
        cells.append(f"{a['cpu_seconds']:.1f} s, {int(a['steps'])} steps, {text(a['integrator'])}")
    return cells, phase2


HEADER = ["model", "knee minimum", "H23 stop: first impact", "H23 latch", "R1 latch: t, rate", "phase 2",
          "legs' largest compression (x Euler), phase 1 / phase 2", "T, strain at the switch",
          "energy balance error (of the largest term)", "smallest clearance", "largest contact force", "peak Tsai-Wu", "CPU"]


def statements(path, label, phase1_end, body):
    run = Run(path, label, phase1_end)
    with h5py.File(path, "r") as f:
        t = f["time"][()]
        p1 = t <= phase1_end + 1e-9
        ta = run.alignment()
        imp = run.h23_impacts
        first = imp[imp[:, 0] <= phase1_end] if len(imp) else imp
        cells = [label]
        cells.append(f"{first[0, 3]:.3f} N m s" if len(first) else "-")
        cells.append(f"{np.max(np.abs(np.diff(run.w3[p1]))):.3f} rad/s")
        reac = []
        for j in ("S8", "S12"):
            if f"joints/{j}/reaction_force" in f:
                r = np.linalg.norm(f[f"joints/{j}/reaction_force"][()][p1], axis=1)
                reac.append(f"{j} {r.max():.0f} N ({t[p1][int(np.argmax(r))]:.2f} s)")
        cells.append(", ".join(reac) or "-")
        kin = f["energy/kinetic"][()]
        cells.append(f"{np.interp(ta, t, kin):.2f} J" if ta is not None else "-")
        cells.append(f"{first[:, 4].sum() * 1e3:.1f} mJ" if len(first) else "-")
        strain = f["energy/strain"][()][p1]
        k = int(np.argmax(strain))
        cells.append(f"{strain[k]:.2f} J ({t[p1][k]:.2f} s)")
        cells.append(" / ".join(f"{np.interp(x, t, run.r3):.3f}" for x in (5.72, 6.08, 6.48)))
        cells.append(f"{(np.interp(8.0, t, run.r3) - np.interp(7.5, t, run.r3)) / 0.5:+.3f} rad/s")
        if body and run.modal3 is not None and ta is not None:
            tw = np.abs(panel_twist(run, body))
            before, after = tw[p1 & (t < ta)], tw[p1 & (t >= ta)]
            cells.append(f"{1e3 * before.max():.0f} / {1e3 * after.max():.0f} mrad")
        else:
            cells.append("-")
        late = ~p1 & (t >= 11.5)
        lat = latches(f)
        if "R1" in lat:
            late &= t <= lat["R1"][0]
        cells.append(f"{np.max(np.abs(np.diff(run.w3[late]))):.3f} rad/s" if late.sum() > 1 else "-")
    return cells


STATEMENT_HEADER = ["model", "first stop impulse", "largest change of omega_3 between rows, phase 1",
                    "hinge reactions, phase 1", "T at the knee minimum", "phase-1 impacts dissipate",
                    "strain energy, phase-1 peak", "R3 at 5.72 / 6.08 / 6.48 s [rad]", "R3 mean rate 7.5-8 s",
                    "panel 3 twist before / after the knee minimum",
                    "largest change of omega_3 between rows, 11.5 s to the R1 latch"]


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(cells) + " |" for cells in rows]


def emit(lines, doc, block):
    if not doc:
        print("\n".join(lines))
        return
    text = open(doc).read()
    start, end = f"<!-- v3_table {block} -->\n", f"<!-- /v3_table {block} -->"
    i, j = text.find(start), text.find(end)
    if i < 0 or j < i:
        raise SystemExit(f"v3_table.py: {doc} has no block '{start.strip()}' ... '{end}'")
    with open(doc, "w") as f:
        f.write(text[:i + len(start)] + "\n".join(lines) + "\n" + text[j:])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--run", action="append", default=[], help="a results file, as FILE:LABEL")
    ap.add_argument("--rigid", help="label of the run whose phase 2 the others are compared with")
    ap.add_argument("--phase1-end", type=float, default=10.0)
    ap.add_argument("--statements", action="store_true", help="the point-by-point figures instead")
    ap.add_argument("--body", action="append", default=[], help="LABEL=FILE: panel 3's body file, for the twist")
    ap.add_argument("--doc", help="a markdown file whose block --block the table replaces")
    ap.add_argument("--block", default="models", help="the block's name in --doc")
    ap.add_argument("--insert", help="put this markdown file (stress_report.py's tables) in the block instead")
    args = ap.parse_args()
    specs = [s.rsplit(":", 1) if ":" in s else (s, s) for s in args.run]
    if args.insert:
        emit(open(args.insert).read().rstrip("\n").splitlines(), args.doc, args.block)
        return
    if args.statements:
        bodies = dict(b.split("=", 1) for b in args.body)
        emit(table(STATEMENT_HEADER, [statements(p, lab, args.phase1_end, bodies.get(lab)) for p, lab in specs]),
             args.doc, args.block)
        return
    rigid_phase2 = None
    if args.rigid:
        for path, label in specs:
            if label == args.rigid:
                rigid_phase2 = row(path, label, args.phase1_end, None)[1]
    emit(table(HEADER, [row(path, label, args.phase1_end, rigid_phase2)[0] for path, label in specs]), args.doc, args.block)


if __name__ == "__main__":
    main()
