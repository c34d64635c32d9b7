#!/usr/bin/python3
"""Loads and ply failure of a SAR deployment run (docs/sar-antenna.md, "Loads and ply failure").

  /usr/bin/python3 stress_report.py --run RESULTS.h5:LABEL:SCENE.yaml [--run ...] [--outdir DIR] [--markdown FILE]

For every run (a scene with `outputs: {stresses: [...]}`), from mbs-run's
/bodies/NAME/failure_index (shells) and /bodies/NAME/section_forces (beams)
and the body files the scene names (/mesh/*, /stress/plies/*):
  - the peak Tsai-Wu index of each panel: value, time, element (its centroid),
    ply (number from the bottom and angle) and the ply's stresses over its
    strengths there (which mode of failure drives it);
  - the peak section forces of each truss: bending moment |(M2, M3)|, shear
    |(V2, V3)|, torque |T| and axial |N|, with element and time;
  - a figure sar_failure_TAG.png: the panels' peak index over time, the
    trusses' peak bending moment over time, and the map of the index (largest
    over the plies) on the panel and at the time of the run's peak.
Prints a Markdown table (and writes it to --markdown). Uses Debian's
python3-h5py, python3-matplotlib and python3-yaml (run with /usr/bin/python3).
"""
import argparse
import os
import re
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def tag_of(label):
    return re.sub(r"[^a-z0-9]+", "", label.lower()) or "run"


class Panel:
    """A shell body's recovery: failure index (n_out, n_el, n_plies) and its mesh."""

    def __init__(self, name, res, body_path):
        self.name = name
        self.index = res["bodies/%s/failure_index" % name][:]
        self.stress = res["bodies/%s/ply_stress" % name][:]
        with h5py.File(body_path, "r") as b:
            self.nodes = b["mesh/nodes"][:]
            self.triangles = b["mesh/triangles"][:]
            self.centroids = b["mesh/centroids"][:]
            self.angles = b["stress/plies/angle_deg"][:]
            self.strength = b["stress/plies/strength"][:]  # (n_plies, 5): Xt Xc Yt Yc S12
            joints = {int(b["interfaces/%s/node" % k][()]) for k in b["interfaces"]}
        # Elements touching a node where a joint attaches: a point load there
        # gives a local peak that grows as the mesh is refined.
        self.at_joint = np.array([any(int(n) in joints for n in tri) for tri in self.triangles])

    def peak(self):
        k, e, p = np.unravel_index(np.argmax(self.index), self.index.shape)
        return k, e, p, self.index[k, e, p]

    def peak_away(self):
        """The peak over the elements that touch no joint node."""
        masked = np.where(self.at_joint[None, :, None], -np.inf, self.index)
        k, e, p = np.unravel_index(np.argmax(masked), masked.shape)
        return k, e, p, self.index[k, e, p]

    def drivers(self, k, e, p):
        """Each stress over the strength it acts against at (k, e, p)."""
        s1, s2, t12 = self.stress[k, e, p]
        xt, xc, yt, yc, s = self.strength[p]
        return (s1 / (xt if s1 >= 0 else xc), s2 / (yt if s2 >= 0 else yc), abs(t12) / s)


class Truss:
    """A beam body's section forces (n_out, n_el, 6): N V2 V3 T M2 M3, and,
    for a solid circular unidirectional rod whose material has strengths, the
    Tsai-Wu index of its outer fibre (beam theory: s1 = N/A +- M r/I along
    the fibres, t12 = T r/J; the shear of V, largest on the axis, is left out)."""

    def __init__(self, name, res, rod=None, joint_axial=None):
        self.name = name
        s = res["bodies/%s/section_forces" % name][:]
        self.bending = np.hypot(s[:, :, 4], s[:, :, 5])
        self.shear = np.hypot(s[:, :, 1], s[:, :, 2])
        self.torque = np.abs(s[:, :, 3])
        self.axial = np.abs(s[:, :, 0])
        # The axial force the end joints put into the truss (n_out), when its
        # modes carry no extension (the SAR trusses' two bending modes).
        self.joint_axial = joint_axial
        if joint_axial is not None:
            s = s.copy()
            s[:, :, 0] = joint_axial[:, None]
        self.rod = rod
        self.index = None
        if rod:
            d, (xt, xc, yt, yc, s12), self.p_cr = rod
            r, area = d / 2, np.pi * d * d / 4
            inertia, polar = np.pi * d ** 4 / 64, np.pi * d ** 4 / 32
            f1, f11, f66 = 1 / xt - 1 / xc, 1 / (xt * xc), 1 / s12 ** 2
            tau = self.torque * r / polar
            idx = []
            for sign in (1.0, -1.0):  # the fibre on either side of the bending axis
                s1 = s[:, :, 0] / area + sign * self.bending * r / inertia
                idx.append(f1 * s1 + f11 * s1 ** 2 + f66 * tau ** 2)
            self.index = np.maximum(*idx)

    @staticmethod
    def peak(field):
        k, e = np.unravel_index(np.argmax(field), field.shape)
        return k, e, field[k, e]


def joint_axial_force(res, scene, name, body_h5):
    """Axial force N(t) (tension > 0) of a truss from the reactions of the joints
    at its ends: the force on the truss at each end, along the outward axis
    (body x at end_max, -x at end_min), summed over the joints at that end, and
    the mean of the two ends (they differ by the truss's own axial inertia).
    None unless both ends carry a joint at a named interface."""
    with h5py.File(body_h5, "r") as b:
        pos = {k: b["interfaces/%s/position" % k][:] for k in b["interfaces"]}
    q = res["bodies/%s/orientation" % name][:]
    e0, e1, e2, e3 = q.T
    axis = np.stack([e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 + e0 * e3), 2 * (e1 * e3 - e0 * e2)], axis=1)
    ends = {1.0: 0.0, -1.0: 0.0}
    seen = {1.0: False, -1.0: False}
    for j in scene.get("joints", []):
        if name not in j["bodies"] or "joints/%s/reaction_force" % j["name"] not in res:
            continue
        i = j["bodies"].index(name)
        point = j["points"][i]
        if not isinstance(point, str) or point not in pos:
            return None
        f = res["joints/%s/reaction_force" % j["name"]][:] * (1.0 if i == 0 else -1.0)  # on the truss
        side = 1.0 if pos[point][0] > 0 else -1.0
        ends[side] = ends[side] + side * np.einsum("ij,ij->i", f, axis)
        seen[side] = True
    if not (seen[1.0] and seen[-1.0]):
        return None
    return 0.5 * (ends[1.0] + ends[-1.0])


def rod_of(scene_dir, body_h5):
    """(diameter, strengths) of a truss body built from sections/*.yaml with a solid_circle of a
    material with `strength`, by following bodies/NAME.yaml -> its section file's YAML; else None."""
    stem = os.path.splitext(os.path.basename(body_h5))[0]
    body_yaml = os.path.join(scene_dir, "bodies", stem + ".yaml")
    try:
        with open(body_yaml) as f:
            sec = yaml.safe_load(f)["body"]["beam"]["section"]
        src = os.path.join(scene_dir, "sections", os.path.splitext(os.path.basename(sec["file"]))[0] + ".yaml")
        with open(src) as f:
            section = yaml.safe_load(f)["section"]
        with open(os.path.join(scene_dir, "bodies", "materials.yaml")) as f:
            mat = yaml.safe_load(f)["materials"][section["material"]]
        st = mat["strength"]
        if section.get("shape") != "solid_circle":
            return None
        d = float(section["diameter"])
        # Euler's pinned-pinned buckling load pi^2 E1 I / L^2 of the rod.
        with open(body_yaml) as f:
            length = float(yaml.safe_load(f)["body"]["beam"]["length"])
        p_cr = np.pi ** 2 * float(mat["E1"]) * np.pi * d ** 4 / 64 / length ** 2
        return d, tuple(float(st[k]) for k in ("Xt", "Xc", "Yt", "Yc", "S12")), p_cr
    except (OSError, KeyError, TypeError):
        return None


def load(spec):
    path, label, scene = spec.split(":", 2)
    with open(scene) as f:
        sc = yaml.safe_load(f)
    files = {b["name"]: b["flexible"]["file"] for b in sc["bodies"] if "flexible" in b}
    asked = (sc.get("outputs") or {}).get("stresses") or []
    where = os.path.dirname(os.path.abspath(scene))
    panels, trusses = [], []
    with h5py.File(path, "r") as res:
        t = res["time"][:]
        # This report pairs the full fields with /time row by row (the trusses'
        # joint forces too): a run with outputs.stress_every > 1 has fewer
        # field rows (their times in /stress_time; docs/stresses.md).
        if "stress_time" in res and len(res["stress_time"]) != len(t):
            sys.exit("stress_report.py: %s decimates its stress fields (outputs.stress_every > 1); run the scene "
                     "without stress_every for this report, or read the envelope (failure_index_peak) it writes"
                     % path)
        for name in asked:
            body_h5 = os.path.join(where, files[name])
            # A truss whose section carries a recovery basis has ply failure indices too
            # (docs/stresses.md, "Beams: ply stresses from the section"): what makes a
            # panel is its triangles.
            with h5py.File(body_h5, "r") as b:
                shell = "mesh/triangles" in b
            if shell and "bodies/%s/failure_index" % name in res:
                panels.append(Panel(name, res, body_h5))
            elif "bodies/%s/section_forces" % name in res:
                trusses.append(Truss(name, res, rod_of(where, files[name]),
                                     joint_axial_force(res, sc, name, body_h5)))
        status = res.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else str(status)
    if not panels and not trusses:
        sys.exit("stress_report.py: %s has no failure_index or section_forces: does %s name bodies in "
                 "outputs: {stresses: [...]}?" % (path, scene))
    return label, t, panels, trusses, status


def figure(label, t, panels, trusses, outdir):
    fig = plt.figure(figsize=(10, 6.4), dpi=80)
    ax1 = fig.add_subplot(2, 2, 1)
    for p in panels:
        ax1.plot(t, p.index.reshape(len(t), -1).max(axis=1), lw=0.8, label=p.name)
    ax1.axhline(1.0, color="k", lw=0.6, ls="--")
    ax1.set_xlabel("t [s]")
    ax1.set_ylabel("peak Tsai-Wu index")
    ax1.set_title("panels: largest index over elements and plies", fontsize=9)
    ax1.legend(fontsize=8)
    ax2 = fig.add_subplot(2, 2, 3)
    for tr in trusses:
        ax2.plot(t, tr.bending.max(axis=1), lw=0.7, label=tr.name)
    ax2.set_xlabel("t [s]")
    ax2.set_ylabel("peak |M| [N m]")
    ax2.set_title("trusses: largest bending moment over elements", fontsize=9)
    ax2.legend(fontsize=7, ncol=3)
    ax3 = fig.add_subplot(1, 2, 2)
    if panels:
        best = max(panels, key=lambda p: p.peak()[3])
        k, e, ply, v = best.peak()
        values = best.index[k].max(axis=1)
        polys = [best.nodes[tri, :2] for tri in best.triangles]
        pc = PolyCollection(polys, array=values, cmap="viridis", edgecolors="face")
        ax3.add_collection(pc)
        ax3.autoscale_view()
        ax3.set_aspect("equal")
        ax3.plot(*best.centroids[e, :2], "r+", ms=12, mew=2)
        fig.colorbar(pc, ax=ax3, shrink=0.7, label="Tsai-Wu index (largest over plies)")
        ax3.set_xlabel("body x [m] (panel length)")
        ax3.set_ylabel("body y [m]")
        ax3.set_title("%s at t = %.2f s (peak %.3g, ply %d, +)" % (best.name, t[k], v, ply + 1), fontsize=9)
    fig.suptitle("%s: loads and ply failure" % label)
    fig.tight_layout()
    out = os.path.join(outdir, "sar_failure_%s.png" % tag_of(label))
    fig.savefig(out)
    plt.close(fig)
    return out


def table(label, t, panels, trusses, status):
    lines = ["### %s (run status: %s)" % (label, status), "",
             "| panel | where | peak Tsai-Wu index | t [s] | element (centroid x, y [m]) | ply (angle) | s1/X, s2/Y, t12/S there |",
             "|---|---|---|---|---|---|---|"]
    for p in panels:
        for where, (k, e, ply, v) in (("all elements", p.peak()), ("away from the joint nodes", p.peak_away())):
            d = p.drivers(k, e, ply)
            c = p.centroids[e]
            lines.append("| %s | %s | %.3g | %.2f | %d (%.3f, %.3f) | %d (%g deg) | %+.3f, %+.3f, %.3f |"
                         % (p.name, where, v, t[k], e, c[0], c[1], ply + 1, p.angles[ply], d[0], d[1], d[2]))
    lines += ["", "| truss | peak bending moment [N m] (element, t [s]) | peak shear [N] | peak torque [N m] | "
              "peak axial, modes [N] | axial from the end joints: max tension, max compression [N] (t [s]) | "
              "outer-fibre Tsai-Wu index (t [s]) | Euler load pi^2 E1 I / L^2 [N] |", "|---|---|---|---|---|---|---|---|"]
    for tr in trusses:
        cells = []
        for field in (tr.bending, tr.shear, tr.torque, tr.axial):
            k, e, v = Truss.peak(field)
            cells.append("%.3g (%d, %.2f)" % (v, e, t[k]))
        if tr.joint_axial is not None:
            kt, kc = np.argmax(tr.joint_axial), np.argmin(tr.joint_axial)
            cells.append("%.3g (%.2f), %.3g (%.2f)" % (tr.joint_axial[kt], t[kt], tr.joint_axial[kc], t[kc]))
        else:
            cells.append("-")
        if tr.index is not None:
            k, e, v = Truss.peak(tr.index)
            cells.append("%.3g (%.2f)" % (v, t[k]))
            cells.append("%.3g" % tr.p_cr)
        else:
            cells += ["-", "-"]
        lines.append("| %s | %s |" % (tr.name, " | ".join(cells)))
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--run", action="append", required=True, help="RESULTS.h5:LABEL:SCENE.yaml")
    ap.add_argument("--outdir", default="out/plots")
    ap.add_argument("--markdown", help="also write the tables to this file")
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    text = ""
    for spec in a.run:
        label, t, panels, trusses, status = load(spec)
        print("wrote", figure(label, t, panels, trusses, a.outdir), file=sys.stderr)
        text += table(label, t, panels, trusses, status) + "\n"
    print(text, end="")
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
