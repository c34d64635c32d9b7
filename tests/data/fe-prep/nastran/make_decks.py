#!/usr/bin/env python3
"""The stiffened panel of examples/stiffened-panel (0.8 x 0.5 m CFRP skin
[0/45/-45/90]s of IM6, two aluminium 4 x 25 mm stringers along x at
y = +-0.125 m, root edge x = -0.4 m, a 0.15 kg fitting at the corner
(0.4, 0.25)) on a structured 16 x 8 quadrilateral mesh, written twice from the
same node and element lists:

  panel.msh            gmsh 2.2 with physical groups skin, stringers, root, fitting
  panel_small.bdf      Nastran small field (executive + case control, BEGIN BULK,
                       INCLUDE of panel_grids_small.inc, '+' and blank continuations,
                       PCOMP with LAM = SYM, $ comments)
  panel_large.bdf      large field (GRID*, '*' continuations), MCID on a CORD2R
  panel_free.bdf       free field (commas, '+' continuations)
  panel_mm.bdf         small field in mm-t-s (N, MPa, t/mm^3)

Every number is written so that it reads back exactly (checked below), so
the decks and the .msh carry the same mesh and properties.
Run: python3 make_decks.py (writes next to itself).
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))
NX, NY = 16, 8
X0, X1, Y0, Y1 = -0.4, 0.4, -0.25, 0.25


def node_id(i, j):
    return 1 + i + (NX + 1) * j


nodes = {}
for j in range(NY + 1):
    for i in range(NX + 1):
        nodes[node_id(i, j)] = ((i - NX // 2) / 20, (j - NY // 2) / 16, 0.0)  # exact decimals: 0.05 and 0.0625 steps
quads = []
for j in range(NY):
    for i in range(NX):
        quads.append((node_id(i, j), node_id(i + 1, j), node_id(i + 1, j + 1), node_id(i, j + 1)))
stringer_rows = [2, 6]  # y = -0.125, +0.125
bars = [(node_id(i, j), node_id(i + 1, j)) for j in stringer_rows for i in range(NX)]
root = [node_id(0, j) for j in range(NY + 1)]
root_lines = [(node_id(0, j), node_id(0, j + 1)) for j in range(NY)]
corner = node_id(NX, NY)
hinge = node_id(0, NY // 2)  # (-0.4, 0, 0)

# gmsh 2.2: physical 1 skin (2D), 2 stringers (1D), 3 root (1D), 4 fitting (0D).
with open(os.path.join(HERE, "panel.msh"), "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n4\n")
    f.write('2 1 "skin"\n1 2 "stringers"\n1 3 "root"\n0 4 "fitting"\n$EndPhysicalNames\n')
    f.write("$Nodes\n%d\n" % len(nodes))
    for k, (x, y, z) in nodes.items():
        f.write("%d %r %r %r\n" % (k, x, y, z))
    f.write("$EndNodes\n$Elements\n")
    elems = []
    elems += ["15 2 4 1 %d" % corner]
    elems += ["1 2 2 1 %d %d" % b for b in bars]
    elems += ["1 2 3 2 %d %d" % b for b in root_lines]
    elems += ["3 2 1 3 %d %d %d %d" % q for q in quads]
    f.write("%d\n" % len(elems))
    for e, s in enumerate(elems, 1):
        f.write("%d %s\n" % (e, s))
    f.write("$EndElements\n")


def fmt8(x):
    """Shortest Nastran real of at most 8 characters that reads back exactly."""
    if isinstance(x, int) or isinstance(x, str):
        return str(x)
    cands = [repr(float(x))]
    for p in range(1, 8):
        s = "%.*e" % (p, x)
        m, e = s.split("e")
        m = m.rstrip("0")
        if "." not in m:
            m += "."
        cands.append(m + ("%+d" % int(e)))
    for c in sorted(cands, key=len):
        cc = c
        if cc.endswith(".0"):
            cc = cc[:-1]
        if cc.startswith("0."):
            cc = cc[1:]
        if cc.startswith("-0."):
            cc = "-" + cc[2:]
        if cc in (".", "-."):
            cc = "0."
        if len(cc) <= 8 and read_real(cc) == float(x):
            return cc
    raise ValueError("no exact 8-character form of %r" % x)


def read_real(s):
    t = s.upper().replace("D", "E")
    for k in range(1, len(t)):
        if t[k] in "+-" and t[k - 1] != "E":
            t = t[:k] + "E" + t[k:]
            break
    return float(t)


def fmt16(x):
    if isinstance(x, (int, str)):
        return str(x)
    s = repr(float(x))
    assert len(s) <= 16 and float(s) == x, s
    return s


def small(name, fields, cont="+"):
    """Small field: 8 data fields a line; continuations start with `cont` ('+' or ' ')."""
    fs = [fmt8(v) if v is not None else "" for v in fields]
    out = []
    for r in range(0, max(1, len(fs)), 8):
        head = name if r == 0 else cont
        out.append(head.ljust(8) + "".join(s.rjust(8) for s in fs[r:r + 8]))
    return "\n".join(l.rstrip() for l in out) + "\n"


def large(name, fields):
    fs = [fmt16(v) if v is not None else "" for v in fields]
    out = []
    for r in range(0, max(1, len(fs)), 4):
        head = (name + "*") if r == 0 else "*"
        out.append(head.ljust(8) + "".join(s.ljust(16) for s in fs[r:r + 4]))
    return "\n".join(l.rstrip() for l in out) + "\n"


def free(name, fields):
    fs = [repr(float(v)) if isinstance(v, float) else ("" if v is None else str(v)) for v in fields]
    out = []
    for r in range(0, max(1, len(fs)), 8):
        head = name if r == 0 else "+"
        out.append(",".join([head] + fs[r:r + 8]))
    return "\n".join(out) + "\n"


def deck(fmt, L=1.0, M=1.0, sym=False, mcid=False):
    """The bulk data as a list of (name, fields); L, M: metres and kilograms per file unit."""
    S = M / L  # stress per file unit: (M L / s^2) / L^2 with s = 1
    cards = []
    grids = [("GRID", [k, None, x / L, y / L, z / L]) for k, (x, y, z) in nodes.items()]
    if mcid:
        cards.append(("CORD2R", [10, None, 1.0 / L, 2.0 / L, 3.0 / L, 1.0 / L, 2.0 / L, 4.0 / L, 2.0 / L, 2.0 / L, 3.0 / L]))
    rho_im6, rho_alu = 1600.0 * L ** 3 / M, 2700.0 * L ** 3 / M
    cards.append(("MAT8", [1, 177e9 / S, 10.8e9 / S, 0.27, 7.6e9 / S, 7.6e9 / S, 3.6e9 / S, rho_im6]))
    cards.append(("MAT1", [2, 70e9 / S, None, 0.33, rho_alu]))
    t = 0.00025 / L
    angles = [0.0, 45.0, -45.0, 90.0] if sym else [0.0, 45.0, -45.0, 90.0, 90.0, -45.0, 45.0, 0.0]
    plies = []
    for k, a in enumerate(angles):
        plies += [1 if k == 0 or fmt != "small" else None, t if k == 0 or fmt != "small" else None, a, None]
    cards.append(("PCOMP", [1, None, 0.2 * L * L / M, None, None, None, None, "SYM" if sym else None] + plies))
    cards.append(("PBARL", [2, 2, None, "BAR", None, None, None, None, 0.004 / L, 0.025 / L]))
    for e, q in enumerate(quads, 1):
        cards.append(("CQUAD4", [e, 1] + list(q) + ([10] if mcid else [])))
    for e, b in enumerate(bars, 1001):
        cards.append(("CBAR", [e, 2, b[0], b[1], 0.0, 1.0, 0.0]))
    cards.append(("SPC1", [1, 123456] + root))
    cards.append(("RBE2", [9100, hinge, 123456] + [g for g in root if g != hinge]))
    cards.append(("CONM2", [9200, corner, None, 0.15 / M]))
    if L != 1.0:  # the file's own round numbers (350. mm, 1.6-9 t/mm^3), not binary residues
        r = lambda v: float("%.12g" % v) if isinstance(v, float) else v
        grids = [(n, [r(v) for v in f]) for n, f in grids]
        cards = [(n, [r(v) for v in f]) for n, f in cards]
    return grids, cards


def write(path, text):
    with open(os.path.join(HERE, path), "w") as f:
        f.write(text)


grids, cards = deck("small", sym=True)
write("panel_grids_small.inc", "$ the grids of panel_small.bdf\n" + "".join(small(n, f) for n, f in grids))
body = "".join(small(n, f, cont="+" if i % 2 else " ") for i, (n, f) in enumerate(cards))
write("panel_small.bdf", "$ stiffened panel, small field (make_decks.py)\nSOL 103\nCEND\nTITLE = stiffened panel\n"
      "BEGIN BULK\n$ materials and properties\nINCLUDE 'panel_grids_small.inc'\n" + body + "ENDDATA\nGRID    999999\n")
grids, cards = deck("large", mcid=True)
write("panel_large.bdf", "$ stiffened panel, large field (make_decks.py)\n" +
      "".join(large(n, f) for n, f in grids + cards) + "ENDDATA\n")
grids, cards = deck("free")
write("panel_free.bdf", "$ stiffened panel, free field (make_decks.py)\n" +
      "".join(free(n, f) for n, f in grids + cards))
grids, cards = deck("small", L=1e-3, M=1e3)
write("panel_mm.bdf", "$ stiffened panel in mm-t-s (make_decks.py)\n" +
      "".join(small(n, f) for n, f in grids + cards))

# The example's deck (examples/stiffened-panel/panel.bdf): the mm-t-s deck with
# an executive section and comments, as a deck from a pre-processor looks.
grids, cards = deck("small", L=1e-3, M=1e3)
example = os.path.join(HERE, "..", "..", "..", "..", "examples", "stiffened-panel", "panel.bdf")
with open(example, "w") as f:
    f.write("$ The stiffened panel of panel.geo as a Nastran deck, in mm-t-s (N, MPa, t/mm^3),\n"
            "$ on a structured 16 x 8 quadrilateral mesh; written by\n"
            "$ tests/data/fe-prep/nastran/make_decks.py (README.md, 'From a Nastran deck').\n"
            "SOL 103\nCEND\nBEGIN BULK\n"
            "$ IM6 plies (MAT8) and the aluminium stringers (MAT1)\n")
    named = {"MAT8": "", "PCOMP": "$ skin: [0/45/-45/90]s, 0.25 mm plies, 0.2 kg/m^2 of paint (NSM)\n",
             "PBARL": "$ stringers: 4 x 25 mm blades (DIM1 along v = y, DIM2 along z)\n",
             "CQUAD4": "$ skin elements (THETA blank: 0 deg along G1-G2 = x)\n",
             "CBAR": "$ stringer elements on the skin's grids, v = (0, 1, 0)\n",
             "SPC1": "$ root edge (SPC set 1), the hinge (RBE2 9100) and the fitting's mass (CONM2 9200)\n"}
    seen = set()
    for n, fl in cards:
        if n in named and n not in seen:
            f.write(named[n])
            seen.add(n)
        f.write(small(n, fl))
    f.write("$ grids\n" + "".join(small(n, fl) for n, fl in grids) + "ENDDATA\n")
