#!/usr/bin/env python3
"""CalculiX deck of the laminated cantilever panel for ply stresses.

A 1 x 0.2 m cross-ply [0/90/90/0] IM6/epoxy panel (plies 0.5 mm; E1 177 GPa,
E2 = E3 10.8 GPa, G12 = G13 7.6 GPa, G23 3.6 GPa, nu12 = nu13 0.27, nu23 0.5),
the edge x = 0 clamped (all six DOF of its nodes), a 2 N downward (-z) load on
the edge x = L, spread as the consistent nodal loads of the quadratic edges
(1/6, 4/6, 1/6 per element side).

CalculiX 2.20 side: a structured mesh of NX x NY S8R shells with
*SHELL SECTION, COMPOSITE (ccx expands each into a layered C3D20R). The 90-degree
plies are written as a second material whose engineering constants are the
0-degree ones rotated by 90 degrees about z (Ex = E2, Ey = E1, nu_xy = nu21,
nu_xz = nu23, nu_yz = nu13, G_xz = G23, G_yz = G13), so that no *ORIENTATION is
needed and ccx's stresses are in global axes for every ply. *EL PRINT writes
the stresses (S) and the coordinates (COORD) of every integration point.

  python3 make_deck.py NX NY > cantilever_NX.inp ; ccx -i cantilever_NX
  python3 make_deck.py --collect cantilever_NX.dat > ccx_ply_stresses.txt

--collect averages, per ply (found from the integration point's z) and per
band of x ([0.4, 0.6] and [0.15, 0.35]: mid-length and a quarter from the
clamp, across the whole width), the stresses converted to each ply's material
axes (0 deg: s11 = sxx, s22 = syy, t12 = sxy; 90 deg: s11 = syy, s22 = sxx,
t12 = -sxy), and prints one line per band and ply.
"""
import sys

L, B, T = 1.0, 0.2, 0.0005
P = 2.0
E1, E2, G12, G13, G23, NU12, NU23 = 177e9, 10.8e9, 7.6e9, 7.6e9, 3.6e9, 0.27, 0.5
ANGLES = [0, 90, 90, 0]
BANDS = [(0.4, 0.6), (0.15, 0.35)]


def deck(nx, ny):
    dx, dy = L / nx, B / ny
    # Nodes of a structured quadratic grid: (2nx+1) x (2ny+1) minus the element centres.
    idx = {}
    nodes = []
    for j in range(2 * ny + 1):
        for i in range(2 * nx + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            idx[(i, j)] = len(nodes) + 1
            nodes.append((i * dx / 2, -B / 2 + j * dy / 2))
    out = ["*HEADING", "laminated cantilever panel, ply stresses (flexcomp)", "*NODE"]
    out += ["%d, %.10g, %.10g, 0" % (k + 1, x, y) for k, (x, y) in enumerate(nodes)]
    out.append("*ELEMENT, TYPE=S8R, ELSET=EALL")
    e = 0
    for j in range(ny):
        for i in range(nx):
            e += 1
            I, J = 2 * i, 2 * j
            c = [idx[(I, J)], idx[(I + 2, J)], idx[(I + 2, J + 2)], idx[(I, J + 2)],
                 idx[(I + 1, J)], idx[(I + 2, J + 1)], idx[(I + 1, J + 2)], idx[(I, J + 1)]]
            out.append("%d, " % e + ", ".join(str(n) for n in c))
    clamp = [idx[(0, j)] for j in range(2 * ny + 1)]
    out.append("*NSET, NSET=CLAMP")
    out += [str(n) for n in clamp]
    nu21 = NU12 * E2 / E1
    out += ["*MATERIAL, NAME=PLY0", "*ELASTIC, TYPE=ENGINEERING CONSTANTS",
            "%g, %g, %g, %g, %g, %g, %g, %g," % (E1, E2, E2, NU12, NU12, NU23, G12, G13), "%g" % G23,
            "*MATERIAL, NAME=PLY90", "*ELASTIC, TYPE=ENGINEERING CONSTANTS",
            "%g, %g, %g, %.12g, %g, %g, %g, %g," % (E2, E1, E2, nu21, NU23, NU12, G12, G23), "%g" % G13,
            "*SHELL SECTION, ELSET=EALL, COMPOSITE"]
    out += ["%g,, PLY%d" % (T, a) for a in ANGLES]
    out += ["*BOUNDARY", "CLAMP, 1, 6", "*STEP", "*STATIC", "*CLOAD"]
    for j in range(ny):
        for jj, w in ((2 * j, 1 / 6), (2 * j + 1, 4 / 6), (2 * j + 2, 1 / 6)):
            out.append("%d, 3, %.12g" % (idx[(2 * nx, jj)], -P / ny * w))
    out += ["*EL PRINT, ELSET=EALL", "S", "*EL PRINT, ELSET=EALL", "COORD", "*END STEP"]
    return "\n".join(out) + "\n"


def collect(path):
    text = open(path).read().split("\n")
    stress, coord = {}, {}
    mode = None
    for line in text:
        low = line.strip().lower()
        if low.startswith("stresses"):
            mode = stress
            continue
        if low.startswith("global coordinates") or low.startswith("coordinates"):
            mode = coord
            continue
        parts = line.split()
        if mode is None or len(parts) < 4:
            continue
        try:
            key = (int(parts[0]), int(parts[1]))
            vals = [float(v) for v in parts[2:8 if mode is stress else 5]]
        except ValueError:
            continue
        mode[key] = vals
    h = T * len(ANGLES)
    print("# band_xmin band_xmax ply angle s11 s22 t12 [Pa] points (material axes, mean over the band)")
    for (x0, x1) in BANDS:
        acc = [[0.0, 0.0, 0.0, 0] for _ in ANGLES]
        for key, s in stress.items():
            x, y, z = coord[key][:3]
            if not (x0 <= x <= x1):
                continue
            k = min(int((z + h / 2) / T), len(ANGLES) - 1)
            sxx, syy, sxy = s[0], s[1], s[3]
            v = (sxx, syy, sxy) if ANGLES[k] == 0 else (syy, sxx, -sxy)
            for c in range(3):
                acc[k][c] += v[c]
            acc[k][3] += 1
        for k, a in enumerate(acc):
            n = max(a[3], 1)
            print("%g %g %d %d %.9e %.9e %.9e %d" % (x0, x1, k, ANGLES[k], a[0] / n, a[1] / n, a[2] / n, a[3]))


if __name__ == "__main__":
    if sys.argv[1] == "--collect":
        collect(sys.argv[2])
    else:
        sys.stdout.write(deck(int(sys.argv[1]), int(sys.argv[2])))
