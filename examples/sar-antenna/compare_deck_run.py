#!/usr/bin/env python3
"""The deck route against the YAML route (docs/sar-antenna.md, "The panels from Nastran decks").

    compare_deck_run.py bodies YAML_BODY.h5 DECK_BODY.h5 [...pairs]
    compare_deck_run.py runs YAML_RUN.h5 DECK_RUN.h5

`bodies`: the largest relative difference of each body-file quantity (frequencies, nodal and interface
shapes, inertia invariants, strain modes), each against the largest entry of the YAML route's value.
`runs`: the largest differences of the joint angles, the energies and the latch times of two results
files. Prints a table; `--max-body REL` / `--max-angle RAD` ... make it a check (exit status 1 past them).
"""
import argparse
import sys

import h5py
import numpy as np


def rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape:
        return np.inf
    scale = np.abs(a).max() if a.size else 0.0
    return float(np.abs(a - b).max() / scale) if scale > 0 else float(np.abs(a - b).max() if a.size else 0.0)


def body_differences(yaml_h5, deck_h5):
    out = {}
    with h5py.File(yaml_h5, "r") as a, h5py.File(deck_h5, "r") as b:
        for key in ("mesh/nodes", "mesh/triangles", "modes/frequencies_hz", "modes/shapes", "mass/nodal",
                    "inertia/mass", "inertia/center_of_mass", "inertia/tensor", "stress/strains"):
            out[key] = rel(a[key][()], b[key][()])
        for key in a["invariants"]:
            out["invariants/" + key] = rel(a["invariants"][key][()], b["invariants"][key][()])
        names = set(a["interfaces"]) | set(b["interfaces"])
        for name in sorted(names):
            if name not in a["interfaces"] or name not in b["interfaces"]:
                out[f"interfaces/{name}"] = np.inf
                continue
            ia, ib = a["interfaces"][name], b["interfaces"][name]
            out[f"interfaces/{name}"] = max(rel(ia["shapes"][()], ib["shapes"][()]),
                                            rel(ia["position"][()], ib["position"][()]),
                                            float(ia["node"][()] != ib["node"][()]))
    return out


def run_differences(yaml_h5, deck_h5):
    out = {}
    with h5py.File(yaml_h5, "r") as a, h5py.File(deck_h5, "r") as b:
        if a["time"].shape != b["time"].shape or np.abs(a["time"][()] - b["time"][()]).max() > 0:
            sys.exit("compare_deck_run.py: the two runs' output times differ")
        for j in ("R1", "R2", "R3", "H23"):
            out[f"joints/{j}/angle [rad]"] = float(np.abs(a[f"joints/{j}/angle"][()] - b[f"joints/{j}/angle"][()]).max())
        emax = max(np.abs(a[f"energy/{k}"][()]).max() for k in ("kinetic", "potential", "strain", "applied_work"))
        for k in ("kinetic", "potential", "strain", "dissipated", "applied_work"):
            out[f"energy/{k} [of the largest energy]"] = float(np.abs(a[f"energy/{k}"][()] - b[f"energy/{k}"][()]).max() / emax)
        if "margins/latches" in a:
            la, lb = a["margins/latches"][()], b["margins/latches"][()]
            out["latch times [s]"] = (np.inf if la.shape != lb.shape else
                                      float(np.abs(la[:, 0] - lb[:, 0]).max()) if la.size else 0.0)
        for attr in ("steps", "rhs_evaluations"):
            out[attr + " (yaml, deck)"] = (int(a.attrs[attr]), int(b.attrs[attr]))
        out["rtol"] = float(a.attrs["rtol"])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("what", choices=("bodies", "runs"))
    ap.add_argument("files", nargs="+")
    ap.add_argument("--max-body", type=float, help="largest relative difference of the body files")
    ap.add_argument("--max-angle", type=float, help="largest joint-angle difference [rad]")
    ap.add_argument("--max-energy", type=float, help="largest energy difference, of the largest energy")
    ap.add_argument("--max-latch", type=float, help="largest latch-time difference [s]")
    a = ap.parse_args()
    if len(a.files) % 2:
        sys.exit("compare_deck_run.py: give the files in pairs, YAML route then deck route")
    bad = []
    for ya, de in zip(a.files[::2], a.files[1::2]):
        d = body_differences(ya, de) if a.what == "bodies" else run_differences(ya, de)
        print(f"{ya} / {de}")
        for key, v in d.items():
            print(f"  {key:50s} {v if isinstance(v, tuple) else f'{v:.3e}'}")
            if isinstance(v, tuple) or key == "rtol":
                continue
            limit = (a.max_body if a.what == "bodies" else a.max_angle if key.startswith("joints") else
                     a.max_energy if key.startswith("energy") else a.max_latch)
            if limit is not None and not v <= limit:
                bad.append(f"{de}: {key} differs by {v:.3e} (bound {limit:.1e})")
    for line in bad:
        print("FAIL " + line)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
