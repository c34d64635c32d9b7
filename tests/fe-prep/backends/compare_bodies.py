#!/usr/bin/env python3
"""The serial program's body (fe-prep --backend serial) against the PETSc
program's (fe-prep --backend petsc) of the same input: exit 0 when they agree
within the bounds below, 1 with the differences otherwise.

  compare_bodies.py SERIAL.h5 PETSC.h5 [--shifted]

--shifted: the body had rigid motions left free, so both eigen-solves
shift-inverted about sigma = -1 (rad/s)^2 (ModalRequest::shift).

Bounds (both eigen-solvers stop at a relative residual of 1e-10, the
ModalRequest default; the two factorisations differ in their pivot order only):
- eigenvalues: 1e-9 relative. An eigenvalue's error is of the order of the
  residual's square times lambda over the gap, far below 1e-10; the PETSc path
  deflates the rigid motions of shell bodies and the serial one removes them
  after the solve, which measured 9e-12..1.8e-11 apart (docs/fe-prep.md).
  --shifted: the shifted operator (K + M)^-1 has its largest eigenvalues,
  the rigid ones, at 1, an elastic mode's at 1 / (lambda + 1): the rounding
  of one solve, a few eps ||OP||, is a few eps (lambda + 1) relative to that
  mode's, so neither solver resolves it below ~1e-15 lambda (eps times the
  factor's growth, ~10; a stiff imported solid at lambda ~ 1e11 (rad/s)^2:
  1e-4; measured 3.8e-7 at 5.1e9). The bound is max(1e-9, 1e-15 lambda).
- shapes (up to sign, per mode, against the mode's largest entry): a mode's
  error is bounded by the residual over its relative gap to the next
  eigenvalue (Davis-Kahan): 1e-10 / gap, times 100 for the two solves'
  rounding; the bound is computed per mode from the eigenvalues.
- massless DOF (a shell node's drilling rotation, /mass/nodal zero for it):
  the shape bound times 1e4, at most 1e-2. No mass and no stress depends on
  them; they follow from K alone through the drilling penalty, 1e-4 of the
  smallest bending stiffness (fc::fe::shellTriangle's default), so a
  perturbation of the solve reaches them amplified by up to 1e4. Measured on
  the static correction's attachment modes (deck_static_correction): the
  massive DOF within 1.3e-9 of each other, the drilling rotation at the load
  points 2.6e-6..1.3e-5 (their own bound 1.8e-6 before the factor).
- mass, centre, inertia, nodal masses: 1e-12 relative (no solver in them: the
  same element kernels and sums, in another order).
- Craig-Bampton fixed-interface coordinates, interface shapes and static
  compliances: as the shapes (they are linear in them or in a direct solve).
"""
import sys

import h5py
import numpy as np


def main(a_path, b_path, shifted=False):
    a, b = h5py.File(a_path, "r"), h5py.File(b_path, "r")
    bad = []

    def rel(x, y):
        return float(np.max(np.abs(x - y))) / max(float(np.max(np.abs(y))), 1e-300)

    la, lb = a["modes/eigenvalues"][()], b["modes/eigenvalues"][()]
    if la.shape != lb.shape:
        print(f"mode counts differ: {la.shape} against {lb.shape}")
        return 1
    ev_bound = np.maximum(1e-9, 1e-15 * np.abs(lb)) if shifted else np.full(len(lb), 1e-9)
    ev = np.abs(la - lb) / np.abs(lb)
    print(f"eigenvalues: {len(la)}, largest relative difference {np.max(ev):.2e} "
          f"(bound {np.min(ev_bound):.1e}..{np.max(ev_bound):.1e})")
    if not np.all(ev <= ev_bound):
        bad.append("eigenvalues")
    # Per-mode shape bound from the relative gap to the nearest other eigenvalue.
    lam = np.abs(lb)
    gaps = np.array([min([abs(lb[j] - lb[k]) / lam[j] for k in range(len(lb)) if k != j] or [1.0])
                     for j in range(len(lb))])
    bound = np.minimum(100 * np.maximum(1e-10, ev_bound / 10) / gaps, 1e-2)
    sa, sb = a["modes/shapes"][()], b["modes/shapes"][()]
    signs = np.sign([np.sum(sa[j] * sb[j]) for j in range(len(lb))])
    # (n_nodes, 6): which DOF carry mass (translations: the nodal mass;
    # rotations: the rotary inertia about that axis).
    m = b["mass/nodal"][()]
    massive = np.concatenate([np.repeat(m[:, :1] > 0, 3, axis=1), m[:, 1:4] > 0], axis=1)
    worst = worst_massless = 0.0
    for j in range(len(lb)):
        diff = np.abs(signs[j] * sa[j] - sb[j]) / max(float(np.max(np.abs(sb[j]))), 1e-300)
        d = float(np.max(diff[massive], initial=0.0))
        worst = max(worst, d / bound[j])
        if not d <= bound[j]:
            bad.append(f"shape {j + 1}: {d:.2e} > {bound[j]:.2e}")
        dz, bz = float(np.max(diff[~massive], initial=0.0)), min(1e4 * bound[j], 1e-2)
        worst_massless = max(worst_massless, dz / bz)
        if not dz <= bz:
            bad.append(f"shape {j + 1}, massless DOF: {dz:.2e} > {bz:.2e}")
    print(f"shapes: largest difference / its bound {worst:.2e} (massless DOF: {worst_massless:.2e})")

    def compare(name, bound_, per_mode=False, scale=None):
        if name not in a and name not in b:
            return
        if (name in a) != (name in b):
            bad.append(f"{name} in one file only")
            return
        x, y = a[name][()], b[name][()]
        if per_mode:
            x = (signs.reshape((-1,) + (1,) * (x.ndim - 1))) * x
        d = rel(x, y) if scale is None else float(np.max(np.abs(x - y))) / scale
        print(f"{name}: {d:.2e} (bound {bound_:.1e})")
        if not d <= bound_:
            bad.append(f"{name}: {d:.2e} > {bound_:.1e}")

    for n in ["inertia/mass", "inertia/center_of_mass", "inertia/tensor", "mass/nodal"]:
        compare(n, 1e-12)
    shape_bound = float(np.max(bound))
    compare("modes/fixed_interface_coordinates", shape_bound, per_mode=True)
    # Interfaces against the largest value over all of them: a held
    # interface's shapes and compliances are rounding about zero.
    names = list(b.get("interfaces", {}))
    def largest(key):
        v = [np.max(np.abs(b[f"interfaces/{i}/{key}"][()])) for i in names if f"interfaces/{i}/{key}" in b]
        return max(v) if v else 1.0
    for i in names:
        compare(f"interfaces/{i}/shapes", shape_bound, per_mode=True, scale=largest("shapes"))
        compare(f"interfaces/{i}/static_compliance", 1e-9, scale=largest("static_compliance"))
    # Modal geometric stiffness K_c = Phi^T K_G(u_c) Phi: per case, both mode
    # indices flipped with the shapes; bound twice the shapes' (a product of
    # two shapes, the static responses u_c solved to rounding).
    S = np.outer(signs, signs)
    for name in ["geometric_stiffness/matrices"] + [f"geometric_stiffness/interfaces/{i}/matrices"
                                                    for i in b.get("geometric_stiffness/interfaces", {})]:
        if (name in a) != (name in b):
            bad.append(f"{name} in one file only")
        elif name in b:
            x, y = a[name][()] * S, b[name][()]
            d = float(np.max(np.abs(x - y))) / max(float(np.max(np.abs(y))), 1e-300)
            print(f"{name}: {d:.2e} (bound {2 * shape_bound:.1e})")
            if not d <= 2 * shape_bound:
                bad.append(f"{name}: {d:.2e} > {2 * shape_bound:.1e}")
    if bad:
        print("DIFFERENT: " + "; ".join(bad))
        return 1
    print("same body")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2], "--shifted" in sys.argv[3:]))
