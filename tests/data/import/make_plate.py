#!/usr/bin/env python3
"""Writes plate_mesh.inp: a free steel plate (mm) 200 x 100 x 2 (x, y, z), mid-surface
z = 0, centred, in NX x NY x 1 twenty-node bricks (C3D20), 20 x 10 unless given.
Run: python3 make_plate.py [NX NY]."""
import itertools, sys
NX = int(sys.argv[1]) if len(sys.argv) > 1 else 20
NY = int(sys.argv[2]) if len(sys.argv) > 2 else 10
L, W, H = 200.0, 100.0, 2.0
nodes = {}
def node(p):
    key = tuple(round(c, 9) for c in p)
    if key not in nodes:
        nodes[key] = len(nodes) + 1
    return nodes[key]
elements = []
for i, j in itertools.product(range(NX), range(NY)):
    x0, x1 = -L / 2 + L * i / NX, -L / 2 + L * (i + 1) / NX
    y0, y1 = -W / 2 + W * j / NY, -W / 2 + W * (j + 1) / NY
    z0, z1 = -H / 2, H / 2
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    corners = [node(p) for p in c]
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    mids = [node(tuple(0.5 * (c[a][d] + c[b][d]) for d in range(3))) for a, b in edges]
    elements.append(corners + mids)
with open("plate_mesh.inp", "w") as f:
    f.write("** free steel plate 200 x 100 x 2 mm, %d x %d C3D20; written by make_plate.py\n*NODE, NSET=NALL\n" % (NX, NY))
    for p, n in sorted(nodes.items(), key=lambda kv: kv[1]):
        f.write("%d, %.6f, %.6f, %.6f\n" % (n, p[0], p[1], p[2]))
    f.write("*ELEMENT, TYPE=C3D20, ELSET=EALL\n")
    for e, conn in enumerate(elements, 1):
        f.write("%d, " % e + ", ".join(map(str, conn[:15])) + ",\n" + ", ".join(map(str, conn[15:])) + "\n")
print(len(nodes), "nodes", len(elements), "elements")
