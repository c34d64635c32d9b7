#!/usr/bin/env python3
"""Writes fitting_mesh.inp: an L-shaped fitting (mm) in 20-node bricks (C3D20R),
a base plate 40 x 20 x 5 (x, y, z) and a lug 5 thick standing on it to z = 25,
meshed on the break lines below. Run: python3 make_fitting.py (no arguments)."""
import itertools

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
cells2 = []
for (i, j, k) in cells:
    x0, x1 = xb[i], xb[i + 1]
    if i != 1:
        cells2 += [((x0, mid(x0, x1)), (yb[j], yb[j + 1]), (zb[k], zb[k + 1])),
                   ((mid(x0, x1), x1), (yb[j], yb[j + 1]), (zb[k], zb[k + 1]))]
    else:
        cells2.append(((x0, x1), (yb[j], yb[j + 1]), (zb[k], zb[k + 1])))

nodes = {}
def node(p):
    key = tuple(round(c, 9) for c in p)
    if key not in nodes:
        nodes[key] = len(nodes) + 1
    return nodes[key]

elements = []
for (x0, x1), (y0, y1), (z0, z1) in cells2:
    c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    corners = [node(p) for p in c]
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    mids = [node(tuple(mid(c[a][d], c[b][d]) for d in range(3))) for a, b in edges]
    elements.append(corners + mids)

with open("fitting_mesh.inp", "w") as f:
    f.write("** L-shaped fitting, mm; written by make_fitting.py\n*NODE, NSET=NALL\n")
    for p, n in sorted(nodes.items(), key=lambda kv: kv[1]):
        f.write(f"{n}, {p[0]:.6f}, {p[1]:.6f}, {p[2]:.6f}\n")
    f.write("*ELEMENT, TYPE=C3D20R, ELSET=EALL\n")
    for e, conn in enumerate(elements, 1):
        f.write(f"{e}, " + ", ".join(map(str, conn[:15])) + ",\n" + ", ".join(map(str, conn[15:])) + "\n")
    # the base's bottom face at the two ends (bolt pads) and the lug's top face
    pads = [n for p, n in nodes.items() if p[2] == 0.0 and abs(p[0]) >= 10.0]
    top = [n for p, n in nodes.items() if p[2] == 25.0]
    for name, ids in (("PADS", pads), ("LUGTOP", top)):
        f.write(f"*NSET, NSET={name}\n")
        for i in range(0, len(ids), 8):
            f.write(", ".join(map(str, ids[i:i + 8])) + "\n")
print(len(nodes), "nodes", len(elements), "elements")
