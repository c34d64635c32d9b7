#!/usr/bin/env python3
"""Writes plate_mesh.inp: a free steel plate (mm) 200 x 100 x 2 (x, y, z), mid-surface
z = 0, centred, in NX x NY x 1 twenty-node bricks (C3D20), 20 x 10 unless given.
Run: python3 make_plate.py [NX NY]. The deck writer is
examples/imported-fitting/brick_deck.py."""
import itertools, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "examples", "imported-fitting"))
from brick_deck import BrickMesh

NX = int(sys.argv[1]) if len(sys.argv) > 1 else 20
NY = int(sys.argv[2]) if len(sys.argv) > 2 else 10
L, W, H = 200.0, 100.0, 2.0
mesh = BrickMesh()
for i, j in itertools.product(range(NX), range(NY)):
    mesh.add_brick((-L / 2 + L * i / NX, -L / 2 + L * (i + 1) / NX),
                   (-W / 2 + W * j / NY, -W / 2 + W * (j + 1) / NY),
                   (-H / 2, H / 2))
mesh.write("plate_mesh.inp", "free steel plate 200 x 100 x 2 mm, %d x %d C3D20; written by make_plate.py" % (NX, NY), "C3D20")
