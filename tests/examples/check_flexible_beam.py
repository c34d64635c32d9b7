"""Checks examples/flexible-beam against Euler-Bernoulli closed forms (check_flexible_beam.py out).

From section-prep's tube: EI = K[4,4] of /stiffness/timoshenko (bending about
x2) and mu = /mass/per_length. A clamped-free beam of length L has
f1 = (1.87510407^2 / 2 pi) sqrt(EI / (mu L^4)) and, under its own weight, a
static tip deflection mu g L^4 / (8 EI). Released straight, a damped single
mode overshoots to (1 + exp(-pi zeta / sqrt(1 - zeta^2))) times the static value.
Tolerances: fe-prep's Timoshenko elements with lumped masses and shear
flexibility sit 0.2 % below f1 and 0.2 % above the static deflection here
(the shear part alone is mu g L^2 / (2 GA) = 0.013 %); 1 % leaves room for
that and nothing more. The overshoot includes the higher modes' share (mode 3
rings at 167 Hz): 3 %.
"""
import math
import sys

import h5py
import numpy as np

from example_checks import attr, check, finish

out = sys.argv[1]
L, g, zeta = 1.0, 9.81, 0.05

with h5py.File(f"{out}/tube.h5", "r") as s:
    EI = s["stiffness/timoshenko"][4, 4]
    mu = s["mass/per_length"][()]
f1 = 1.87510407 ** 2 / (2 * math.pi) * math.sqrt(EI / (mu * L ** 4))
static = mu * g * L ** 4 / (8 * EI)
with h5py.File(f"{out}/beam.h5", "r") as b:
    f_fe = b["modes/frequencies_hz"][0]
    tip_shapes = b["interfaces/tip/shapes"][:, :3]
check(abs(f_fe - f1) < 0.01 * f1, f"fe-prep f1 {f_fe:.4f} Hz, Euler-Bernoulli {f1:.4f} Hz")
with h5py.File(f"{out}/beam-run.h5", "r") as r:
    check(attr(r, "status") == "completed", f"status {attr(r, 'status')}")
    w = r["bodies/beam/modal_coordinates"][:]
tip = w @ tip_shapes[: w.shape[1]]
final = -tip[-1, 2]
check(abs(final - static) < 0.01 * static, f"tip deflection at the end {final * 1e3:.4f} mm, static {static * 1e3:.4f} mm")
peak = -tip[:, 2].min()
overshoot = 1 + math.exp(-math.pi * zeta / math.sqrt(1 - zeta * zeta))
check(abs(peak / static - overshoot) < 0.03 * overshoot,
      f"first swing {peak * 1e3:.4f} mm = {peak / static:.3f} x static, single damped mode {overshoot:.3f}")
finish()
