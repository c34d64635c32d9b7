#!/usr/bin/env python3
"""Writes the matrix-file seeds of the format fuzzer: a free steel tube of 1 m,
5 Euler-Bernoulli 3D beam elements (6 nodes labelled 101-106, 36 DOF), its
stiffness and consistent mass in every import format fe-prep reads:
CalculiX (tube.sti/tube.mas triplets, tube.dof "node.dof" rows, tube.inp
model), Matrix Market (tube_k.mtx/tube_m.mtx symmetric, tube.dofs "node dof"
rows, tube_nodes.txt "label x y z"), Abaqus (tube_k_abq.mtx/tube_m_abq.mtx
"node,dof,node,dof,value", lower triangle). Written for this repository."""
import numpy as np

E, G, rho = 2.1e11, 8.1e10, 7850.0
do, t = 0.04, 0.004
di = do - 2 * t
A = np.pi / 4 * (do**2 - di**2)
I = np.pi / 64 * (do**4 - di**4)
J = 2 * I
n_el, L = 5, 1.0
le = L / n_el

def element():
    K = np.zeros((12, 12)); M = np.zeros((12, 12))
    a = E * A / le
    K[np.ix_([0, 6], [0, 6])] = a * np.array([[1, -1], [-1, 1]])
    K[np.ix_([3, 9], [3, 9])] = G * J / le * np.array([[1, -1], [-1, 1]])
    kb = E * I / le**3 * np.array([[12, 6 * le, -12, 6 * le], [6 * le, 4 * le**2, -6 * le, 2 * le**2],
                                   [-12, -6 * le, 12, -6 * le], [6 * le, 2 * le**2, -6 * le, 4 * le**2]])
    mb = rho * A * le / 420 * np.array([[156, 22 * le, 54, -13 * le], [22 * le, 4 * le**2, 13 * le, -3 * le**2],
                                        [54, 13 * le, 156, -22 * le], [-13 * le, -3 * le**2, -22 * le, 4 * le**2]])
    for (w, th, s) in ((1, 5, 1), (2, 4, -1)):  # v with theta_z; w with theta_y (sign)
        idx = [w, th, w + 6, th + 6]
        S = np.diag([1, s, 1, s])
        K[np.ix_(idx, idx)] += S @ kb @ S
        M[np.ix_(idx, idx)] += S @ mb @ S
    M[np.ix_([0, 6], [0, 6])] += rho * A * le / 6 * np.array([[2, 1], [1, 2]])
    M[np.ix_([3, 9], [3, 9])] += rho * J * le / 6 * np.array([[2, 1], [1, 2]])
    return K, M

N = 6 * (n_el + 1)
K = np.zeros((N, N)); M = np.zeros((N, N))
ke, me = element()
for e in range(n_el):
    s = slice(6 * e, 6 * e + 12)
    K[s, s] += ke; M[s, s] += me
labels = [101 + k for k in range(n_el + 1)]
dofs = [(labels[i // 6], i % 6 + 1) for i in range(N)]

def lower(A):
    return [(i, j, A[i, j]) for j in range(N) for i in range(j, N) if A[i, j] != 0.0]

with open("tube.dof", "w") as f:
    f.writelines("%d.%d\n" % d for d in dofs)
with open("tube.dofs", "w") as f:
    f.writelines("%d %d\n" % d for d in dofs)
with open("tube_nodes.txt", "w") as f:
    f.writelines("%d %.17g 0 0\n" % (lab, k * le) for k, lab in enumerate(labels))
with open("tube.inp", "w") as f:
    f.write("*NODE, NSET=ALL\n")
    f.writelines("%d, %.17g, 0, 0\n" % (lab, k * le) for k, lab in enumerate(labels))
    f.write("*ELEMENT, TYPE=B31, ELSET=TUBE\n")
    f.writelines("%d, %d, %d\n" % (e + 1, labels[e], labels[e + 1]) for e in range(n_el))
    f.write("*NSET, NSET=ROOT\n%d\n*NSET, NSET=TIP\n%d\n" % (labels[0], labels[-1]))
for name, A, ext in (("k", K, "sti"), ("m", M, "mas")):
    ent = lower(A)
    with open("tube.%s" % ext, "w") as f:  # CalculiX: row col value, upper triangle (col >= row), one-based
        f.writelines("%d %d %.13e\n" % (j + 1, i + 1, v) for i, j, v in ent)
    with open("tube_%s.mtx" % name, "w") as f:
        f.write("%%%%MatrixMarket matrix coordinate real symmetric\n%d %d %d\n" % (N, N, len(ent)))
        f.writelines("%d %d %.17g\n" % (i + 1, j + 1, v) for i, j, v in ent)
    with open("tube_%s_abq.mtx" % name, "w") as f:
        f.writelines("%d,%d,%d,%d,%.17g\n" % (dofs[i] + dofs[j] + (v,)) for i, j, v in ent)
