#!/usr/bin/env python3
"""Writes the .msh seeds of the format fuzzer: a 0.6 m x 0.3 m plate of 7 x 4
nodes (36 triangles, physical surface "skin"), a stringer along y = 0.15 m (6
line elements, physical curve "stringer") and the root edge x = 0 (3 line
elements, physical curve "root"), in gmsh's MSH 2.2 and 4.1 ASCII formats.
Written for this repository (no gmsh needed); gmsh 4.8 reads both."""
nx, ny, lx, ly = 7, 4, 0.6, 0.3
nodes = [(j * nx + i + 1, lx * i / (nx - 1), ly * j / (ny - 1)) for j in range(ny) for i in range(nx)]
def nid(i, j): return j * nx + i + 1
tris = []
for j in range(ny - 1):
    for i in range(nx - 1):
        a, b, c, d = nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)
        tris += [(a, b, c), (a, c, d)]
js = 1  # y = 0.1 m row (ly / 3): the stringer
stringer = [(nid(i, js), nid(i + 1, js)) for i in range(nx - 1)]
root = [(nid(0, j), nid(0, j + 1)) for j in range(ny - 1)]

with open("plate22.msh", "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n1 1 \"root\"\n1 2 \"stringer\"\n2 3 \"skin\"\n$EndPhysicalNames\n")
    f.write("$Nodes\n%d\n" % len(nodes))
    for n, x, y in nodes:
        f.write("%d %.17g %.17g 0\n" % (n, x, y))
    f.write("$EndNodes\n$Elements\n%d\n" % (len(tris) + len(stringer) + len(root)))
    k = 1
    for a, b in root:
        f.write("%d 1 2 1 1 %d %d\n" % (k, a, b)); k += 1
    for a, b in stringer:
        f.write("%d 1 2 2 2 %d %d\n" % (k, a, b)); k += 1
    for a, b, c in tris:
        f.write("%d 2 2 3 1 %d %d %d\n" % (k, a, b, c)); k += 1
    f.write("$EndElements\n")

with open("plate41.msh", "w") as f:
    f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n1 1 \"root\"\n1 2 \"stringer\"\n2 3 \"skin\"\n$EndPhysicalNames\n")
    f.write("$Entities\n0 2 1 0\n")
    f.write("1 0 0 0 0 %g 0 1 1 0\n" % ly)
    f.write("2 0 0.1 0 %g 0.1 0 1 2 0\n" % lx)
    f.write("1 0 0 0 %g %g 0 1 3 0\n" % (lx, ly))
    f.write("$EndEntities\n")
    f.write("$Nodes\n1 %d 1 %d\n2 1 0 %d\n" % (len(nodes), len(nodes), len(nodes)))
    for n, _, _ in nodes:
        f.write("%d\n" % n)
    for _, x, y in nodes:
        f.write("%.17g %.17g 0\n" % (x, y))
    f.write("$EndNodes\n")
    ne = len(tris) + len(stringer) + len(root)
    f.write("$Elements\n3 %d 1 %d\n" % (ne, ne))
    k = 1
    f.write("1 1 1 %d\n" % len(root))
    for a, b in root:
        f.write("%d %d %d\n" % (k, a, b)); k += 1
    f.write("1 2 1 %d\n" % len(stringer))
    for a, b in stringer:
        f.write("%d %d %d\n" % (k, a, b)); k += 1
    f.write("2 1 2 %d\n" % len(tris))
    for a, b, c in tris:
        f.write("%d %d %d %d\n" % (k, a, b, c)); k += 1
    f.write("$EndElements\n")
