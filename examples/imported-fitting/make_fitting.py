#!/usr/bin/env python3
"""Writes fitting_mesh.inp: an L-shaped fitting (mm) in 20-node bricks (C3D20R),
a base plate 40 x 20 x 5 (x, y, z) and a lug 5 thick standing on it to z = 25,
meshed on the break lines below. Run: python3 make_fitting.py (no arguments)."""
import itertools

from brick_deck import BrickMesh

xb = [-20.0, -2.5, 2.5, 20.0]
yb = [-10.0, 0.0, 10.0]
zb = [0.0, 5.0, 15.0, 25.0]

def mid(a, b):
    return 0.5 * (a + b)

cells = []
for i, j, k in itertools.product(range(len(xb) - 1), range(len(yb) - 1), range(len(zb) - 1)):
    if k >= 1 and i != 1:      # above the base only the lug column (x in [-2.5, 2.5])
        continue
    cells.append((i, j, k))
# split the base's outer cells in x once more so that the plate bends with two elements per side
mesh = BrickMesh()
for (i, j, k) in cells:
    x0, x1 = xb[i], xb[i + 1]
    y, z = (yb[j], yb[j + 1]), (zb[k], zb[k + 1])
    if i != 1:
        mesh.add_brick((x0, mid(x0, x1)), y, z)
        mesh.add_brick((mid(x0, x1), x1), y, z)
    else:
        mesh.add_brick((x0, x1), y, z)

# the base's bottom face at the two ends (bolt pads) and the lug's top face
pads = [n for p, n in mesh.nodes.items() if p[2] == 0.0 and abs(p[0]) >= 10.0]
top = [n for p, n in mesh.nodes.items() if p[2] == 25.0]
mesh.write("fitting_mesh.inp", "L-shaped fitting, mm; written by make_fitting.py", "C3D20R",
           [("PADS", pads), ("LUGTOP", top)])
