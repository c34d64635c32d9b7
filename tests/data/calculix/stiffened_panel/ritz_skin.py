#!/usr/bin/env python3
"""Ritz solutions of the stiffened panel's bare skin as a cantilever plate
(0.8 x 0.5 m, root x = -0.4 clamped, other edges free; [0/45/-45/90]s IM6 plies
of 0.25 mm), for docs/validation.md's stiffened-panel row (not read by the tests):
  clt:  classical lamination theory with D16, D26 (w only; Legendre P_i times
        (1 + xi)^2, so w = w_x = 0 at the root). Reproduces ccx_results.txt's
        ritz_clt_skin row and tests/fe-prep/elements/closed_forms.h's
        ritzClampedPlateOmegas (all edges clamped) on this plate's D.
  fsdt: first-order shear deformation theory (w, phi_x, phi_y, each Legendre
        P_i times (1 + xi), so all three vanish at the root; Reddy, Mechanics of
        Laminated Composite Plates and Shells, 2nd ed., sec. 3.4 and ch. 7),
        transverse shear A44, A45, A55 = k sum_k Qbar_s t_k (Reddy eq. 3.4.23,
        ply shear moduli rotated as eq. 2.4.9; k = 5/6 unless given), rotary
        inertia I2. Ritz is an upper bound of FSDT's eigenvalues; the free edges'
        shear boundary layers make it converge like 1/p (p = 14, 20, 26, 34:
        f4 = 39.1516, 39.1371, 39.1290, 39.1256 Hz).
The stiffness and mass are Kronecker products of 1-D Gauss-Legendre integrals
(the laminate is uniform). Numpy and scipy only.
  python3 ritz_skin.py clt 18
  python3 ritz_skin.py fsdt 34 [k]
  python3 ritz_skin.py clt 18 --angles 0,0,90,90,90,90,0,0   (another stacking of the 8 plies)
"""
import math
import sys
import numpy as np
from numpy.polynomial import legendre as L
import scipy.linalg as sl

LX, LY, H = 0.8, 0.5, 0.002
E1, E2, NU12, NU23, G12, G23, RHO = 177e9, 10.8e9, 0.27, 0.5, 7.6e9, 3.6e9, 1600.0
G13 = G12
ANG = [0, 45, -45, 90, 90, -45, 45, 0]
t = H / len(ANG)

def laminate(kshear):
    nu21 = NU12 * E2 / E1
    d = 1 - NU12 * nu21
    Q = np.array([[E1 / d, NU12 * E2 / d, 0], [NU12 * E2 / d, E2 / d, 0], [0, 0, G12]])
    D = np.zeros((3, 3)); As = np.zeros((2, 2)); I2 = 0
    z0 = -H / 2
    for a in ANG:
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        T = np.array([[c * c, s * s, 2 * c * s], [s * s, c * c, -2 * c * s], [-c * s, c * s, c * c - s * s]])
        R = np.diag([1, 1, 2.0])
        Qb = np.linalg.inv(T) @ Q @ R @ T @ np.linalg.inv(R)
        z1 = z0 + t
        D += Qb * (z1**3 - z0**3) / 3
        I2 += RHO * (z1**3 - z0**3) / 3
        # transverse shear [yz, xz] in the laminate frame (Reddy eq. 2.4.9)
        Qs = np.array([[G23 * c * c + G13 * s * s, (G13 - G23) * c * s],
                       [(G13 - G23) * c * s, G13 * c * c + G23 * s * s]])
        As += kshear * Qs * t
        z0 = z1
    return D, As, RHO * H, I2

def basis(p, nq, clamp_power):
    """values and first/second derivatives (in xi) of (1+xi)^k P_i at Gauss points"""
    x, w = L.leggauss(nq)
    V = np.zeros((nq, p + 1)); D1 = np.zeros_like(V); D2 = np.zeros_like(V)
    f = (1 + x)**clamp_power
    f1 = clamp_power * (1 + x)**(clamp_power - 1) if clamp_power > 0 else 0 * x
    f2 = clamp_power * (clamp_power - 1) * (1 + x)**(clamp_power - 2) if clamp_power > 1 else 0 * x
    for i in range(p + 1):
        c = np.zeros(i + 1); c[i] = 1
        P = L.legval(x, c); dP = L.legval(x, L.legder(c)); d2P = L.legval(x, L.legder(c, 2))
        V[:, i] = f * P; D1[:, i] = f1 * P + f * dP; D2[:, i] = f2 * P + 2 * f1 * dP + f * d2P
    return V, D1, D2, w

def ints(A, B, w):
    return (A * w[:, None]).T @ B

def clt(p, count=10):
    D, As, I0, I2 = laminate(5 / 6)
    jx, jy = 2 / LX, 2 / LY
    Vx, D1x, D2x, wx = basis(p, p + 8, 2)
    Vy, D1y, D2y, wy = basis(p, p + 8, 0)
    # curvature components as (x-factor, y-factor) pairs
    k = [(D2x * jx * jx, Vy), (Vx, D2y * jy * jy), (2 * D1x * jx, D1y * jy)]
    K = 0
    for a in range(3):
        for b in range(3):
            if D[a, b] == 0: continue
            K = K + D[a, b] * np.kron(ints(k[a][0], k[b][0], wx), ints(k[a][1], k[b][1], wy))
    M = I0 * np.kron(ints(Vx, Vx, wx), ints(Vy, Vy, wy))
    J = LX * LY / 4
    ev = sl.eigh(K * J, M * J, eigvals_only=True, subset_by_index=[0, count - 1])
    return np.sqrt(ev) / (2 * math.pi)

def fsdt(p, kshear=5 / 6, rotary=True, count=10, py=None):
    D, As, I0, I2 = laminate(kshear)
    py = p if py is None else py
    jx, jy = 2 / LX, 2 / LY
    Vx, D1x, _, wx = basis(p, p + 6, 1)
    Vy, D1y, _, wy = basis(py, py + 6, 0)
    nx, ny = p + 1, py + 1
    n = nx * ny
    Z = (np.zeros((len(wx), nx)), np.zeros((len(wy), ny)))
    # each strain = sum of terms (field index, x-factor, y-factor); fields 0 w, 1 phi_x, 2 phi_y
    kap = [[(1, D1x * jx, Vy)], [(2, Vx, D1y * jy)], [(1, Vx, D1y * jy), (2, D1x * jx, Vy)]]
    gam = [[(0, Vx, D1y * jy), (2, Vx, Vy)], [(0, D1x * jx, Vy), (1, Vx, Vy)]]   # [yz, xz]
    K = np.zeros((3 * n, 3 * n))
    def add(C, strains):
        for a in range(len(strains)):
            for b in range(len(strains)):
                if C[a, b] == 0: continue
                for (fa, xa, ya) in strains[a]:
                    for (fb, xb, yb) in strains[b]:
                        K[fa * n:(fa + 1) * n, fb * n:(fb + 1) * n] += C[a, b] * np.kron(ints(xa, xb, wx), ints(ya, yb, wy))
    add(D, kap); add(As, gam)
    M = np.zeros_like(K)
    Mw = np.kron(ints(Vx, Vx, wx), ints(Vy, Vy, wy))
    M[:n, :n] = I0 * Mw
    r = I2 if rotary else 1e-12 * I2
    M[n:2 * n, n:2 * n] = r * Mw; M[2 * n:, 2 * n:] = r * Mw
    J = LX * LY / 4
    ev = sl.eigh(K * J, M * J, eigvals_only=True, subset_by_index=[0, count - 1])
    return np.sqrt(ev) / (2 * math.pi)

if __name__ == "__main__":
    if "--angles" in sys.argv:
        k = sys.argv.index("--angles")
        ANG = [float(a) for a in sys.argv[k + 1].split(",")]
        assert len(ANG) == 8, "8 plies of 0.25 mm"
        del sys.argv[k:k + 2]
    kind = sys.argv[1]; p = int(sys.argv[2])
    if kind == "clt":
        f = clt(p)
    else:
        k = float(sys.argv[3]) if len(sys.argv) > 3 else 5 / 6
        py = int(sys.argv[4]) if len(sys.argv) > 4 else None
        f = fsdt(p, k, py=py)
    print(kind, p, " ".join("%.5f" % v for v in f))
