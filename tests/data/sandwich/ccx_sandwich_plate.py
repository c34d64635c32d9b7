#!/usr/bin/env python3
"""Layered 3-D CalculiX model of a simply supported sandwich plate: the reference
for fe-prep's sandwich shell (tests/fe-prep/elements/test_sandwich_plate.cpp).

Writes the deck, runs CalculiX (`ccx`, 2.20 in Debian 12) and writes the fixture
ccx_sandwich_plate.yaml next to this script, which the test reads (it never runs
ccx). Run from anywhere:  python3 tests/data/sandwich/ccx_sandwich_plate.py

The plate: a = b = 0.5 m; aluminium faces (E 70 GPa, nu 0.3, rho 2700) t = 1 mm
each; aluminium-honeycomb-like core c = 20 mm (E3 600 MPa, G13 200 MPa along x,
G23 100 MPa, in-plane E1 = E2 = G12 = 0.1 MPa, Poisson ratios 0, rho 50).
C3D20R bricks, NX x NX in plane, one through each face and NCORE through the core.
Hard simple supports, as Navier's first-order shear solution assumes (Reddy,
Mechanics of Laminated Composite Plates and Shells, 2nd ed., ch. 6): on x = 0, a
every node through the thickness has u_y = u_z = 0, on y = 0, b u_x = u_z = 0.
Step 1: the lowest frequencies. Step 2: uniform pressure P on the top face; the
centre's displacement at the bottom, mid-surface and top.
"""
import os
import re
import subprocess
import sys
import tempfile

A = 0.5
T_FACE, C_CORE = 1e-3, 20e-3
NX, NCORE = int(os.environ.get("NX", 20)), int(os.environ.get("NCORE", 4))
MODES = 8
P = 1000.0  # Pa

H = C_CORE + 2 * T_FACE
zb = [-H / 2, -C_CORE / 2] + [-C_CORE / 2 + C_CORE * (k + 1) / NCORE for k in range(NCORE)] + [H / 2]
layer_mat = ["FACE"] + ["CORE"] * NCORE + ["FACE"]
NZ = len(zb) - 1
z2 = []  # the doubled grid: element boundaries and midpoints
for k in range(NZ):
    z2 += [zb[k], 0.5 * (zb[k] + zb[k + 1])]
z2.append(zb[-1])
x2 = [A * i / (2 * NX) for i in range(2 * NX + 1)]

nodes = {}


def node(i, j, k):
    key = (i, j, k)
    if key not in nodes:
        nodes[key] = len(nodes) + 1
    return nodes[key]


elements = []  # (id, material, 20 nodes)
for k in range(NZ):
    for j in range(NX):
        for i in range(NX):
            I, J, K = 2 * i, 2 * j, 2 * k
            c = [(I, J, K), (I + 2, J, K), (I + 2, J + 2, K), (I, J + 2, K),
                 (I, J, K + 2), (I + 2, J, K + 2), (I + 2, J + 2, K + 2), (I, J + 2, K + 2)]
            mid = [(I + 1, J, K), (I + 2, J + 1, K), (I + 1, J + 2, K), (I, J + 1, K),
                   (I + 1, J, K + 2), (I + 2, J + 1, K + 2), (I + 1, J + 2, K + 2), (I, J + 1, K + 2),
                   (I, J, K + 1), (I + 2, J, K + 1), (I + 2, J + 2, K + 1), (I, J + 2, K + 1)]
            elements.append((len(elements) + 1, layer_mat[k], [node(*p) for p in c + mid], k))


def deck():
    out = ["*HEADING", "Simply supported sandwich plate, layered C3D20R", "*NODE"]
    for (i, j, k), n in sorted(nodes.items(), key=lambda kv: kv[1]):
        out.append(f"{n}, {x2[i]:.12g}, {x2[j]:.12g}, {z2[k]:.12g}")
    for mat in ("FACE", "CORE"):
        out.append(f"*ELEMENT, TYPE=C3D20R, ELSET=E{mat}")
        for eid, m, nn, _ in elements:
            if m == mat:
                out.append(f"{eid}, " + ", ".join(map(str, nn[:15])) + ",")
                out.append(", ".join(map(str, nn[15:])))
    out.append("*ELSET, ELSET=ETOP")
    top = [str(e[0]) for e in elements if e[3] == NZ - 1]
    out += [", ".join(top[i:i + 16]) for i in range(0, len(top), 16)]
    xedge = [n for (i, j, k), n in nodes.items() if i in (0, 2 * NX)]
    yedge = [n for (i, j, k), n in nodes.items() if j in (0, 2 * NX)]
    for name, ids in (("NXEDGE", xedge), ("NYEDGE", yedge)):
        out.append(f"*NSET, NSET={name}")
        s = [str(n) for n in sorted(ids)]
        out += [", ".join(s[i:i + 16]) for i in range(0, len(s), 16)]
    kmid = z2.index(min(z2, key=abs))
    centre = [nodes[(NX, NX, 0)], nodes[(NX, NX, kmid)], nodes[(NX, NX, 2 * NZ)]]
    out.append("*NSET, NSET=NCENTRE")
    out.append(", ".join(map(str, centre)))
    out += ["*MATERIAL, NAME=FACE", "*ELASTIC", "70e9, 0.3", "*DENSITY", "2700",
            "*MATERIAL, NAME=CORE", "*ELASTIC, TYPE=ENGINEERING CONSTANTS",
            "1e5, 1e5, 600e6, 0, 0, 0, 1e5, 200e6", "100e6", "*DENSITY", "50",
            "*SOLID SECTION, ELSET=EFACE, MATERIAL=FACE",
            "*SOLID SECTION, ELSET=ECORE, MATERIAL=CORE",
            "*BOUNDARY", "NXEDGE, 2, 3", "NYEDGE, 1, 1", "NYEDGE, 3, 3",
            "*STEP", "*FREQUENCY", f"{MODES}", "*END STEP",
            "*STEP", "*STATIC", "*DLOAD", f"ETOP, P2, {P}",
            "*NODE PRINT, NSET=NCENTRE", "U", "*END STEP"]
    return "\n".join(out) + "\n", centre


def main():
    text, centre = deck()
    here = os.path.dirname(os.path.abspath(__file__))
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "plate.inp"), "w") as f:
            f.write(text)
        r = subprocess.run(["ccx", "-i", "plate"], cwd=tmp, capture_output=True, text=True,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
        if r.returncode != 0:
            sys.exit("ccx failed:\n" + r.stdout[-3000:] + r.stderr[-3000:])
        dat = open(os.path.join(tmp, "plate.dat")).read()
    version = subprocess.run(["ccx", "-v"], capture_output=True, text=True).stdout.strip()
    freqs = []
    block = dat.split("E I G E N V A L U E   O U T P U T")[1]
    for line in block.splitlines():
        f = line.split()
        if len(f) == 5 and f[0].isdigit():
            freqs.append(float(f[3]))  # CYCLES/TIME
        if "P A R T I C I P A T I O N" in line:
            break
    w = {}
    for line in dat.split("displacements (vx,vy,vz)")[1].splitlines()[1:]:
        f = line.split()
        if len(f) == 4:
            w[int(f[0])] = float(f[3])
    with open(os.path.join(here, "ccx_sandwich_plate.yaml"), "w") as f:
        f.write("# Written by ccx_sandwich_plate.py (" + version + "); do not edit.\n")
        f.write(f"# Mesh: C3D20R {NX} x {NX} in plane, 1 + {NCORE} + 1 through the thickness,"
                f" {len(nodes)} nodes, {len(elements)} elements.\n")
        f.write(f"a: {A}\nt_face: {T_FACE}\nc_core: {C_CORE}\npressure: {P}\n")
        f.write("frequencies_hz: [" + ", ".join(f"{x:.7g}" for x in freqs[:MODES]) + "]\n")
        f.write("# centre deflection (u_z, m) under the pressure, at z = -h/2, 0, +h/2\n")
        f.write("centre_w: [" + ", ".join(f"{w[n]:.7g}" for n in centre) + "]\n")
    print(open(os.path.join(here, "ccx_sandwich_plate.yaml")).read())


if __name__ == "__main__":
    main()
