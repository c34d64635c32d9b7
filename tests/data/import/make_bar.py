#!/usr/bin/env python3
"""Writes bar_mesh.inp: a free steel bar (mm) 240 x 20 x 10 (x, y, z) on the x
axis (y, z centred) in NX x NY x NZ twenty-node bricks (C3D20), 12 x 1 x 1 unless
given. Run: python3 make_bar.py [NX [NY NZ]] (no other arguments). The deck
writer is examples/imported-fitting/brick_deck.py."""
import itertools, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "examples", "imported-fitting"))
from brick_deck import BrickMesh

NX = int(sys.argv[1]) if len(sys.argv) > 1 else 12
NY = int(sys.argv[2]) if len(sys.argv) > 2 else 1
NZ = int(sys.argv[3]) if len(sys.argv) > 3 else 1
L, W, H = 240.0, 20.0, 10.0
mesh = BrickMesh()
for i, j, k in itertools.product(range(NX), range(NY), range(NZ)):
    mesh.add_brick((L * i / NX, L * (i + 1) / NX),
                   (-W / 2 + W * j / NY, -W / 2 + W * (j + 1) / NY),
                   (-H / 2 + H * k / NZ, -H / 2 + H * (k + 1) / NZ))
mesh.write("bar_mesh.inp", "free steel bar 240 x 20 x 10 mm, %d C3D20; written by make_bar.py" % NX, "C3D20")
