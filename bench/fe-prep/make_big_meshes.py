#!/usr/bin/env python3
"""Writes a flat aluminium panel 2.0 x 1.3 m of n x m four-node quadrilaterals in
the three mesh files fe-prep reads, for bench_mesh_read (bench/fe-prep/):
  panel.bdf     Nastran bulk data, small fixed fields: GRID, CQUAD4, PSHELL, MAT1
                (the common case of exported decks: 8-character fields);
  panel41.msh   gmsh 4.1 ASCII, the quads in physical surface "skin";
  panel22.msh   gmsh 2.2 ASCII, the same.
Run: python3 make_big_meshes.py N [M] [DIR]: N x M quads (M = N unless given),
into DIR (default: the current folder). N = 1000 gives the 1e6-element files
(106 / 56 / 64 MB). The files are scratch data, not committed."""
import os
import sys

n = int(sys.argv[1])
m = int(sys.argv[2]) if len(sys.argv) > 2 else n
out = sys.argv[3] if len(sys.argv) > 3 else "."
os.makedirs(out, exist_ok=True)
Lx, Ly = 2.0, 1.3
nodes = (n + 1) * (m + 1)
quads = n * m


def node_id(i, j):
    return j * (n + 1) + i + 1


def coords():
    for j in range(m + 1):
        y = Ly * j / m
        for i in range(n + 1):
            yield node_id(i, j), Lx * i / n, y


def quad_nodes():
    e = 0
    for j in range(m):
        for i in range(n):
            e += 1
            yield e, node_id(i, j), node_id(i + 1, j), node_id(i + 1, j + 1), node_id(i, j + 1)


def small(x):
    """A real in an 8-character Nastran field."""
    s = f"{x:.6f}"
    return s[:8] if "." in s[:8] else f"{x:8.2e}"


with open(os.path.join(out, "panel.bdf"), "w") as f:
    f.write(f"$ flat panel {Lx} x {Ly} m, {n} x {m} CQUAD4; written by make_big_meshes.py\nBEGIN BULK\n")
    f.write("MAT1           1   7.+10             .33   2.7+3\n")
    f.write("PSHELL         1       1   .002        1\n")
    lines = []
    for k, x, y in coords():
        lines.append(f"GRID    {k:8d}        {small(x):>8s}{small(y):>8s}      0.\n")
        if len(lines) >= 100000:
            f.write("".join(lines)); lines = []
    for e, a, b, c, d in quad_nodes():
        lines.append(f"CQUAD4  {e:8d}       1{a:8d}{b:8d}{c:8d}{d:8d}\n")
        if len(lines) >= 100000:
            f.write("".join(lines)); lines = []
    f.write("".join(lines))
    f.write("ENDDATA\n")

with open(os.path.join(out, "panel41.msh"), "w") as f:
    f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"skin\"\n$EndPhysicalNames\n")
    f.write(f"$Entities\n0 0 1 0\n1 0 0 0 {Lx} {Ly} 0 1 1 0\n$EndEntities\n")
    f.write(f"$Nodes\n1 {nodes} 1 {nodes}\n2 1 0 {nodes}\n")
    f.write("".join(f"{k}\n" for k in range(1, nodes + 1)))
    f.write("".join(f"{x:.9g} {y:.9g} 0\n" for _, x, y in coords()))
    f.write(f"$EndNodes\n$Elements\n1 {quads} 1 {quads}\n2 1 3 {quads}\n")
    f.write("".join(f"{e} {a} {b} {c} {d}\n" for e, a, b, c, d in quad_nodes()))
    f.write("$EndElements\n")

with open(os.path.join(out, "panel22.msh"), "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"skin\"\n$EndPhysicalNames\n")
    f.write(f"$Nodes\n{nodes}\n")
    f.write("".join(f"{k} {x:.9g} {y:.9g} 0\n" for k, x, y in coords()))
    f.write(f"$EndNodes\n$Elements\n{quads}\n")
    f.write("".join(f"{e} 3 2 1 1 {a} {b} {c} {d}\n" for e, a, b, c, d in quad_nodes()))
    f.write("$EndElements\n")
print(nodes, "nodes", quads, "quads in", out)
