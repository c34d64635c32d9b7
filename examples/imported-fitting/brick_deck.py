"""Twenty-node brick meshes written as CalculiX/Abaqus decks: the one writer
behind make_fitting.py here and the test fixtures' make_bar.py and make_plate.py
(tests/data/import/). Nodes are numbered in order of first use, shared by
coordinates rounded to 1e-9; each brick is given by its corner box."""

EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


class BrickMesh:
    def __init__(self):
        self.nodes = {}      # rounded (x, y, z) -> label
        self.elements = []   # 20 labels each: 8 corners, then the 12 edge midpoints (EDGES)

    def node(self, p):
        key = tuple(round(c, 9) for c in p)
        if key not in self.nodes:
            self.nodes[key] = len(self.nodes) + 1
        return self.nodes[key]

    def add_brick(self, x, y, z):
        """A brick on the box x = (x0, x1), y = (y0, y1), z = (z0, z1)."""
        (x0, x1), (y0, y1), (z0, z1) = x, y, z
        c = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
        corners = [self.node(p) for p in c]
        mids = [self.node(tuple(0.5 * (c[a][d] + c[b][d]) for d in range(3))) for a, b in EDGES]
        self.elements.append(corners + mids)

    def write(self, path, heading, element_type, nsets=()):
        """The deck: a '** heading' line, *NODE (NSET=NALL), *ELEMENT (ELSET=EALL; 15
        nodes on the first line, 5 on its continuation), then each (name, labels) of
        `nsets` as an *NSET of 8 labels a line."""
        with open(path, "w") as f:
            f.write(f"** {heading}\n*NODE, NSET=NALL\n")
            for p, n in sorted(self.nodes.items(), key=lambda kv: kv[1]):
                f.write(f"{n}, {p[0]:.6f}, {p[1]:.6f}, {p[2]:.6f}\n")
            f.write(f"*ELEMENT, TYPE={element_type}, ELSET=EALL\n")
            for e, conn in enumerate(self.elements, 1):
                f.write(f"{e}, " + ", ".join(map(str, conn[:15])) + ",\n" + ", ".join(map(str, conn[15:])) + "\n")
            for name, ids in nsets:
                f.write(f"*NSET, NSET={name}\n")
                for i in range(0, len(ids), 8):
                    f.write(", ".join(map(str, ids[i:i + 8])) + "\n")
        print(len(self.nodes), "nodes", len(self.elements), "elements")
