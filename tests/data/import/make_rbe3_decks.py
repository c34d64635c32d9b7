#!/usr/bin/env python3
"""Writes the CalculiX decks of the fitting with two distributing (RBE3) patches
from fitting_mesh.inp (examples/imported-fitting/make_fitting.py):
  PADS patch: the bottom faces (S1) of the four base elements under the bolt pads
              (|x| >= 11.25 mm, 350 mm^2), reference point (0, 0, 0);
  LUG patch:  the top faces (S2) of the lug's two top elements (z = 25 mm,
              100 mm^2), reference point (0, 0, 30).
fitting_rbe3_static.inp: the PADS reference held, the LUG reference loaded through
  CalculiX's own *COUPLING + *DISTRIBUTING (its area weights, its load
  distribution), six steps: 100 N along x, y, z, 100 N mm about x, y, z; each
  step prints the total strain energy U (2 U / P^2 is the compliance of the
  loaded reference along its load).
fitting_rbe3_swap.inp: the same with the roles swapped (the LUG reference held,
  the PADS reference loaded through *DISTRIBUTING).
fitting_rbe3_modes.inp: the PADS reference held, *FREQUENCY, 10 modes.
A held reference is written as the six *EQUATIONs W u = 0 of the RBE3 fit
(CalculiX 2.20's *DISTRIBUTING only distributes loads, it adds no kinematic
equation a *BOUNDARY could hold): [u_P; theta_P] = A^-1 sum_i w_i G_i^T u_i,
G_i = [I, -skew(X_i - P)], A = sum_i w_i G_i^T G_i, with w_i the integral of the
face shape function N_i over the patch faces (3 x 3 Gauss on the 8-node faces),
coded here from those formulas (not from fe-prep), in reduced row echelon form so
that each equation's first term is a distinct dependent DOF.
Run: python3 make_rbe3_decks.py, then ccx -i fitting_rbe3_static,
ccx -i fitting_rbe3_swap and ccx -i fitting_rbe3_modes (Debian calculix-ccx 2.20).
Needs numpy."""
import numpy as np

nodes, elems = {}, {}
mode, cur = None, []
for line in open("fitting_mesh.inp"):
    s = line.strip()
    if not s or s.startswith("**"):
        continue
    if s.startswith("*"):
        k = s.upper()
        mode = "node" if k.startswith("*NODE") else "elem" if k.startswith("*ELEMENT") else None
        continue
    f = [x for x in s.split(",") if x.strip()]
    if mode == "node":
        nodes[int(f[0])] = np.array([float(x) for x in f[1:4]])
    elif mode == "elem":
        cur += [int(x) for x in f]
        if not s.endswith(","):
            elems[cur[0]] = cur[1:]
            cur = []

# C3D20 faces: corners then mid-sides of edges c0-c1, c1-c2, c2-c3, c3-c0 (0-based node positions).
FACES = {"S1": [0, 1, 2, 3, 8, 9, 10, 11], "S2": [4, 7, 6, 5, 15, 14, 13, 12]}
pads, top = [], []
for e, c in elems.items():
    z = [nodes[n][2] for n in c[:8]]
    x = [nodes[n][0] for n in c[:8]]
    if max(z[:4]) == 0.0 and min(abs(v) for v in x[:4]) >= 11.25 - 1e-9:
        pads.append((e, "S1"))
    if min(z[4:8]) == 25.0:
        top.append((e, "S2"))


def quad8(xi, eta):
    N, dN = np.zeros(8), np.zeros((8, 2))
    for i, (a, b) in enumerate([(-1, -1), (1, -1), (1, 1), (-1, 1)]):
        N[i] = 0.25 * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1)
        dN[i] = [0.25 * a * (1 + b * eta) * (2 * a * xi + b * eta), 0.25 * b * (1 + a * xi) * (a * xi + 2 * b * eta)]
    for i, (a, b) in zip(range(4, 8), [(0, -1), (1, 0), (0, 1), (-1, 0)]):
        if a == 0:
            N[i] = 0.5 * (1 - xi * xi) * (1 + b * eta)
            dN[i] = [-xi * (1 + b * eta), 0.5 * b * (1 - xi * xi)]
        else:
            N[i] = 0.5 * (1 + a * xi) * (1 - eta * eta)
            dN[i] = [0.5 * a * (1 - eta * eta), -eta * (1 + a * xi)]
    return N, dN


def weights(faces):
    g, gw = [-np.sqrt(0.6), 0.0, np.sqrt(0.6)], [5 / 9, 8 / 9, 5 / 9]
    w = {}
    for e, s in faces:
        ids = [elems[e][k] for k in FACES[s]]
        X = np.array([nodes[i] for i in ids])
        for a, wa in zip(g, gw):
            for b, wb in zip(g, gw):
                N, dN = quad8(a, b)
                J = X.T @ dN
                dA = np.linalg.norm(np.cross(J[:, 0], J[:, 1])) * wa * wb
                for k, i in enumerate(ids):
                    w[i] = w.get(i, 0.0) + N[k] * dA
    return w


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def held(faces, P):
    w = weights(faces)
    ids = sorted(w)
    A = np.zeros((6, 6))
    G = []
    for i in ids:
        G.append(np.hstack([np.eye(3), -skew(nodes[i] - P)]))
        A += w[i] * G[-1].T @ G[-1]
    W = np.hstack([w[i] * np.linalg.solve(A, g.T) for i, g in zip(ids, G)])
    M, piv, r = W.copy(), [], 0
    for c in range(M.shape[1]):
        if r == 6:
            break
        p = r + int(np.argmax(np.abs(M[r:, c])))
        if abs(M[p, c]) < 1e-8 * np.abs(W).max():
            continue
        M[[r, p]] = M[[p, r]]
        M[r] /= M[r, c]
        for q in range(6):
            if q != r:
                M[q] -= M[q, c] * M[r]
        piv.append(c)
        r += 1
    terms = [(ids[c // 3], c % 3 + 1) for c in range(M.shape[1])]
    txt = "** the reference (%g, %g, %g) of a distributing patch held: W u = 0\n" % tuple(P)
    for q in range(6):
        t = [(terms[piv[q]], 1.0)] + [(terms[c], M[q, c]) for c in range(M.shape[1])
                                      if c != piv[q] and abs(M[q, c]) > 1e-14]
        txt += "*EQUATION\n%d\n" % len(t)
        for k in range(0, len(t), 4):
            txt += ",".join("%d,%d,%.12e" % (a[0], a[1], v) for a, v in t[k:k + 4]) + "\n"
    return txt


def surface(name, faces):
    return "*SURFACE, NAME=%s, TYPE=ELEMENT\n" % name + "".join("%d, %s\n" % f for f in faces)


MATERIAL = """*MATERIAL, NAME=STEEL
*ELASTIC
210000., 0.3
*DENSITY
7.85E-9
*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL
"""
LUG, PADS = np.array([0.0, 0.0, 30.0]), np.zeros(3)


def static_deck(name, loaded, p_loaded, fixed, p_fixed):
    with open(name, "w") as f:
        f.write("** written by make_rbe3_decks.py from fitting_mesh.inp (units mm-t-s)\n"
                "*INCLUDE, INPUT=fitting_mesh.inp\n*NODE, NSET=NREF\n1000, %g, %g, %g\n" % tuple(p_loaded))
        f.write(surface("LOADED", loaded))
        f.write("*COUPLING, REF NODE=1000, SURFACE=LOADED, CONSTRAINT NAME=LOADED\n*DISTRIBUTING\n1, 6\n")
        f.write(held(fixed, p_fixed) + MATERIAL)
        for dof in range(1, 7):
            f.write("*STEP\n*STATIC\n*CLOAD, OP=NEW\n1000, %d, 100.\n*EL PRINT, ELSET=EALL, TOTALS=ONLY\nELSE\n*END STEP\n" % dof)


static_deck("fitting_rbe3_static.inp", top, LUG, pads, PADS)
static_deck("fitting_rbe3_swap.inp", pads, PADS, top, LUG)
with open("fitting_rbe3_modes.inp", "w") as f:
    f.write("** written by make_rbe3_decks.py from fitting_mesh.inp (units mm-t-s)\n*INCLUDE, INPUT=fitting_mesh.inp\n")
    f.write(held(pads, PADS) + MATERIAL + "*STEP\n*FREQUENCY\n10\n*END STEP\n")
print(len(pads), "pad faces,", len(top), "lug faces; pad area %.6g, lug area %.6g mm^2"
      % (sum(weights(pads).values()), sum(weights(top).values())))
