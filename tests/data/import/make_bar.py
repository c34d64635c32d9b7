#!/usr/bin/env python3
"""Writes bar_mesh.inp: a free steel bar (mm) 240 x 20 x 10 (x, y, z) on the x
axis (y, z centred) in NX x NY x NZ twenty-node bricks (C3D20), 12 x 1 x 1 unless
given. Run: python3 make_bar.py [NX [NY NZ]] (no other arguments)."""
import itertools, sys
NX = int(sys.argv[1]) if len(sys.argv) > 1 else 12
NY = int(sys.argv[2]) if len(sys.argv) > 2 else 1
NZ = int(sys.argv[3]) if len(sys.argv) > 3 else 1
L, W, H = 240.0, 20.0, 10.0
nodes = {}
def node(p):
    key = tuple(round(c, 9) for c in p)
    if key not in nodes:
        nodes[key] = len(nodes) + 1
    return nodes[key]
elements = []
for i, j, k in itertools.product(range(NX), range(NY), range(NZ)):
    x0, x1 = L * i / NX, L * (i + 1) / NX
    y0, y1 = -W / 2 + W * j / NY, -W / 2 + W * (j + 1) / NY
    z0, z1 = -H / 2 + H * k / NZ, -H / 2 + H * (k + 1) / NZ
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    corners = [node(p) for p in c]
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    mids = [node(tuple(0.5 * (c[a][d] + c[b][d]) for d in range(3))) for a, b in edges]
    elements.append(corners + mids)
with open("bar_mesh.inp", "w") as f:
    f.write("** free steel bar 240 x 20 x 10 mm, %d C3D20; written by make_bar.py\n*NODE, NSET=NALL\n" % NX)
    for p, n in sorted(nodes.items(), key=lambda kv: kv[1]):
        f.write("%d, %.6f, %.6f, %.6f\n" % (n, p[0], p[1], p[2]))
    f.write("*ELEMENT, TYPE=C3D20, ELSET=EALL\n")
    for e, conn in enumerate(elements, 1):
        f.write("%d, " % e + ", ".join(map(str, conn[:15])) + ",\n" + ", ".join(map(str, conn[15:])) + "\n")
print(len(nodes), "nodes", len(elements), "elements")
