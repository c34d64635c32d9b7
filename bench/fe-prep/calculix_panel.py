#!/usr/bin/env python3
"""Writes a CalculiX 2.20 input for the benchmark panel: 2.0 x 1.3 m, 2 mm,
E = 159 GPa, nu = 0.38, rho = 1610, centred on the origin, structured nx x ny
eight-node quadrilaterals (S8R; ccx expands each into a C3D20R brick).

  calculix_panel.py NX NY OUT.inp
      free-free *FREQUENCY, 26 modes (6 rigid + 20 elastic).
  calculix_panel.py NX NY OUT.inp --craig-bampton R
      the Craig-Bampton equivalent of fe-prep's panel with 8 pinned
      `distributing` interfaces (points (+-0.9 / +-0.3, +-0.55, 0), the
      mid-surface nodes within R of each): step 1, *FREQUENCY with the 8 points'
      translations fixed, 8 fixed-interface modes; step 2, *SUBSTRUCTURE
      GENERATE retaining those 24 translations (the static part: one
      factorisation, one solve per retained DOF, i.e. the constraint modes'
      work; ccx writes the condensed stiffness to OUT.mtx).

The distributing coupling (RBE3) is written as *EQUATIONs on a free point
node P: the point's motion is the weighted least-squares rigid fit of the
patch translations, [u_P; theta_P] = A^-1 sum_i w_i G_i^T u_i with
G_i = [I, -skew(X_i - P)], A = sum_i w_i G_i^T G_i (MSC Nastran QRG, RBE3;
CalculiX's *DISTRIBUTING is the same fit), of which only the three
translation rows are used (fe-prep pins translations). Weights: tributary
areas (an S8R's area over its eight nodes, summed over the node's elements).
Rows are put in reduced row echelon form so each dependent DOF (first term)
is a patch translation used in no other equation; u_P stays independent, so
it can be fixed (*BOUNDARY) or retained. Prints the node, element and DOF
counts.

  ... --msh PANEL.msh
      also writes fe-prep's mesh of the same panel at equal DOF: a gmsh 2.2
      .msh (physical surface "panel") of a structured grid of mx x my
      rectangles, each cut into two three-node triangles (diagonals
      alternating in a checkerboard, so the grid has no preferred direction),
      with (mx + 1)(my + 1) as close as the grid allows to the S8R grid's node
      count (corners and mid-sides, 6 DOF each in both codes) and cells
      within 10 % of square. fe-prep reads it through `mesh: {file}` (no
      meshing inside its timed run, as CalculiX's deck). Prints its counts.
  ... --bdf PANEL.bdf
      the same grid as a Nastran bulk-data deck (free field: GRID, CTRIA3,
      PSHELL with MID3 given, i.e. DST with TS/T = 5/6, MAT1), which fe-prep
      reads with its own parser: no gmsh in its run (docs/nastran.md).
      With --msh, both files hold the same nodes and triangles."""
import argparse

import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("nx", type=int)
ap.add_argument("ny", type=int)
ap.add_argument("out")
ap.add_argument("--craig-bampton", type=float, default=None, metavar="R")
ap.add_argument("--msh", default=None)
ap.add_argument("--bdf", default=None)
args = ap.parse_args()
nx, ny, out = args.nx, args.ny, args.out
cb_radius = args.craig_bampton
L, W = 2.0, 1.3
E, NU, RHO, T = 159.0e9, 0.38, 1610.0, 0.002  # as in the *MATERIAL lines below
POINTS = [(x, y) for x in (-0.9, -0.3, 0.3, 0.9) for y in (-0.55, 0.55)]
# Node grid (2 nx + 1) x (2 ny + 1) without the quads' centre points.
ids, xy = {}, {}
lines = ["*HEADING", "fe-prep benchmark panel, S8R", "*NODE"]
n = 0
for j in range(2 * ny + 1):
    for i in range(2 * nx + 1):
        if i % 2 == 1 and j % 2 == 1:
            continue
        n += 1
        ids[(i, j)] = n
        xy[n] = (-L / 2 + L * i / (2 * nx), -W / 2 + W * j / (2 * ny))
        lines.append(f"{n}, {xy[n][0]:.12g}, {xy[n][1]:.12g}, 0.0")
weight = {}
area = L * W / (nx * ny) / 8
lines.append("*ELEMENT, TYPE=S8R, ELSET=PANEL")
e = 0
for j in range(ny):
    for i in range(nx):
        e += 1
        I, J = 2 * i, 2 * j
        c = [ids[(I, J)], ids[(I + 2, J)], ids[(I + 2, J + 2)], ids[(I, J + 2)],
             ids[(I + 1, J)], ids[(I + 2, J + 1)], ids[(I + 1, J + 2)], ids[(I, J + 1)]]
        for k in c:
            weight[k] = weight.get(k, 0.0) + area
        lines.append(f"{e}, " + ", ".join(map(str, c)))
lines += ["*MATERIAL, NAME=CFRP", "*ELASTIC", "159.0e9, 0.38", "*DENSITY", "1610.",
          "*SHELL SECTION, ELSET=PANEL, MATERIAL=CFRP", "0.002"]


def skew(d):
    return np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]])


if cb_radius is None:
    lines += ["*STEP", "*FREQUENCY, SOLVER=SPOOLES", "26", "*END STEP"]
else:
    point_nodes = []
    eqs = ["*EQUATION"]
    for p in POINTS:
        n += 1
        point_nodes.append(n)
        lines.insert(lines.index("*ELEMENT, TYPE=S8R, ELSET=PANEL"), f"{n}, {p[0]:.12g}, {p[1]:.12g}, 0.0")
        P = np.array([p[0], p[1], 0.0])
        patch = [k for k, v in xy.items() if np.hypot(v[0] - p[0], v[1] - p[1]) <= cb_radius]
        if len(patch) < 3:
            sys.exit(f"calculix_panel.py: radius {cb_radius} holds {len(patch)} nodes at {p}: coarser than the patch")
        A = np.zeros((6, 6))
        Gt = []
        for k in patch:
            G = np.hstack([np.eye(3), -skew(np.array([xy[k][0], xy[k][1], 0.0]) - P)])
            A += weight[k] * G.T @ G
            Gt.append(weight[k] * G.T)
        C = np.linalg.solve(A, np.hstack(Gt))[:3]          # u_P = C u_patch
        # Reduced row echelon form of C: pivots are the dependent patch DOFs.
        R = C.copy()
        Pm = np.eye(3)                                     # R = Pm C, u_P coefficients -Pm
        piv = []
        row = 0
        for col in range(R.shape[1]):
            if row == 3:
                break
            r = row + int(np.argmax(np.abs(R[row:, col])))
            if abs(R[r, col]) < 1e-9 * np.abs(C).max():
                continue
            R[[row, r]] = R[[r, row]]
            Pm[[row, r]] = Pm[[r, row]]
            s = R[row, col]
            R[row] /= s
            Pm[row] /= s
            for q in range(3):
                if q != row:
                    f = R[q, col]
                    R[q] -= f * R[row]
                    Pm[q] -= f * Pm[row]
            piv.append(col)
            row += 1
        for q in range(3):
            terms = [(patch[piv[q] // 3], piv[q] % 3 + 1, 1.0)]
            terms += [(patch[c // 3], c % 3 + 1, R[q, c]) for c in range(R.shape[1])
                      if c not in piv and abs(R[q, c]) > 1e-14]
            terms += [(point_nodes[-1], d + 1, -Pm[q, d]) for d in range(3) if abs(Pm[q, d]) > 1e-14]
            eqs.append(str(len(terms)))
            # CalculiX reads the first 20 characters of a number: .14g is at
            # most 20 ("-1.2345678901234e-05"); .15g made 21 and lost the
            # exponent's last digit (a 1e-5 coefficient read as 1).
            flat = [f"{t[0]}, {t[1]}, {t[2]:.14g}" for t in terms]
            for k in range(0, len(flat), 4):                # at most 12 entries a line
                eqs.append(", ".join(flat[k:k + 4]) + ("," if k + 4 < len(flat) else ""))
    lines += eqs
    lines += ["*NSET, NSET=POINTS"] + [", ".join(map(str, point_nodes))]
    lines += ["*STEP", "*FREQUENCY, SOLVER=SPOOLES", "8",
              "*BOUNDARY", "POINTS, 1, 3", "*END STEP",
              "*STEP", "*SUBSTRUCTURE GENERATE, SOLVER=SPOOLES",
              "*BOUNDARY, OP=NEW",
              "*RETAINED NODAL DOFS, SORTED=NO", "POINTS, 1, 3",
              "*SUBSTRUCTURE MATRIX OUTPUT, STIFFNESS=YES",
              "*END STEP"]
open(out, "w").write("\n".join(lines) + "\n")
shell = 6 * (n - (8 if cb_radius is not None else 0))
print(f"{n} nodes, {e} S8R elements, {shell} shell DOF")

if args.msh or args.bdf:
    target = (2 * nx + 1) * (2 * ny + 1) - nx * ny
    my0 = np.sqrt(target * W / L)
    best = None
    for my in range(max(1, int(0.85 * my0)), int(1.15 * my0) + 2):
        mx = max(1, round(target / (my + 1)) - 1)
        if not 0.9 <= (L / mx) / (W / my) <= 1.1:
            continue
        cand = (abs((mx + 1) * (my + 1) - target), mx, my)
        best = cand if best is None or cand < best else best
    _, mx, my = best
    grid = [(j * (mx + 1) + i + 1, -L / 2 + L * i / mx, -W / 2 + W * j / my)
            for j in range(my + 1) for i in range(mx + 1)]
    tris = []
    for j in range(my):
        for i in range(mx):
            a = j * (mx + 1) + i + 1
            b, c, d = a + 1, a + mx + 2, a + mx + 1          # counter-clockwise a b c d
            tris += ((a, b, c), (a, c, d)) if (i + j) % 2 == 0 else ((a, b, d), (b, c, d))
    if args.msh:
        with open(args.msh, "w") as f:
            f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"panel\"\n$EndPhysicalNames\n")
            f.write(f"$Nodes\n{len(grid)}\n")
            f.write("".join(f"{g} {x:.12g} {y:.12g} 0\n" for g, x, y in grid))
            f.write(f"$EndNodes\n$Elements\n{len(tris)}\n")
            f.write("".join(f"{t + 1} 2 2 1 1 {a} {b} {c}\n" for t, (a, b, c) in enumerate(tris)))
            f.write("$EndElements\n")
    if args.bdf:
        # The material and thickness of the S8R deck; PSHELL's MID3 = MID1
        # selects fe-prep's DST (transverse shear, TS/T blank = 5/6), the
        # element the .msh run's `element: dst` region gives.
        with open(args.bdf, "w") as f:
            f.write("$ fe-prep benchmark panel (bench/fe-prep/calculix_panel.py)\nBEGIN BULK\n")
            f.write(f"MAT1,1,{E:.12e},,{NU:.12e},{RHO:.12e}\n")
            f.write(f"PSHELL,1,1,{T:.12e},1,1.0,1\n")
            f.write("".join(f"GRID,{g},,{x:.12g},{y:.12g},0.0\n" for g, x, y in grid))
            f.write("".join(f"CTRIA3,{t + 1},1,{a},{b},{c}\n" for t, (a, b, c) in enumerate(tris)))
            f.write("ENDDATA\n")
    print(f"{(mx + 1) * (my + 1)} nodes, {2 * mx * my} triangles ({mx} x {my}), {6 * (mx + 1) * (my + 1)} shell DOF")
