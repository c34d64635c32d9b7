#!/usr/bin/env python3
"""Write a SAR panel as a Nastran bulk-data deck (the deck route, README.md "From Nastran decks").

    make_decks.py deck PANEL.yaml PANEL.h5 OUT.bdf OUT_deck.yaml
    make_decks.py scene SCENE.yaml -o OUT.yaml

`deck`: 
PANEL.yaml is the YAML route's body (bodies/panel*_layup*.yaml), PANEL.h5 the body fe-prep built from
it: the deck takes that body's own mesh (/mesh/nodes, /mesh/triangles, in fe-prep's order) so that the
two routes build the same body, element for element. It holds:
  - a GRID per mesh node (id = node index + 1) and a CTRIA3 per triangle (id = triangle index + 1,
    MCID 0: the fibre reference is the basic x axis projected on each triangle, as the YAML laminate's
    default body x axis is);
  - a PCOMP of the YAML laminate (plies bottom up, THETA their angles) with a MAT8 per orthotropic
    material (E1, E2, NU12, G12, G1Z = G13, G2Z = G23, RHO and the strengths Xt, Xc, Yt, Yc, S);
  - per interface a GRID at its point and an RBE2 (CM 123456) from it to the interface's node (the
    node fe-prep attached the YAML interface to, /interfaces/NAME/node): the point moves rigidly with
    that node, as the YAML route's point interface does (docs/fe-prep.md, "Interfaces").
OUT_deck.yaml names those RBE2s as the interfaces and repeats the YAML's reference, modes and mass.
The reference stays a `reference:` of the body YAML (the panels are pinned at their hinge interfaces,
which are not grids of the mesh: an SPC1 would hold the wrong point).

`scene`: SCENE.yaml with its panels B2 and B3 read from the deck bodies (out/bodies/panelN_LAYUP_deck.h5)
and every other path rewritten relative to OUT.yaml (mbs-run reads them relative to the scene file);
everything else unchanged.
"""
import argparse
import os
import re
import sys

import h5py
import numpy as np
import yaml


def load_with_includes(path):
    """The body YAML with its `{include: FILE}` sections read (the form the example's bodies use)."""
    doc = yaml.safe_load(open(path))
    for key, value in list(doc.items()):
        if isinstance(value, dict) and set(value) == {"include"}:
            inc = yaml.safe_load(open(os.path.join(os.path.dirname(path), value["include"])))
            doc[key] = inc[key]
    return doc


def real(x):
    """A free-field real that Nastran and fe-prep both read back to the same double."""
    return repr(float(x))


def free_card(name, fields):
    """A free-field card: 8 data fields to a line (fields 2-9; field 10 is the continuation's), then '+' lines."""
    fields = ["" if f is None else str(f) for f in fields]
    lines = [",".join([name] + fields[:8])]
    rest = fields[8:]
    while rest:
        lines.append(",".join(["+"] + rest[:8]))
        rest = rest[8:]
    return "\n".join(lines)


def deck(spec, body_h5, bdf_name):
    body = spec["body"]
    shell = body["shell"]
    plies = spec["laminates"][shell["laminate"]]
    materials = spec["materials"]
    with h5py.File(body_h5, "r") as f:
        nodes = f["mesh/nodes"][:]
        triangles = f["mesh/triangles"][:]
        interfaces = {k: (int(f["interfaces"][k]["node"][()]), f["interfaces"][k]["position"][:])
                      for k in body["interfaces"]}
    out = [f"$ {bdf_name}: {body['name']} as a Nastran deck, written by make_decks.py from the YAML route's",
           "$ mesh (docs/sar-antenna.md, \"The panels from Nastran decks\"). SI units (m, kg, s).",
           "BEGIN BULK"]
    mids = {}
    for ply in plies:
        name = ply["material"]
        if name in mids:
            continue
        m = materials[name]
        if m["type"] != "orthotropic":
            sys.exit(f"make_decks.py: material '{name}' is {m['type']}; the lay-up decks write MAT8 (orthotropic)")
        mids[name] = len(mids) + 1
        s = m.get("strength")
        strengths = [real(s[k]) for k in ("Xt", "Xc", "Yt", "Yc", "S12")] if s else [None] * 5
        out.append(f"$ {name}")
        out.append(free_card("MAT8", [mids[name], real(m["E1"]), real(m["E2"]), real(m["nu12"]), real(m["G12"]),
                                      real(m["G13"]), real(m["G23"]), real(m["rho"]),
                                      None, None, None] + strengths))
    pcomp = [1, None, None, None, None, None, None, None]  # PID, Z0 (-T/2), NSM, SB, FT, TREF, GE, LAM
    for ply in plies:
        pcomp += [mids[ply["material"]], real(ply["thickness"]), real(ply.get("angle_deg", 0.0)), None]
    out.append(f"$ laminate {shell['laminate']}, plies bottom up")
    out.append(free_card("PCOMP", pcomp))
    for i, x in enumerate(nodes):
        out.append(free_card("GRID", [i + 1, None, real(x[0]), real(x[1]), real(x[2])]))
    for e, t in enumerate(triangles):
        out.append(free_card("CTRIA3", [e + 1, 1, t[0] + 1, t[1] + 1, t[2] + 1, 0]))
    rbe = {}
    grid0 = 10 ** len(str(len(nodes))) * 10   # interface points' grids above the mesh's ids
    for k, (name, (node, point)) in enumerate(interfaces.items()):
        gid, eid = grid0 + k + 1, 9000 + k + 1
        rbe[name] = eid
        out.append(f"$ interface {name}: its point, rigid with node {node + 1}")
        out.append(free_card("GRID", [gid, None, real(point[0]), real(point[1]), real(point[2])]))
        out.append(free_card("RBE2", [eid, gid, 123456, node + 1]))
    out.append("ENDDATA")
    deck_yaml = {"body": {"name": body["name"], "mesh": {"file": bdf_name},
                          "interfaces": {name: {"rbe": eid} for name, eid in rbe.items()}}}
    for key in ("reference", "modes", "mass", "craig_bampton"):
        if key in body:
            deck_yaml["body"][key] = body[key]
    return "\n".join(out) + "\n", deck_yaml


def write_atomic(path, content):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(content)
    os.replace(tmp, path)


def deck_scene(src, output):
    src = os.path.abspath(src)
    s = yaml.safe_load(open(src))
    out_dir = os.path.dirname(os.path.abspath(output))
    swapped = []
    for b in s["bodies"]:
        fl = b.get("flexible")
        if not fl:
            continue
        path = os.path.join(os.path.dirname(src), fl["file"])
        if b["name"] in ("B2", "B3"):
            stem, ext = os.path.splitext(path)
            if not re.fullmatch(r"panel[23]_[a-z0-9]+", os.path.basename(stem)):
                sys.exit(f"make_decks.py: {src}: body {b['name']}: expected a panel file panelN_LAYUP.h5, got {fl['file']}")
            path = stem + "_deck" + ext
            swapped.append(os.path.basename(path))
        fl["file"] = os.path.relpath(path, out_dir)
    header = (f"# Generated by make_decks.py from {os.path.basename(src)}: panels B2 and B3 from their Nastran decks\n"
              f"# ({', '.join(swapped)}); everything else as in {os.path.basename(src)}. Do not edit.\n")
    os.makedirs(out_dir, exist_ok=True)
    write_atomic(output, header + yaml.safe_dump(s, default_flow_style=None, sort_keys=False, width=120))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    d = sub.add_parser("deck")
    for name in ("panel_yaml", "body_h5", "bdf", "out_yaml"):
        d.add_argument(name)
    sc = sub.add_parser("scene")
    sc.add_argument("scene")
    sc.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    if a.command == "scene":
        deck_scene(a.scene, a.output)
        return
    panel_yaml, body_h5, bdf, out_yaml = a.panel_yaml, a.body_h5, a.bdf, a.out_yaml
    text, deck_yaml = deck(load_with_includes(panel_yaml), body_h5, os.path.basename(bdf))
    head = (f"# {os.path.basename(panel_yaml)} from its Nastran deck {os.path.basename(bdf)} (written by make_decks.py):\n"
            "# the deck holds the mesh, the PCOMP/MAT8 lay-up and an RBE2 per interface.\n")
    write_atomic(bdf, text)
    write_atomic(out_yaml, head + yaml.safe_dump(deck_yaml, default_flow_style=None, sort_keys=False))


if __name__ == "__main__":
    main()
