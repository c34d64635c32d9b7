#!/usr/bin/env python3
"""Where the lateral stays cross the other panel's mid-plane (docs/sar-antenna.md, "The stays at the hinge edge").

    stay_crossing.py RESULTS.h5 [...]                      # the bodies' frames only
    stay_crossing.py --bodies SCENE.yaml RESULTS.h5 [...]  # also the deformed meshes of a flexible scene

The contact monitor reports 0 m for the pairs B9-B3 and B10-B2 in every flexible model: it gives the
smallest distance, not on which side of an edge the stay passes. Each stay runs from its knee (R3 for B9,
R2 for B10) to the hinge-2/3 axis on its own panel (S14, S16), so it must cross the plane of the other
panel, whose hinge edge lies under that axis. This script finds, at every output row, where the stay's
axis (its frame's x axis, length 1.24 m, centred) meets the other panel's mid-plane (the panel frame's
x-y plane) and how far that point lies past the panel's hinge edge (> 0: inside the 2.0 x 1.3 m
rectangle, i.e. through the panel; < 0: in the hinge gap). Frames only: the elastic deflections of the
stay and of the panel's edge (millimetres near the hinge, whose corners S8/S12 hold the edge) are not
included, so the figures are the rigid-frame geometry of each row. With --bodies (the scene the results
came from, flexible bodies from their files), each row's deformed stay (its beam nodes) is intersected
with the panel's deformed triangles, and the pierced point's undeformed position gives how far inside
the panel's hinge edge the stay passes through the panel itself.
"""
import os
import sys

import h5py
import numpy as np

STAY_LENGTH = 1.24
HALF = (1.0, 0.65)           # the panels' half length (x) and half width (y)
PAIRS = (("B9", "B3", -1.0), ("B10", "B2", 1.0))   # stay, panel, x of that panel's hinge-2/3 edge


def rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def crossing_depth(f, stay, panel, edge):
    """Per output row: depth [m] of the stay's crossing past the hinge edge (nan: no crossing in the
    rectangle's width), and the crossing's panel y."""
    n = len(f["time"])
    depth, y = np.full(n, np.nan), np.full(n, np.nan)
    for i in range(n):
        a_s = rotation(f[f"bodies/{stay}/orientation"][i])
        a_p = rotation(f[f"bodies/{panel}/orientation"][i])
        x_s, x_p = f[f"bodies/{stay}/position"][i], f[f"bodies/{panel}/position"][i]
        ends = [(x_s + s * STAY_LENGTH / 2 * a_s[:, 0] - x_p) @ a_p for s in (-1.0, 1.0)]
        if ends[0][2] * ends[1][2] >= 0.0:
            continue
        c = ends[0] + (ends[1] - ends[0]) * (ends[0][2] / (ends[0][2] - ends[1][2]))
        if abs(c[1]) > HALF[1]:
            continue
        depth[i] = (c[0] - edge) if edge < 0 else (edge - c[0])
        y[i] = c[1]
    return depth, y


def deformed(f, body, mesh, i):
    """Global node positions of a flexible body at output row i (frame + modal displacement)."""
    nodes, shapes = mesh
    q = f[f"bodies/{body}/modal_coordinates"][i]
    u = nodes + np.tensordot(q, shapes[:len(q), :, 0:3], axes=1)
    return f[f"bodies/{body}/position"][i] + u @ rotation(f[f"bodies/{body}/orientation"][i]).T


def pierce_depth(f, stay, panel, edge, meshes):
    """Per output row: how far inside the hinge edge [m] the deformed stay passes through the deformed
    panel (nan: it does not pass through any triangle)."""
    nodes_p, _ = meshes[panel]
    tri = meshes[panel + "/triangles"]
    depth = np.full(len(f["time"]), np.nan)
    for i in range(len(depth)):
        s = deformed(f, stay, meshes[stay], i)
        p = deformed(f, panel, meshes[panel], i)
        a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
        for o, e in zip(s[:-1], s[1:]):           # each beam element of the stay (Moller-Trumbore)
            d = e - o
            e1, e2 = b - a, c - a
            h = np.cross(d, e2)
            det = np.einsum("ij,ij->i", e1, h)
            ok = np.abs(det) > 1e-14
            inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
            r = o - a
            u = inv * np.einsum("ij,ij->i", r, h)
            qv = np.cross(r, e1)
            v = inv * (qv @ d)
            w = inv * np.einsum("ij,ij->i", e2, qv)
            hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (w >= 0) & (w <= 1)
            for k in np.where(hit)[0]:
                x0 = ((1 - u[k] - v[k]) * nodes_p[tri[k, 0]] + u[k] * nodes_p[tri[k, 1]] + v[k] * nodes_p[tri[k, 2]])[0]
                dk = (x0 - edge) if edge < 0 else (edge - x0)
                depth[i] = dk if np.isnan(depth[i]) else max(depth[i], dk)
    return depth


def load_meshes(scene_path):
    import yaml
    scene = yaml.safe_load(open(scene_path))
    meshes = {}
    for b in scene["bodies"]:
        if "flexible" not in b:
            continue
        with h5py.File(os.path.join(os.path.dirname(os.path.abspath(scene_path)), b["flexible"]["file"]), "r") as g:
            meshes[b["name"]] = (g["mesh/nodes"][()], g["modes/shapes"][()])
            if "triangles" in g["mesh"]:
                meshes[b["name"] + "/triangles"] = g["mesh/triangles"][()]
    return meshes


def main(paths):
    meshes = None
    if paths[:1] == ["--bodies"]:
        meshes, paths = load_meshes(paths[1]), paths[2:]
    for path in paths:
        with h5py.File(path, "r") as f:
            t = f["time"][()]
            if meshes is not None:
                for stay, panel, edge in PAIRS:
                    depth = pierce_depth(f, stay, panel, edge, meshes)
                    for name, m in (("phase 1", t <= 10.0), ("phase 2", t > 10.0)):
                        d = np.where(m, depth, np.nan)
                        if np.all(np.isnan(d)):
                            print(f"{path}: {stay}-{panel} {name}, deformed: never through the panel")
                            continue
                        k = int(np.nanargmax(d))
                        print(f"{path}: {stay}-{panel} {name}, deformed: through the panel in {int(np.sum(~np.isnan(d)))} "
                              f"rows, {t[~np.isnan(d)][0]:.2f}-{t[~np.isnan(d)][-1]:.2f} s; deepest {1e3 * d[k]:.1f} mm "
                              f"inside the hinge edge at {t[k]:.2f} s")
            for stay, panel, edge in PAIRS:
                depth, y = crossing_depth(f, stay, panel, edge)
                for name, m in (("phase 1", t <= 10.0), ("phase 2", t > 10.0)):
                    d = np.where(m, depth, np.nan)
                    if np.all(np.isnan(d)):
                        print(f"{path}: {stay}-{panel} {name}: no crossing within the panel's width")
                        continue
                    k = int(np.nanargmax(d))
                    print(f"{path}: {stay}-{panel} {name}: crosses the mid-plane in {int(np.sum(~np.isnan(d)))} rows; "
                          f"deepest {1e3 * d[k]:+.1f} mm past the hinge edge at {t[k]:.2f} s (panel y {y[k]:+.3f} m)")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
