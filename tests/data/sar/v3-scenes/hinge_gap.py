#!/usr/bin/env python3
"""Open a hinge gap between panels 2 and 3 of the SAR scenes and panel bodies (docs/sar-antenna.md,
"The hinge-2/3 gap").

    hinge_gap.py GAP FILE [...]      # GAP in m; sar-*.yaml scenes and bodies/panel[23]_*.yaml, edited in place

The reconstruction puts hinge 2/3 (S8, S12, H23) exactly on the panels' edges, so deployed panels 2 and 3
abut with no gap and the knees and stays, which lie in the hinge's bisector plane, pass through that seam
0.1-0.6 mm from the edges (rigid). GAP opens the seam: each hinge pin stands GAP/2 beyond its panel's edge
on a bracket carried by the edge node (fe-prep's `bracket:`), and every point of the hinge-2/3 mechanism on
the panels (the knee anchors S6, S9, S10, S11 and the stay ends S14, S16) moves GAP/2 towards the hinge with
it. The mechanism is then the same relative to the hinge line (the same knee, the same 0.030-rad minimum);
only the panels stand GAP/2 off each side. Stowed, both sides move GAP/2 the same way in global x, so the
stowed stack is unchanged and the trusses B5-B10 start GAP/2 further along -x. Run once on the gap-free files.
"""
import re
import sys

GAP = float(sys.argv[1])
H = GAP / 2


def num(x):
    return repr(round(x, 9))


# panel-local points of the hinge-2/3 mechanism: (name, old x, new x); y and z unchanged
PANEL2 = {"S6": (0.004151058, 0.004151058 + H), "S10": (-0.195, -0.195 + H)}
PANEL3 = {"S9": (-0.004151058, -0.004151058 - H), "S11": (0.195, 0.195 - H)}
PINS2 = ("S8", "S12", "S14", "H23")   # x = 1.0 on panel 2
PINS3 = ("S8", "S12", "S16", "H23")   # x = -1.0 on panel 3


def body(text, path):
    p3 = "panel3" in path
    moved, pins, edge = (PANEL3, PINS3, -1.0) if p3 else (PANEL2, PINS2, 1.0)
    out = []
    for line in text.splitlines(keepends=True):
        m = re.match(r"^(\s+)(\w+): \[(\S+), (\S+), (\S+)\]\s*$", line)
        if m and m.group(2) in pins and float(m.group(3)) == edge:
            ind, n, _, y, z = m.groups()
            line = f"{ind}{n}: {{point: [{num(edge + (H if edge > 0 else -H))}, {y}, {z}], bracket: [{edge}, {y}]}}\n"
        elif m and m.group(2) in moved:
            ind, n, x, y, z = m.groups()
            assert abs(float(x) - moved[n][0]) < 1e-12, (path, n, x)
            line = f"{ind}{n}: [{num(moved[n][1])}, {y}, {z}]\n"
        out.append(line)
    return "".join(out)


def scene(text, path):
    # trusses B5-B10 start GAP/2 further along -x (the whole stowed mechanism moves with the pins)
    def shift(m):
        return f"{m.group(1)}position: [{num(float(m.group(2)) - H)}, "
    text = re.sub(r"(- name: B(?:5|6|7|8|9|10)\b[^\n]*\n(?:[^\n]*\n)*?\s+)position: \[(\S+), ", shift, text)
    rigid = "rigid:" in text.split("- name: B2")[1].split("- name: B3")[0]
    reps = []
    if rigid:  # panel points in the joints themselves
        reps += [("[1.0, 0.0, -0.0705], [-1.0, 0.0, -0.0705]", f"[{num(1 + H)}, 0.0, -0.0705], [{num(-1 - H)}, 0.0, -0.0705]"),
                 ("[0.004151058, 0.65, -0.025]", f"[{num(0.004151058 + H)}, 0.65, -0.025]"),
                 ("[-0.004151058, 0.65, -0.025]", f"[{num(-0.004151058 - H)}, 0.65, -0.025]"),
                 ("[-0.195, -0.65, -0.025]", f"[{num(-0.195 + H)}, -0.65, -0.025]"),
                 ("[0.195, -0.65, -0.025]", f"[{num(0.195 - H)}, -0.65, -0.025]"),
                 ("[1.0, -0.59, -0.0705]", f"[{num(1 + H)}, -0.59, -0.0705]"),
                 ("[-1.0, 0.545, -0.025]", f"[{num(-1 - H)}, 0.545, -0.025]"),
                 ("point: [1.0, 0.65, -0.0705]", f"point: [{num(1 + H)}, 0.65, -0.0705]"),
                 ("point: [1.0, -0.65, -0.0705]", f"point: [{num(1 + H)}, -0.65, -0.0705]")]
    # the hold-down fittings and the snubber patches follow the pins S8/S12 (global x = -1 - GAP/2 stowed)
    reps += [("[-1.0, 0.65, 0.2115]", f"[{num(-1 - H)}, 0.65, 0.2115]"),
             ("[-1.0, -0.65, 0.2115]", f"[{num(-1 - H)}, -0.65, 0.2115]"),
             ("plane: {point: [-1.0, 0.65, 0.1915]", f"plane: {{point: [{num(-1 - H)}, 0.65, 0.1915]"),
             ("plane: {point: [-1.0, -0.65, 0.1915]", f"plane: {{point: [{num(-1 - H)}, -0.65, 0.1915]")]
    for a, b in reps:
        n = text.count(a)
        assert n <= 1, (path, a, n)
        text = text.replace(a, b)
    return text


for path in sys.argv[2:]:
    text = open(path).read()
    new = body(text, path) if "/bodies/" in path or path.startswith("bodies/") else scene(text, path)
    open(path, "w").write(new)
    print(path, "changed" if new != text else "unchanged")
