"""Checks examples/pendulum against closed forms (run in the example folder: check_pendulum.py out).

A uniform rod of mass m, length L and diameter d released from horizontal on
a frictionless hinge is a physical pendulum of amplitude 90 degrees: with
I = m (L^2/3 + d^2/16) about the hinge and the centre of mass at L/2, it
reaches the bottom after a quarter period, t = sqrt(I / (m g L/2)) K(sin 45 deg)
(complete elliptic integral of the first kind, K = 1.8540746773013719), with
angular velocity sqrt(m g L / I) (energy). The event that enables the spring
fires at that crossing.
"""
import math
import re
import sys

import h5py
import numpy as np

from example_checks import attr, check, finish

out = sys.argv[1]
m, L, d, g = 1.0, 1.0, 0.02, 9.81
I = m * (L * L / 3 + d * d / 16)
t_bottom = math.sqrt(I / (m * g * L / 2)) * 1.8540746773013719

with h5py.File(f"{out}/pendulum.h5", "r") as f:
    check(attr(f, "status") == "completed", f"status {attr(f, 'status')}")
    events = str(attr(f, "events"))
    hit = re.search(r"t=([0-9.eE+-]+): joint hinge crossed", events)
    check(hit is not None, f"event log: {events.strip()}")
    # rtol 1e-8 and the crossing located to machine precision: 1e-7 relative.
    if hit:
        t_event = float(hit.group(1))
        check(abs(t_event - t_bottom) < 1e-7 * t_bottom, f"bottom reached at {t_event:.10f} s, closed form {t_bottom:.10f} s")
    t = f["time"][:]
    angle = f["joints/hinge/angle"][:]
    omega = f["bodies/rod/angular_velocity"][:, 1]
    # Energy before the event at every output: 1/2 I w^2 = m g (L/2) sin(angle).
    before = t < t_bottom
    w_energy = np.sqrt(m * g * L * np.sin(angle[before]) / I)
    err = np.abs(np.abs(omega[before]) - w_energy).max()
    check(err < 1e-6, f"angular velocity vs energy before the catch: largest difference {err:.2e} rad/s")
    # After the catch the damper takes energy out: no output beyond the bottom
    # angle's swing energy, and the energy balance of the run holds.
    balance = attr(f, "energy_balance_error")
    check(balance < 1e-6, f"energy balance error {balance:.2e} J")
    dissipated = f["energy/dissipated"][-1]
    check(dissipated > 0.1, f"the damper dissipated {dissipated:.3f} J after the catch")
finish()
