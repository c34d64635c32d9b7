#!/usr/bin/env python3
"""The stiffened CFRP panel of examples/stiffened-panel side by side with
CalculiX 2.20 (provenance of the fixtures here; read by
tests/fe-prep/test_stiffened_panel_calculix.cpp).

Geometry and properties (those of examples/stiffened-panel/panel.yaml without
its paint, fitting mass and interfaces, so that both sides model the bare
structure):
  skin      0.8 x 0.5 m (x in [-0.4, 0.4], y in [-0.25, 0.25], z = 0),
            [0/45/-45/90]s IM6 plies of 0.25 mm (2 mm), 0 deg along x
  stringers two aluminium blades 4 mm (along y) x 25 mm (along z) along x at
            y = -0.125 and y = +0.125, E 70 GPa, nu 0.33, rho 2700; the beam
            axis on the skin's mid-plane in both models (no offset: the beam
            nodes are the skin's nodes)
  support   the root edge x = -0.4 clamped (all six components of every node)
  static    the tip edge x = +0.4 made rigid with a reference point at
            (0.4, 0, 0) (fe-prep: a rigid interface on the set "tip";
            CalculiX: *RIGID BODY), loaded by Fz = 1 N: the tip deflection
            uz/Fz (and Mx = 1 N m: rx/Mx, recorded, not compared: the two
            rigid edges differ in the rotations they tie, see below).

Writes, for the mesh sizes given:
  panel_NX.msh       gmsh 2.2 ASCII for fe-prep: NX x NY square cells (NY =
                     NX * 5 / 8, a multiple of 4 so that the stringers lie on
                     grid lines), each cut into two 3-node triangles along
                     alternating diagonals; groups "skin" (surface),
                     "stringers" (2-node lines along the stringers), "root"
                     and "tip" (lines on the edges x = -0.4 and x = +0.4)
  modal_NC.inp       CalculiX: NC x NC*3/4 S8R shells (*SHELL SECTION,
                     COMPOSITE, one rectangular *ORIENTATION per ply angle),
                     B32R beams (*BEAM SECTION, SECTION=RECT, 1-direction z)
                     on the S8R edges at y = +-0.125 (corner-mid-corner
                     nodes), root clamped, *FREQUENCY 12
  static_NC.inp      the same with the tip edge's *RIGID BODY and three
                     *STATIC steps
CalculiX expands S8R and B32R into C3D20R bricks; at the nodes shared by
shells and beams it makes rigid knots.

  python3 make_decks.py msh 32 64 128    -> panel_32.msh ...
  python3 make_decks.py section          -> stringer.h5
  python3 make_decks.py ccx 16 32 64     -> modal_16.inp static_16.inp ...
  python3 make_decks.py skin 32          -> skin_32.inp (the skin alone, modal)
  python3 make_decks.py ccx-crossply 32 64 -> modal_crossply_32.inp ... (the [0/0/90/90]s skin)
  python3 make_decks.py stringer 32      -> stringer_alone.inp (one stringer, clamped-free)
                                            and beam theory's frequencies of it
  ccx -i modal_16; ccx -i static_16 ...  (Debian calculix-ccx 2.20-1)
  python3 make_decks.py --collect 16 32 64 > ccx_results.txt
"""
import math
import re
import sys

LX, LY, YS = 0.8, 0.5, 0.125
PLY, ANGLES = 0.00025, (0, 45, -45, 90, 90, -45, 45, 0)
CROSSPLY = (0, 0, 90, 90, 90, 90, 0, 0)  # the variant with a [0/0/90/90]s skin
E1, E2, NU12, NU23, G12, G23, RHO_C = 177e9, 10.8e9, 0.27, 0.5, 7.6e9, 3.6e9, 1600.0
E_AL, NU_AL, RHO_AL, BW, BH = 70e9, 0.33, 2700.0, 0.004, 0.025


def ccx_num(v):
    """A number for a CalculiX data line. CalculiX reads every number of a
    data line from its first 20 characters (read(textpart(i)(1:20),
    '(f20.0)'), e.g. in orientations.f and nodes.f), so '%.17g' of
    cos(90 deg) = 6.123233995736766e-17 (21 characters) was read as
    6.123233995736766e-1 = 0.61: the 90-degree plies became 58.5-degree
    plies. Round-off below 1e-15 is written as 0 and every number in 15
    significant digits, which always fits."""
    v = 0.0 if abs(v) < 1e-15 else v
    t = "%.15g" % v
    assert len(t) <= 20, t
    return t


def write_msh(nx):
    ny = nx * 5 // 8
    assert ny * 8 == nx * 5 and ny % 4 == 0, "NX must be a multiple of 32"
    n = nx + 1
    idx = lambda i, j: j * n + i + 1
    lines = []  # (group, n1, n2)
    for i in range(nx):
        for j in (ny // 4, 3 * ny // 4):
            lines.append((2, idx(i, j), idx(i + 1, j)))
    for j in range(ny):
        lines.append((3, idx(0, j), idx(0, j + 1)))
        lines.append((4, idx(nx, j), idx(nx, j + 1)))
    tris = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            if (i + j) % 2 == 0:
                tris += [(a, b, c), (a, c, d)]
            else:
                tris += [(a, b, d), (b, c, d)]
    with open("panel_%d.msh" % nx, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n4\n2 1 "skin"\n1 2 "stringers"\n1 3 "root"\n1 4 "tip"\n$EndPhysicalNames\n')
        f.write("$Nodes\n%d\n" % (n * (ny + 1)))
        for j in range(ny + 1):
            for i in range(n):
                f.write("%d %.17g %.17g 0\n" % (idx(i, j), -LX / 2 + LX * i / nx, -LY / 2 + LY * j / ny))
        f.write("$EndNodes\n$Elements\n%d\n" % (len(lines) + len(tris)))
        e = 1
        for g, a, b in lines:
            f.write("%d 1 2 %d %d %d %d\n" % (e, g, g, a, b))
            e += 1
        for a, b, c in tris:
            f.write("%d 2 2 1 1 %d %d %d\n" % (e, a, b, c))
            e += 1
        f.write("$EndElements\n")


def write_ccx(nc, static, knot=False, bare=False, angles=ANGLES, tag=""):
    ncy = nc * 3 // 4
    assert ncy * 4 == nc * 3 and ncy % 4 == 0, "NC must be a multiple of 16"
    mx, my = 2 * nc, 2 * ncy  # half-element grid
    nodes = {}
    for j in range(my + 1):
        for i in range(mx + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue  # S8R: no centre node
            nodes[(i, j)] = len(nodes) + 1
    xy = lambda i, j: (-LX / 2 + LX * i / mx, -LY / 2 + LY * j / my)
    name = ("static_%d" if static else "modal_%d") % nc
    if knot:
        name = "modal_knot_%d" % nc
    if bare:
        name = "skin_%d" % nc  # the skin alone: no stringer nodes, beams, equations or beam section
    if tag:
        name = name.replace("_%d" % nc, "_%s_%d" % (tag, nc))
    with open(name + ".inp", "w") as f:
        label = {ANGLES: "[0/45/-45/90]s", CROSSPLY: "[0/0/90/90]s"}[tuple(angles)]
        f.write("** stiffened %s panel with two blade stringers (make_decks.py)\n*NODE, NSET=NALL\n" % label)
        for (i, j), k in nodes.items():
            x, y = xy(i, j)
            f.write("%d, %s, %s, 0\n" % (k, ccx_num(x), ccx_num(y)))
        ref, rot = len(nodes) + 1, len(nodes) + 2
        if static:
            f.write("%d, 0.4, 0, 0\n%d, 0.4, 0, 0\n" % (ref, rot))
        f.write("*ELEMENT, TYPE=S8R, ELSET=SKIN\n")
        e = 1
        for J in range(ncy):
            for I in range(nc):
                i, j = 2 * I, 2 * J
                c = [nodes[(i, j)], nodes[(i + 2, j)], nodes[(i + 2, j + 2)], nodes[(i, j + 2)],
                     nodes[(i + 1, j)], nodes[(i + 2, j + 1)], nodes[(i + 1, j + 2)], nodes[(i, j + 1)]]
                f.write("%d, %s\n" % (e, ", ".join(map(str, c))))
                e += 1
        # The stringers' own nodes (beam_nodes), beside the skin's.
        beam_nodes = {}
        for j in (my // 4, 3 * my // 4):
            for i in range(mx + 1):
                beam_nodes[(i, j)] = ref + 2 + len(beam_nodes)
        lay = beam_nodes if not knot else nodes
        if bare:
            beam_nodes = {}
        if not knot and not bare:
            f.write("*NODE, NSET=NSTR\n")
            for (i, j), k in beam_nodes.items():
                x, y = xy(i, j)
                f.write("%d, %s, %s, 0\n" % (k, ccx_num(x), ccx_num(y)))
        if not bare:
            f.write("*ELEMENT, TYPE=B32R, ELSET=STR\n")
        for j in ((my // 4, 3 * my // 4) if not bare else ()):
            for I in range(nc):
                i = 2 * I
                f.write("%d, %d, %d, %d\n" % (e, lay[(i, j)], lay[(i + 1, j)], lay[(i + 2, j)]))
                e += 1
        if not knot and not bare:
            # Translations tied, rotations free: each stringer node moves with
            # the skin node it lies on (the root ones are clamped themselves).
            f.write("*EQUATION\n")
            for (i, j), k in beam_nodes.items():
                if i == 0:
                    continue
                for d in (1, 2, 3):
                    f.write("2\n%d, %d, 1., %d, %d, -1.\n" % (k, d, nodes[(i, j)], d))
        for setname, i in (("ROOT", 0), ("TIP", mx)):
            f.write("*NSET, NSET=%s\n" % setname)
            ids = [nodes[(i, j)] for j in range(my + 1)]
            if setname == "ROOT" and not knot:
                ids += [k for (bi, bj), k in beam_nodes.items() if bi == 0]
            for k in range(0, len(ids), 8):
                f.write(", ".join(map(str, ids[k:k + 8])) + ",\n")
        f.write("*MATERIAL, NAME=IM6\n*ELASTIC, TYPE=ENGINEERING CONSTANTS\n")
        f.write("%.6e, %.6e, %.6e, %.6e, %.6e, %.6e, %.6e, %.6e,\n%.6e, 0.\n" %
                (E1, E2, E2, NU12, NU12, NU23, G12, G12, G23))
        f.write("*DENSITY\n%g\n" % RHO_C)
        f.write("*MATERIAL, NAME=ALU\n*ELASTIC\n%g, %g\n*DENSITY\n%g\n" % (E_AL, NU_AL, RHO_AL))
        for a in sorted(set(angles)):
            c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
            f.write("*ORIENTATION, NAME=P%s, SYSTEM=RECTANGULAR\n%s, %s, 0., %s, %s, 0.\n" %
                    ((str(a).replace("-", "M"),) + tuple(ccx_num(v) for v in (c, s, -s, c))))
        f.write("*SHELL SECTION, ELSET=SKIN, COMPOSITE\n")
        for a in angles:
            f.write("%g, , IM6, P%s\n" % (PLY, str(a).replace("-", "M")))
        # The section's 1-direction along the skin normal z (25 mm), its
        # 2-direction t x n1 = -y (4 mm): with the 1-direction along y the
        # expansion tilts the shared nodes' normals and the skin's bricks
        # next to the stringers get negative Jacobians.
        if not bare:
            f.write("*BEAM SECTION, ELSET=STR, MATERIAL=ALU, SECTION=RECT\n%g, %g\n0., 0., 1.\n" % (BH, BW))
        f.write("*BOUNDARY\nROOT, 1, 6\n")
        if not static:
            f.write("*STEP\n*FREQUENCY\n12\n*END STEP\n")
            return
        f.write("*RIGID BODY, NSET=TIP, REF NODE=%d, ROT NODE=%d\n" % (ref, rot))
        f.write("*NSET, NSET=REFS\n%d, %d\n" % (ref, rot))
        for node, dof in ((ref, 3), (rot, 1)):  # Fz; Mx on the rotation node
            f.write("*STEP\n*STATIC\n*CLOAD, OP=NEW\n%d, %d, 1.\n*NODE PRINT, NSET=REFS\nU\n*END STEP\n" % (node, dof))


def write_stringer_alone(ne):
    """stringer_alone.inp: one stringer as a 0.8 m cantilever (B32R, the
    panel's *BEAM SECTION, ne elements along x, root node clamped), free of
    the skin: its first bending modes in both planes and its first torsion
    mode against beam theory (stringer_closed_form)."""
    with open("stringer_alone.inp", "w") as f:
        f.write("** one blade stringer alone, clamped-free (make_decks.py stringer)\n*NODE, NSET=NALL\n")
        for i in range(2 * ne + 1):
            f.write("%d, %s, 0, 0\n" % (i + 1, ccx_num(-LX / 2 + LX * i / (2 * ne))))
        f.write("*ELEMENT, TYPE=B32R, ELSET=STR\n")
        for e in range(ne):
            f.write("%d, %d, %d, %d\n" % (e + 1, 2 * e + 1, 2 * e + 2, 2 * e + 3))
        f.write("*MATERIAL, NAME=ALU\n*ELASTIC\n%g, %g\n*DENSITY\n%g\n" % (E_AL, NU_AL, RHO_AL))
        f.write("*BEAM SECTION, ELSET=STR, MATERIAL=ALU, SECTION=RECT\n%g, %g\n0., 0., 1.\n" % (BH, BW))
        f.write("*BOUNDARY\n1, 1, 6\n*STEP\n*FREQUENCY\n8\n*NODE FILE\nU\n*END STEP\n")


def stringer_closed_form():
    """The clamped-free blade's frequencies [Hz] in beam theory: Euler-
    Bernoulli bending in the stiff plane (deflection along z, I = BW BH^3/12)
    and the weak plane (along y, I = BH BW^3/12), beta L = 1.875104, 4.694091,
    7.854757; St-Venant torsion (2n - 1)/(4 L) sqrt(G J / (rho Ip)) with
    J = a b^3 (1/3 - 0.21 b/a (1 - b^4/(12 a^4))) (Roark, Table 10.7, case 4,
    a = 25 mm, b = 4 mm) and Ip = BW BH (BW^2 + BH^2)/12."""
    A, m = BW * BH, RHO_AL * BW * BH
    G = E_AL / (2 * (1 + NU_AL))
    out = {}
    for name, I in (("stiff", BW * BH ** 3 / 12), ("weak", BH * BW ** 3 / 12)):
        out[name] = [bl ** 2 / (2 * math.pi * LX ** 2) * math.sqrt(E_AL * I / m) for bl in (1.875104, 4.694091, 7.854757)]
    a, b = BH, BW
    J = a * b ** 3 * (1 / 3 - 0.21 * b / a * (1 - b ** 4 / (12 * a ** 4)))
    Ip = A * (BW ** 2 + BH ** 2) / 12
    out["torsion"] = [(2 * n - 1) / (4 * LX) * math.sqrt(G * J / (RHO_AL * Ip)) for n in (1, 2)]
    return out


def write_section():
    """stringer.h5 (format section/1) for fe-prep: the 4 x 25 mm aluminium
    blade's closed-form Timoshenko section (width 4 mm along x2, height 25 mm
    along x3; shear factor 10(1+nu)/(12+11nu), Cowper) with its torsion
    stiffness and polar inertia taken out (1e-9 of theirs): in CalculiX the
    stringer's nodes share the skin's translations only, so its twist does
    not follow the skin's rotation and neither its torsion stiffness nor its
    polar inertia enters the panel's motion."""
    import h5py
    import numpy as np
    G = E_AL / (2 * (1 + NU_AL))
    A, I2, I3 = BW * BH, BW * BH ** 3 / 12, BH * BW ** 3 / 12
    a, c = BH, BW
    J = a * c ** 3 * (1 / 3 - 0.21 * c / a * (1 - (c / a) ** 4 / 12))
    k = 10 * (1 + NU_AL) / (12 + 11 * NU_AL)
    K = np.diag([E_AL * A, k * G * A, k * G * A, 1e-9 * G * J, E_AL * I2, E_AL * I3])
    M = np.diag([RHO_AL * A, RHO_AL * A, RHO_AL * A, 1e-9 * RHO_AL * (I2 + I3), RHO_AL * I2, RHO_AL * I3])
    with h5py.File("stringer.h5", "w") as f:
        f.attrs["format"] = "section/1"
        f.attrs["units"] = "SI"
        f.attrs["source"] = "make_decks.py (closed form, torsion removed)"
        f["/stiffness/timoshenko"] = K
        f["/mass/matrix"] = M
        f["/mass/per_length"] = RHO_AL * A


def collect(ncs):
    """Frequencies of modal_NC.dat, compliances of static_NC.dat."""
    print("# CalculiX 2.20 (Debian calculix-ccx 2.20-1) on the decks of make_decks.py;")
    print("# frequencies NC: the first 10 frequencies [Hz] of modal_NC.dat's EIGENVALUE OUTPUT;")
    print("# frequencies_knot NC: the same with the stringers on the skin's own nodes (CalculiX's rigid knots; modal_knot_NC.dat)")
    print("# frequencies_crossply NC: the same as frequencies NC with a [0/0/90/90]s skin (modal_crossply_NC.dat)")
    print("# compliance NC: uz/Fz [m/N], rx/Mx [rad/(N m)] of the tip's rigid reference point (static_NC.dat);")
    print("#   ry/My is not measured: *RIGID BODY on the straight tip edge leaves the rotation about the edge free")
    for nc in ncs:
        txt = open("modal_%d.dat" % nc).read()
        block = txt.split("E I G E N V A L U E   O U T P U T")[1]
        f = []
        for line in block.splitlines():
            p = line.split()
            if len(p) == 5 and p[0].isdigit():
                f.append(float(p[3]))
        print("frequencies %d %s" % (nc, " ".join("%.7g" % v for v in f[:10])))
        try:
            block = open("modal_crossply_%d.dat" % nc).read().split("E I G E N V A L U E   O U T P U T")[1]
            f = [float(l.split()[3]) for l in block.splitlines() if len(l.split()) == 5 and l.split()[0].isdigit()]
            print("frequencies_crossply %d %s" % (nc, " ".join("%.7g" % v for v in f[:10])))
        except FileNotFoundError:
            pass
        try:
            block = open("modal_knot_%d.dat" % nc).read().split("E I G E N V A L U E   O U T P U T")[1]
            f = [float(l.split()[3]) for l in block.splitlines() if len(l.split()) == 5 and l.split()[0].isdigit()]
            print("frequencies_knot %d %s" % (nc, " ".join("%.7g" % v for v in f[:10])))
        except FileNotFoundError:
            pass
        steps = open("static_%d.dat" % nc).read().split("displacements (vx,vy,vz) for set REFS")[1:]
        vals = []
        for s, (node, comp) in zip(steps, ((0, 2), (1, 0))):
            rows = [l.split() for l in s.splitlines()[1:] if re.match(r"\s+\d+\s", l)][:2]
            vals.append(float(rows[node][1 + comp]))
        print("compliance %d %s" % (nc, " ".join("%.7e" % v for v in vals)))


if __name__ == "__main__":
    what, sizes = sys.argv[1], [int(a) for a in sys.argv[2:]]
    for s in sizes:
        if what == "msh":
            write_msh(s)
        elif what == "ccx":
            write_ccx(s, False)
            write_ccx(s, True)
            write_ccx(s, False, knot=True)
        elif what == "skin":
            write_ccx(s, False, bare=True)
        elif what == "ccx-crossply":
            write_ccx(s, False, angles=CROSSPLY, tag="crossply")
    if what == "section":
        write_section()
    if what == "stringer":
        write_stringer_alone(sizes[0] if sizes else 32)
        for k, v in stringer_closed_form().items():
            print("stringer_closed_form", k, " ".join("%.5f" % x for x in v))
    if what == "--collect":
        collect(sizes)
