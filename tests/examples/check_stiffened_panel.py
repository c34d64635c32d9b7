"""Checks examples/stiffened-panel (check_stiffened_panel.py out): the body from
panel.geo's regions is one body of skin triangles and stringer beams sharing
nodes, its mass is the closed form of its parts, and the hinged run completes
with its energy balanced.

Mass: skin 0.8 x 0.5 m x (1600 kg/m^3 x 2 mm + 0.2 kg/m^2 paint), two
0.8 m aluminium blades 4 x 25 mm (2700 kg/m^3), a 0.15 kg fitting: 1.942 kg,
to rounding (1e-12: the moment-consistent nodal masses keep the total exactly).
"""
import sys

import h5py
import numpy as np

from example_checks import attr, check, finish

out = sys.argv[1]

with h5py.File(f"{out}/panel.h5", "r") as f:
    tri = f["mesh/triangles"][:]
    beams = f["mesh/beams"][:]
    check(len(tri) > 0 and len(beams) > 0, f"{len(tri)} triangles and {len(beams)} beams in one body")
    check(np.isin(beams, tri).all(), "every stringer node is a skin node")
    mass = float(f["inertia/mass"][()])
    exact = 0.8 * 0.5 * (1600 * 0.002 + 0.2) + 2 * 0.8 * 2700 * 0.004 * 0.025 + 0.15
    check(abs(mass - exact) < 1e-12 * exact, f"mass {mass:.15g} kg, parts {exact:.15g} kg")

with h5py.File(f"{out}/stiffened-panel.h5", "r") as f:
    check(attr(f, "status") == "completed", f"status {attr(f, 'status')}")
    balance = attr(f, "energy_balance_error")
    check(balance < 1e-6, f"energy balance error {balance:.2e} J")
finish()
