#!/usr/bin/env python3
"""The curved composite panel of tests/fe-prep/test_general_mesh.cpp, side by side
with CalculiX 2.20 (provenance of the fixtures here).

A cylindrical segment, radius R = 0.5 m about the z axis, arc -30 .. +30 deg
(0.524 m), height H = 0.5 m, [0/90/90/0] IM6/SC1081 plies of 0.5 mm, clamped
along its arc edge z = 0. Two lay-ups: 0 deg along the axis (z) and 0 deg along
the arc (hoop).

Writes
  panel.msh           gmsh 2.2 ASCII, NQ x NQ bilinear quadrilaterals on the
                      surface (fe-prep splits each into two triangles), groups
                      "shell" (surface) and "root" (curve z = 0)
  ccx_axial.inp, ccx_hoop.inp
                      CalculiX decks: NC x NC S8R elements (midside nodes on the
                      exact arc), *SHELL SECTION, COMPOSITE with a cylindrical
                      *ORIENTATION (local 1 radial, 2 hoop, 3 axial) and the ply
                      material's engineering constants permuted so that its
                      fibre lies along the local hoop or axial direction.
Run:  python3 make_meshes.py && ccx ccx_axial && ccx ccx_hoop
and keep the frequencies of the .dat files in ccx_frequencies.txt.
"""
import math

R, H, HALF = 0.5, 0.5, math.radians(30.0)
NQ = 64   # fe-prep quadrilaterals per side
NC = 24   # CalculiX S8R per side
EL, ET, NULT, NUTT, GLT, GTT, RHO = 177e9, 10.8e9, 0.27, 0.5, 7.6e9, 8.504e9, 1600.0
PLY = 0.0005


def point(s, t):  # s in [0, 1] along the arc, t in [0, 1] along z
    a = -HALF + 2 * HALF * s
    return (R * math.cos(a), R * math.sin(a), H * t)


def write_msh():
    n = NQ + 1
    idx = lambda i, j: j * n + i + 1
    with open("panel.msh", "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n2\n1 2 "root"\n2 1 "shell"\n$EndPhysicalNames\n')
        f.write("$Nodes\n%d\n" % (n * n))
        for j in range(n):
            for i in range(n):
                x, y, z = point(i / NQ, j / NQ)
                f.write("%d %.17g %.17g %.17g\n" % (idx(i, j), x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % (NQ * NQ + NQ))
        e = 1
        for i in range(NQ):  # root line elements (physical 2, elementary curve 1)
            f.write("%d 1 2 2 1 %d %d\n" % (e, idx(i, 0), idx(i + 1, 0)))
            e += 1
        for j in range(NQ):  # quads, counter-clockwise about the outward normal (radial)
            for i in range(NQ):
                f.write("%d 3 2 1 1 %d %d %d %d\n" % (e, idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)))
                e += 1
        f.write("$EndElements\n")


def write_ccx(name, zero):
    """zero: the 0-degree direction, axial or hoop; the 90-degree plies the other.
    Each column of elements (one hoop interval) has two rectangular
    *ORIENTATIONs at its centre angle phi, local 1 along the axis (0, 0, 1) or
    along the hoop tangent (-sin phi, cos phi, 0); each layer of the column's
    *SHELL SECTION, COMPOSITE names the one its fibres follow. Within a column
    the tangent turns by +-1.25 deg about the centre (cos^4 = 0.9995)."""
    other = "hoop" if zero == "axial" else "axial"
    n = 2 * NC + 1
    nodes = {}
    for j in range(n):
        for i in range(n):
            if i % 2 == 1 and j % 2 == 1:
                continue  # S8R: no centre node
            nodes[(i, j)] = len(nodes) + 1
    with open(name + ".inp", "w") as f:
        f.write("** curved [0/90/90/0] panel, 0 deg along the %s (make_meshes.py)\n*NODE, NSET=NALL\n" % zero)
        for (i, j), k in nodes.items():
            x, y, z = point(i / (2 * NC), j / (2 * NC))
            f.write("%d, %.17g, %.17g, %.17g\n" % (k, x, y, z))
        for I in range(NC):
            f.write("*ELEMENT, TYPE=S8R, ELSET=COL%d\n" % I)
            for J in range(NC):
                i, j = 2 * I, 2 * J
                c = [nodes[(i, j)], nodes[(i + 2, j)], nodes[(i + 2, j + 2)], nodes[(i, j + 2)],
                     nodes[(i + 1, j)], nodes[(i + 2, j + 1)], nodes[(i + 1, j + 2)], nodes[(i, j + 1)]]
                f.write("%d, %s\n" % (J * NC + I + 1, ", ".join(map(str, c))))
        f.write("*NSET, NSET=ROOT\n")
        root = [nodes[(i, 0)] for i in range(n)]
        for k in range(0, len(root), 8):
            f.write(", ".join(map(str, root[k:k + 8])) + ",\n")
        f.write("*MATERIAL, NAME=IM6\n*ELASTIC, TYPE=ENGINEERING CONSTANTS\n")
        f.write("%.6e, %.6e, %.6e, %.6e, %.6e, %.6e, %.6e, %.6e,\n%.6e, 0.\n" %
                (EL, ET, ET, NULT, NULT, NUTT, GLT, GLT, GTT))
        f.write("*DENSITY\n%g\n" % RHO)
        for I in range(NC):
            phi = -HALF + 2 * HALF * (I + 0.5) / NC
            t = (-math.sin(phi), math.cos(phi), 0.0)
            f.write("*ORIENTATION, NAME=AX%d, SYSTEM=RECTANGULAR\n0., 0., 1., %.17g, %.17g, 0.\n" % (I, t[0], t[1]))
            f.write("*ORIENTATION, NAME=HO%d, SYSTEM=RECTANGULAR\n%.17g, %.17g, 0., 0., 0., 1.\n" % (I, t[0], t[1]))
            f.write("*SHELL SECTION, ELSET=COL%d, COMPOSITE\n" % I)
            for m in (zero, other, other, zero):
                f.write("%g, , IM6, %s%d\n" % (PLY, "AX" if m == "axial" else "HO", I))
        f.write("*BOUNDARY\nROOT, 1, 6\n*STEP\n*FREQUENCY\n8\n*END STEP\n")


write_msh()
write_ccx("ccx_axial", "axial")
write_ccx("ccx_hoop", "hoop")
