#!/usr/bin/env python3
"""Writes the CalculiX decks of the raised-pins panel side-by-side.

A 1 x 0.65 m, 2 mm isotropic CFRP panel (E 159 GPa, nu 0.38, rho 1610) held by
two hinge points 70 mm above its mid-surface at x = -0.5, y = -/+0.2, each
clamped through a distributing (RBE3) coupling of the mid-surface nodes within
0.1 m of its projection; a third distributing point T at (0.5, 0, 0.07) couples
the nodes within 0.1 m of (0.5, 0) and carries the static loads.

CalculiX 2.20 side: a structured mesh of S4 shells (expanded by ccx into
C3D8I bricks, incompatible modes) of nx x ny squares. The RBE3 is written out
as *EQUATIONs, because *COUPLING/*DISTRIBUTING wants element faces of solids:
the point's motion [u_P; theta_P] = A^-1 sum_i w_i G_i^T u_i with
G_i = [I, -skew(X_i - P)], A = sum_i w_i G_i^T G_i, w_i the node's tributary
area (a quarter of each adjacent square). This is the textbook RBE3 (MSC
Nastran QRG, RBE3; CalculiX's own distributing coupling is the same fit with
face-area weights), coded here in plain Python from the formula, not from
fe-prep. Equations are put in reduced row echelon form so that every
dependent DOF (the first term) is a patch translation used nowhere else.

The rigid variant (static_rigid_NX.inp) couples T's patch with CalculiX's own
*RIGID BODY (REF NODE at the point, ROT NODE for the rotations) instead.

  python3 make_decks.py NX   -> modal_NX.inp, static_NX.inp, static_rigid_NX.inp
  ccx -i modal_NX ; ccx -i static_NX ; ccx -i static_rigid_NX   (results in the .dat files)
"""
import sys

L, B, T, Z = 1.0, 0.65, 0.002, 0.07
E, NU, RHO = 159.0e9, 0.38, 1610.0
R = 0.1
POINTS = {"H1": (-0.5, -0.2), "H2": (-0.5, 0.2), "T": (0.5, 0.0)}


def mesh(nx):
    ny = round(nx * B / L)
    assert abs(ny * L / nx - B) < 1e-12, "nx must give square elements on 0.65 m"
    dx = L / nx
    nodes = {}
    for j in range(ny + 1):
        for i in range(nx + 1):
            nodes[1 + i + j * (nx + 1)] = (-L / 2 + i * dx, -B / 2 + j * dx, 0.0)
    elems = {}
    for j in range(ny):
        for i in range(nx):
            n1 = 1 + i + j * (nx + 1)
            elems[1 + i + j * nx] = (n1, n1 + 1, n1 + nx + 2, n1 + nx + 1)
    return nodes, elems, dx


def tributary(elems, dx):
    w = {}
    for conn in elems.values():
        for n in conn:
            w[n] = w.get(n, 0.0) + dx * dx / 4.0
    return w


def solve6(A, b):
    """Gaussian elimination with partial pivoting, 6 x 6 (no numpy here)."""
    M = [row[:] + [b[i]] for i, row in enumerate(A)]
    n = len(M)
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(M[r][c]))
        M[c], M[p] = M[p], M[c]
        for r in range(n):
            if r != c:
                f = M[r][c] / M[c][c]
                for k in range(c, n + 1):
                    M[r][k] -= f * M[c][k]
    return [M[i][n] / M[i][i] for i in range(n)]


def rbe3(nodes, w, P):
    """Rows of W (6 x 3p): [u_P; theta_P] = W u_patch (translations only)."""
    patch = sorted(n for n, x in nodes.items()
                   if ((x[0] - P[0]) ** 2 + (x[1] - P[1]) ** 2) ** 0.5 <= R * (1 + 1e-12))
    def G(x):
        d = (x[0] - P[0], x[1] - P[1], x[2] - P[2])
        # u_i = t + omega x d = t - skew(d) omega
        return [[1, 0, 0, 0, d[2], -d[1]], [0, 1, 0, -d[2], 0, d[0]], [0, 0, 1, d[1], -d[0], 0]]
    A = [[0.0] * 6 for _ in range(6)]
    Gs = {}
    for n in patch:
        g = G(nodes[n])
        Gs[n] = g
        for a in range(6):
            for b in range(6):
                A[a][b] += w[n] * sum(g[k][a] * g[k][b] for k in range(3))
    # W = A^-1 [w_i G_i^T] column by column
    cols = []
    for n in patch:
        for k in range(3):
            rhs = [w[n] * Gs[n][k][a] for a in range(6)]
            cols.append(((n, k + 1), solve6(A, rhs)))
    return patch, cols


def rref_equations(rows, dofs, pivot_ok):
    """rows: list of coefficient lists over dofs. Returns equations whose first
    term is a pivot DOF (absent from every other equation)."""
    M = [r[:] for r in rows]
    eqs = []
    used = set()
    for r in range(len(M)):
        c = max((j for j in range(len(dofs)) if pivot_ok(dofs[j]) and j not in used), key=lambda j: abs(M[r][j]))
        used.add(c)
        piv = M[r][c]
        M[r] = [v / piv for v in M[r]]
        for s in range(len(M)):
            if s != r and M[s][c] != 0.0:
                f = M[s][c]
                M[s] = [a - f * b for a, b in zip(M[s], M[r])]
        eqs.append(c)
    out = []
    for r, c in enumerate(eqs):
        terms = [(dofs[c], 1.0)] + [(dofs[j], M[r][j]) for j in range(len(dofs)) if j != c and abs(M[r][j]) > 1e-14]
        out.append(terms)
    return out


def equation_text(terms):
    s = "*EQUATION\n%d\n" % len(terms)
    line = []
    for (n, d), a in terms:
        line.append("%d,%d,%.12e" % (n, d, a))
        if len(line) == 4:
            s += ",".join(line) + "\n"
            line = []
    if line:
        s += ",".join(line) + "\n"
    return s


def common(nx, aux, rigid=False):
    nodes, elems, dx = mesh(nx)
    w = tributary(elems, dx)
    s = "** raised-pins panel, %d x %d S4 (written by make_decks.py; see its docstring)\n" % (nx, round(nx * B / L))
    s += "*NODE, NSET=NALL\n" + "".join("%d,%.12e,%.12e,%.12e\n" % (n, *x) for n, x in nodes.items())
    s += "*ELEMENT, TYPE=S4, ELSET=EALL\n" + "".join("%d,%d,%d,%d,%d\n" % (e, *c) for e, c in elems.items())
    s += "*MATERIAL, NAME=CFRP_ISO\n*ELASTIC\n%.6e,%.6f\n*DENSITY\n%.6f\n" % (E, NU, RHO)
    s += "*SHELL SECTION, ELSET=EALL, MATERIAL=CFRP_ISO\n%.6f\n" % T
    eqtext = ""
    for name in ("H1", "H2"):  # clamped points: W u = 0
        P = (*POINTS[name], Z)
        patch, cols = rbe3(nodes, w, P)
        dofs = [c[0] for c in cols]
        rows = [[c[1][a] for c in cols] for a in range(6)]
        for terms in rref_equations(rows, dofs, lambda d: True):
            eqtext += equation_text(terms)
    if aux and rigid:  # loaded point on a rigid patch: CalculiX's own *RIGID BODY (RBE2)
        P = (*POINTS["T"], Z)
        patch, _ = rbe3(nodes, w, P)
        pn, rn = max(nodes) + 1, max(nodes) + 2
        s += "*NODE, NSET=NAUX\n%d,%.12e,%.12e,%.12e\n%d,%.12e,%.12e,%.12e\n" % (pn, *P, rn, *P)
        s += "*NSET, NSET=NPATCH\n" + "".join("%d,\n" % n for n in patch)
        s += "*RIGID BODY, NSET=NPATCH, REF NODE=%d, ROT NODE=%d\n" % (pn, rn)
    elif aux:  # loaded point: [u_P; theta_P] - W u = 0, P's and R's DOF independent
        P = (*POINTS["T"], Z)
        patch, cols = rbe3(nodes, w, P)
        pn, rn = max(nodes) + 1, max(nodes) + 2
        s += "*NODE, NSET=NAUX\n%d,%.12e,%.12e,%.12e\n%d,%.12e,%.12e,%.12e\n" % (pn, *P, rn, *P)
        aux_dofs = [(pn, 1), (pn, 2), (pn, 3), (rn, 1), (rn, 2), (rn, 3)]
        dofs = aux_dofs + [c[0] for c in cols]
        rows = [[1.0 if j == a else 0.0 for j in range(6)] + [-c[1][a] for c in cols] for a in range(6)]
        for terms in rref_equations(rows, dofs, lambda d: d not in aux_dofs):
            eqtext += equation_text(terms)
    return s + eqtext, aux and (pn, rn)


def collect(meshes):
    """Parses the .dat files of the given meshes into ccx_results.txt."""
    out = ["# CalculiX 2.20 (Debian calculix-ccx 2.20-1) results of the decks make_decks.py writes;",
           "# regenerate: for N in 40 80 160: python3 make_decks.py N; ccx -i modal_N; ccx -i static_N;",
           "# ccx -i static_rigid_N; then python3 make_decks.py --collect 40 80 160",
           "# frequencies NX f1..f6 [Hz]; compliance_KIND NX: displacement of T under a unit force x y z [m/N]",
           "# and rotation under a unit moment x y z [rad/(N m)] (diagonal of the 6 load cases)"]
    for nx in meshes:
        lines = open("modal_%d.dat" % nx).read().splitlines()
        k = next(i for i, l in enumerate(lines) if "E I G E N V A L U E" in l)
        f = [float(lines[k + 6 + j].split()[3]) for j in range(6)]
        out.append("frequencies %d " % nx + " ".join("%.7e" % v for v in f))
        for kind, name in (("distributing", "static_%d.dat"), ("rigid", "static_rigid_%d.dat")):
            blocks = open(name % nx).read().split("displacements")[1:]
            c = []
            for j, b in enumerate(blocks):
                rows = [l.split() for l in b.splitlines()[2:4]]
                c.append(float(rows[j // 3][1 + j % 3]))
            out.append("compliance_%s %d " % (kind, nx) + " ".join("%.7e" % v for v in c))
    open("ccx_results.txt", "w").write("\n".join(out) + "\n")


def main():
    if sys.argv[1] == "--collect":
        collect([int(a) for a in sys.argv[2:]])
        return
    nx = int(sys.argv[1])
    text, _ = common(nx, False)
    with open("modal_%d.inp" % nx, "w") as f:
        f.write(text + "*STEP\n*FREQUENCY\n6\n*NODE FILE\nU\n*END STEP\n")
    text, (pn, rn) = common(nx, True)
    steps = ""
    for k in range(6):
        node, dof = (pn, k + 1) if k < 3 else (rn, k - 2)
        steps += "*STEP\n*STATIC\n*CLOAD, OP=NEW\n%d,%d,1.0\n*NODE PRINT, NSET=NAUX\nU\n*END STEP\n" % (node, dof)
    with open("static_%d.inp" % nx, "w") as f:
        f.write(text + steps)
    text, _ = common(nx, True, rigid=True)
    with open("static_rigid_%d.inp" % nx, "w") as f:
        f.write(text + steps)


if __name__ == "__main__":
    main()
