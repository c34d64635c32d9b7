#!/usr/bin/env python3
"""Writes the brick's CalculiX matrices (brick_matrices.sti, .mas, .dof: ccx 2.20,
upper triangle, one-based) in the two text layouts Abaqus's *MATRIX OUTPUT writes
(docs/file-formats.md, "Imported matrices", gives the sources):
  FORMAT=COORDINATE   -> brick_coordinate_STIF1.mtx, brick_coordinate_MASS1.mtx:
      'row column  value', blank-separated, global equation numbers (one-based,
      node-major in ascending node order: here the .dof order), both triangles
      (each off-diagonal entry as the pair 'i j' then 'j i');
  FORMAT=MATRIX INPUT -> brick_matrix_input_STIF1.mtx, brick_matrix_input_MASS1.mtx:
      'row node,row dof,column node,column dof,value', comma-separated, the lower
      triangle (row at or after column in equation order).
The values are the CalculiX files' own (14 significant digits), so both layouts
hold exactly the same doubles. No Abaqus run was made. Run: python3 make_abaqus_layouts.py"""
dofs = [tuple(int(x) for x in l.split(".")) for l in open("brick_matrices.dof") if l.strip()]


def entries(path):
    out = []
    for l in open(path):
        f = l.split()
        if len(f) == 3:
            i, j = int(f[0]), int(f[1])
            out.append((min(i, j), max(i, j), f[2]))
    return sorted(out)


def value(v):
    x = float(v)
    return ("% .15e" % x)


for which, name in (("sti", "STIF1"), ("mas", "MASS1")):
    e = entries("brick_matrices." + which)
    with open("brick_coordinate_%s.mtx" % name, "w") as f:
        for i, j, v in e:
            f.write("%d %d %s\n" % (i, j, value(v)))
            if i != j:
                f.write("%d %d %s\n" % (j, i, value(v)))
    with open("brick_matrix_input_%s.mtx" % name, "w") as f:
        for i, j, v in sorted(e, key=lambda t: (t[1], t[0])):
            a, b = dofs[j - 1], dofs[i - 1]  # row j >= column i: the lower triangle
            f.write("%d,%d,%d,%d,%s\n" % (a[0], a[1], b[0], b[1], ("%.15e" % float(v))))
