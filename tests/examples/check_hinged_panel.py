"""Checks examples/hinged-panel (check_hinged_panel.py out): the latch fires
at 90 degrees, holds the hinge there, and the panel's modes ring after it.

Before the latch the panel turns as one piece under the spring's torque
f(angle) (linear from 1.5 N m at 0 to 0.5 N m at -1.6 rad): the work of the
spring up to the latch equals the kinetic energy there plus the strain energy
(energy balance of the run, checked to 1e-6 J). After the latch the angle stays
within the constraint tolerance of -pi/2. A bad --animation argument fails
before the run with a message naming it.
"""
import os
import re
import subprocess
import sys

import h5py
import numpy as np

from example_checks import attr, check, finish

out = sys.argv[1]

with h5py.File(f"{out}/hinged-panel.h5", "r") as f:
    check(attr(f, "status") == "completed", f"status {attr(f, 'status')}")
    events = str(attr(f, "events"))
    hit = re.search(r"t=([0-9.eE+-]+): joint hinge crossed", events)
    check(hit is not None and "lock hinge" in events, f"event log: {events.strip()}")
    t = f["time"][:]
    angle = f["joints/hinge/angle"][:]
    w = f["bodies/panel/modal_coordinates"][:]
    balance = attr(f, "energy_balance_error")
    check(balance < 1e-6, f"energy balance error {balance:.2e} J")
    if hit:
        t_latch = float(hit.group(1))
        after = t > t_latch + 1e-9
        held = np.abs(angle[after] + np.pi / 2).max()
        check(held < 1e-6, f"hinge held at -pi/2 after the latch: largest deviation {held:.2e} rad")
        ring = np.abs(w[after]).max(axis=0)
        check(ring[0] > 1e-4, f"first mode rings after the latch: |w1| up to {ring[0]:.2e} kg^1/2 m")
# A bad --animation target fails at once, before the run, naming the folder.
p = subprocess.run(["mbs-run", "scene.yaml", "-o", f"{out}/bad.h5", "--animation", "/nonexistent/x.pvd", "-q"],
                   capture_output=True, text=True)
check(p.returncode != 0 and "/nonexistent/x" in p.stderr and not os.path.exists(f"{out}/bad.h5"),
      f"unwritable animation folder: exit {p.returncode}, '{p.stderr.strip()}', no results written")
p = subprocess.run(["mbs-run", "scene.yaml", "-o", f"{out}/bad.h5", "--animation", f"{out}/x.vtk", "-q"],
                   capture_output=True, text=True)
check(p.returncode != 0 and ".pvd" in p.stderr and not os.path.exists(f"{out}/bad.h5"),
      f"animation name not .pvd: exit {p.returncode}, '{p.stderr.strip().splitlines()[0] if p.stderr.strip() else ''}'")
finish()
