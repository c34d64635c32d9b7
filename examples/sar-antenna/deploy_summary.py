#!/usr/bin/python3
"""The end-of-make summary of the SAR example: one line per model from its results file
(mbs-run's margins, docs/mbs-run.md "Margins"; layout in docs/file-formats.md).

  deploy_summary.py --run FILE:LABEL[:STRESS_FILE] ...

Per model: the deployment time (the R1 latch, /margins/latches), each latch's time and
arrival rate, the smallest margins (the largest axial compression of the named trusses
against its Euler load, root attribute buckling_ratio_max; the smallest clearance of the
contact monitor's pairs up to 0.2 s before the R1 latch, from /distances) and the peak Tsai-Wu failure index (root
attribute peak_failure_index, from STRESS_FILE when the run's own file has no stresses).
Uses Debian's python3-h5py (run with /usr/bin/python3).
"""
import argparse
import sys

import h5py


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def latches(f):
    """Each latched joint's row of /margins/latches (time, angle, arrival rate), by joint name."""
    if "margins/latches" not in f:
        return {}
    names = text(f["margins/latches"].attrs.get("joints", "")).split()
    return {n: row for n, row in zip(names, f["margins/latches"][()])}


def smallest_clearance(f, lat):
    """The contact monitor's smallest distance up to 0.2 s before the R1 latch (at the latch panels 1 and
    2 are coplanar and their mid-plane rectangles meet at the hinge line: the monitor's idealisation, not
    a crossing), or to the end without one: (distance, pair, time, end), or None without a monitor."""
    if "distances" not in f:
        return None
    t = f["time"][()]
    end = lat["R1"][0] - 0.2 if "R1" in lat else t[-1]
    rows = t <= end
    pair, d = min(((k, f["distances"][k][()][rows]) for k in f["distances"]), key=lambda kv: kv[1].min())
    return d.min(), pair, t[rows][d.argmin()], end


def line(spec):
    path, _, rest = spec.partition(":")
    label, _, stress = rest.partition(":")
    with h5py.File(path, "r") as f:
        a = f.attrs
        out = [f"{label or path}: {text(a.get('status', '?'))}"]
        lat = latches(f)
        out.append(f"deployed (R1 latch) at {lat['R1'][0]:.3f} s" if "R1" in lat else "NOT deployed (no R1 latch)")
        out.append("latches " + (", ".join(f"{n} {row[0]:.3f} s at {row[2]:.3f} rad/s" for n, row in lat.items())
                                 or "none"))
        if "buckling_ratio_max" in a:
            out.append(f"largest truss compression {a['buckling_ratio_max']:.2f} x Euler ({text(a['buckling_ratio_max_body'])})")
        clearance = smallest_clearance(f, lat)
        if clearance:
            d, pair, when, end = clearance
            out.append(f"smallest clearance {1e3 * d:.1f} mm ({pair}, {when:.2f} s; to {end:.2f} s)")
        fi = a.get("peak_failure_index")
        src = f
        if fi is None and stress:
            src = h5py.File(stress, "r")
            fi = src.attrs.get("peak_failure_index")
        if fi is not None:
            out.append(f"peak failure index {fi:.3g} ({text(src.attrs['peak_failure_index_body'])}, "
                       f"{src.attrs['peak_failure_index_time']:.2f} s)")
        out.append(f"CPU {a['cpu_seconds']:.1f} s")
    return " | ".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--run", action="append", required=True, help="FILE:LABEL[:STRESS_FILE]")
    a = ap.parse_args()
    try:
        print("SAR deployment summary (docs/sar-antenna.md):")
        for spec in a.run:
            print("  " + line(spec))
    except (OSError, KeyError) as e:
        sys.exit(f"deploy_summary.py: cannot read a results file: {e}")


if __name__ == "__main__":
    main()
