#!/usr/bin/python3
"""Deformed shapes of a multibody run: a ParaView animation and PNG snapshots.

  /usr/bin/python3 animate.py SCENE.yaml RESULTS.h5 --out DIR
        [--every N] [--scale S] [--snapshots T1,T2,...] [--visual NAME=BODY.h5 ...]

For every output time (every N-th), each body is drawn in the global frame:
flexible bodies as their deformed mesh, x = r + A (s0 + S * sum_j w_j phi_j),
from the body file named in the scene (S = --scale magnifies the elastic
displacement, 1 = true size); rigid bodies as the mesh of a body file given
with --visual NAME=FILE (e.g. a panel's flexible body file, undeformed), or else
as sticks between their joint points. Writes

  DIR/NAME_NNNN.vtp and DIR/NAME.pvd   a VTK PolyData series ParaView opens as an
                                        animation (point data: elastic displacement)
  DIR/NAME_t=T.png                      a 3-D snapshot at each --snapshots time

Only Debian's python3-h5py, python3-yaml, python3-numpy and python3-matplotlib
are needed (run with /usr/bin/python3).
"""
import argparse
import os
import sys

import h5py
import numpy as np
import yaml


def rotation(p):
    """A(p) for Euler parameters [e0, e1, e2, e3] (Nikravesh 1988, eq. 6.19)."""
    e0, e = p[0], np.asarray(p[1:])
    s = np.array([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
    return (2 * e0 * e0 - 1) * np.eye(3) + 2 * (np.outer(e, e) + e0 * s)


class BodyShape:
    """Undeformed geometry of one body in its own frame, and its mode shapes."""

    def __init__(self, name):
        self.name = name
        self.nodes = np.zeros((0, 3))
        self.triangles = np.zeros((0, 3), dtype=np.int64)
        self.lines = np.zeros((0, 2), dtype=np.int64)
        self.modes = np.zeros((0, 0, 3))  # (n_modes, n_nodes, 3) translations

    @staticmethod
    def from_body_file(name, path, n_modes):
        b = BodyShape(name)
        with h5py.File(path, "r") as f:
            b.nodes = f["mesh/nodes"][:]
            if "mesh/triangles" in f:
                b.triangles = f["mesh/triangles"][:].astype(np.int64)
            if "mesh/beams" in f:
                b.lines = f["mesh/beams"][:].astype(np.int64)
            if n_modes > 0:
                b.modes = f["modes/shapes"][:n_modes, :, :3]
        return b

    @staticmethod
    def from_points(name, points):
        """A stick figure: every attachment point joined to their centroid."""
        b = BodyShape(name)
        pts = np.unique(np.array(points, dtype=float).reshape(-1, 3), axis=0)
        if len(pts) == 0:
            pts = np.zeros((1, 3))
        centre = pts.mean(axis=0)
        b.nodes = np.vstack([centre, pts])
        b.lines = np.array([[0, k] for k in range(1, len(b.nodes))], dtype=np.int64).reshape(-1, 2)
        return b

    def placed(self, r, p, w, scale):
        """Global node positions and elastic displacement magnitudes."""
        u = np.zeros_like(self.nodes)
        if w is not None and len(self.modes):
            u = np.tensordot(w[: len(self.modes)], self.modes, axes=1)
        x = r + (self.nodes + scale * u) @ rotation(p).T
        return x, np.linalg.norm(u, axis=1)


def load_shapes(scene_path, visuals):
    with open(scene_path) as fh:
        scene = yaml.safe_load(fh)
    base = os.path.dirname(os.path.abspath(scene_path))
    points = {}
    for j in scene.get("joints", []) or []:
        for body, pt in zip(j.get("bodies", []), j.get("points", [])):
            if isinstance(pt, list):
                points.setdefault(body, []).append(pt)
    shapes = {}
    for b in scene["bodies"]:
        name = b["name"]
        if "flexible" in b:
            fl = b["flexible"]
            path = fl["file"] if os.path.isabs(fl["file"]) else os.path.join(base, fl["file"])
            modes = fl.get("modes", 0)  # "all": every mode of the file (Craig-Bampton bodies)
            shapes[name] = BodyShape.from_body_file(name, path, 1 << 30 if modes == "all" else int(modes))
        elif name in visuals:
            shapes[name] = BodyShape.from_body_file(name, visuals[name], 0)
        else:
            shapes[name] = BodyShape.from_points(name, points.get(name, []))
    return shapes


def frame_geometry(f, shapes, k, scale):
    """All bodies at output k, merged: points, triangles, lines, displacement, body id."""
    xs, us, tris, lines, ids_t, ids_l = [], [], [], [], [], []
    offset = 0
    for bid, (name, s) in enumerate(shapes.items()):
        g = f["bodies"][name]
        w = g["modal_coordinates"][k] if "modal_coordinates" in g else None
        x, u = s.placed(g["position"][k], g["orientation"][k], w, scale)
        xs.append(x)
        us.append(u)
        tris.append(s.triangles + offset)
        lines.append(s.lines + offset)
        ids_t += [bid] * len(s.triangles)
        ids_l += [bid] * len(s.lines)
        offset += len(x)
    return (np.vstack(xs), np.concatenate(us), np.vstack(tris).astype(np.int64),
            np.vstack(lines).astype(np.int64), np.array(ids_l + ids_t))


def write_vtp(path, x, u, tris, lines, ids):
    def arr(a, fmt):
        return " ".join(fmt % v for v in np.ravel(a))

    def cells(c):
        n = c.shape[1] if len(c) else 0
        return arr(c, "%d"), arr(np.arange(1, len(c) + 1) * n, "%d")

    lc, lo = cells(lines)
    tc, to = cells(tris)
    with open(path + ".tmp", "w") as fh:
        fh.write('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n'
                 f'<PolyData><Piece NumberOfPoints="{len(x)}" NumberOfVerts="0" NumberOfLines="{len(lines)}"'
                 f' NumberOfStrips="0" NumberOfPolys="{len(tris)}">\n'
                 '<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">'
                 f'{arr(x, "%.9g")}</DataArray></Points>\n'
                 '<PointData Scalars="elastic_displacement"><DataArray type="Float64" Name="elastic_displacement" format="ascii">'
                 f'{arr(u, "%.6g")}</DataArray></PointData>\n'
                 '<CellData Scalars="body"><DataArray type="Int32" Name="body" format="ascii">'
                 f'{arr(ids, "%d")}</DataArray></CellData>\n'
                 f'<Lines><DataArray type="Int64" Name="connectivity" format="ascii">{lc}</DataArray>'
                 f'<DataArray type="Int64" Name="offsets" format="ascii">{lo}</DataArray></Lines>\n'
                 f'<Polys><DataArray type="Int64" Name="connectivity" format="ascii">{tc}</DataArray>'
                 f'<DataArray type="Int64" Name="offsets" format="ascii">{to}</DataArray></Polys>\n'
                 '</Piece></PolyData></VTKFile>\n')
    os.replace(path + ".tmp", path)


def snapshot(path, x, u, tris, lines, t, title, umax):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    fig = plt.figure(figsize=(7, 5.5))
    ax = fig.add_subplot(projection="3d")
    if len(tris):
        cmap = plt.get_cmap("viridis")
        face_u = u[tris].mean(axis=1) / (umax if umax > 0 else 1.0)
        ax.add_collection3d(Poly3DCollection(x[tris], facecolors=cmap(face_u), edgecolor="k",
                                             linewidths=0.2, alpha=0.9))
    if len(lines):
        ax.add_collection3d(Line3DCollection(x[lines], colors="tab:red", linewidths=1.5))
    lo, hi = x.min(axis=0), x.max(axis=0)
    c, half = (lo + hi) / 2, (hi - lo).max() / 2 + 0.05
    ax.set_xlim(c[0] - half, c[0] + half)
    ax.set_ylim(c[1] - half, c[1] + half)
    ax.set_zlim(c[2] - half, c[2] + half)
    ax.set_xlabel("X [m]")
    ax.set_ylabel("Y [m]")
    ax.set_zlabel("Z [m]")
    ax.view_init(elev=20, azim=-60)
    ax.set_title(f"{title}, t = {t:.2f} s (max elastic displacement {u.max() * 1e3:.2f} mm)")
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("results")
    ap.add_argument("--out", required=True)
    ap.add_argument("--name", help="file stem (default: the results file's)")
    ap.add_argument("--every", type=int, default=5, help="write every N-th output time")
    ap.add_argument("--scale", type=float, default=1.0, help="magnification of elastic displacements")
    ap.add_argument("--snapshots", default="", help="comma-separated times for PNG snapshots")
    ap.add_argument("--visual", action="append", default=[], metavar="NAME=BODY.h5",
                    help="draw rigid body NAME with the mesh of a body file")
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    visuals = dict(v.split("=", 1) for v in a.visual)
    shapes = load_shapes(a.scene, visuals)
    stem = a.name or os.path.splitext(os.path.basename(a.results))[0]
    os.makedirs(a.out, exist_ok=True)
    with h5py.File(a.results, "r") as f:
        t = f["time"][:]
        frames = list(range(0, len(t), max(1, a.every)))
        entries = []
        for n, k in enumerate(frames):
            x, u, tris, lines, ids = frame_geometry(f, shapes, k, a.scale)
            name = f"{stem}_{n:04d}.vtp"
            write_vtp(os.path.join(a.out, name), x, u, tris, lines, ids)
            entries.append(f'<DataSet timestep="{t[k]:.6g}" part="0" file="{name}"/>')
        pvd = os.path.join(a.out, stem + ".pvd")
        with open(pvd + ".tmp", "w") as fh:
            fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                     + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
        os.replace(pvd + ".tmp", pvd)
        print(f"{pvd}: {len(frames)} frames, t = {t[0]:.3g} .. {t[-1]:.3g} s")
        times = [float(s) for s in a.snapshots.split(",") if s.strip()]
        geos = [frame_geometry(f, shapes, int(np.argmin(abs(t - ts))), a.scale) for ts in times]
        umax = max([g[1].max() for g in geos], default=0.0)
        for ts, g in zip(times, geos):
            k = int(np.argmin(abs(t - ts)))
            png = os.path.join(a.out, f"{stem}_t={t[k]:.2f}.png")
            snapshot(png, g[0], g[1], g[2], g[3], t[k], a.title or stem, umax)
            print(png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
