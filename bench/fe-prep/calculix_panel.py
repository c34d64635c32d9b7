#!/usr/bin/env python3
"""Writes a CalculiX input (*FREQUENCY, S8R shells) for the benchmark panel:
2.0 x 1.3 m, 2 mm, E = 159 GPa, nu = 0.38, rho = 1610, free-free, centred on
the origin, structured nx x ny eight-node quadrilaterals. Asks for 26 modes
(6 rigid + 20 elastic). Usage: calculix_panel.py NX NY OUT.inp"""
import sys

nx, ny, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
L, W = 2.0, 1.3
# Node grid (2 nx + 1) x (2 ny + 1) without the quads' centre points.
ids = {}
lines = ["*HEADING", "fe-prep benchmark panel, S8R, free-free", "*NODE"]
n = 0
for j in range(2 * ny + 1):
    for i in range(2 * nx + 1):
        if i % 2 == 1 and j % 2 == 1:
            continue
        n += 1
        ids[(i, j)] = n
        lines.append(f"{n}, {-L / 2 + L * i / (2 * nx):.12g}, {-W / 2 + W * j / (2 * ny):.12g}, 0.0")
lines.append("*ELEMENT, TYPE=S8R, ELSET=PANEL")
e = 0
for j in range(ny):
    for i in range(nx):
        e += 1
        I, J = 2 * i, 2 * j
        c = [ids[(I, J)], ids[(I + 2, J)], ids[(I + 2, J + 2)], ids[(I, J + 2)],
             ids[(I + 1, J)], ids[(I + 2, J + 1)], ids[(I + 1, J + 2)], ids[(I, J + 1)]]
        lines.append(f"{e}, " + ", ".join(map(str, c)))
lines += ["*MATERIAL, NAME=CFRP", "*ELASTIC", "159.0e9, 0.38", "*DENSITY", "1610.",
          "*SHELL SECTION, ELSET=PANEL, MATERIAL=CFRP", "0.002",
          "*STEP", "*FREQUENCY, SOLVER=SPOOLES", "26", "*END STEP"]
open(out, "w").write("\n".join(lines) + "\n")
print(f"{n} nodes, {e} S8R elements, {6 * n} shell DOF")
