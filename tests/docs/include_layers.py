#!/usr/bin/python3
"""No include runs upward (docs/architecture.md, "The include rule").

    include_layers.py REPO      # exit 1 naming every include that breaks the rule

- The tools stand on common/ and on nothing of each other: common/ includes no
  tool, and section-prep, fe-prep and mbs-run include only common/ and
  themselves (they talk through their files).
- Inside mbs-run/ a file includes only its own folder and the layers below it
  in the picture of docs/architecture.md (a subfolder such as
  mechanics/flexible/ belongs to its folder's layer); folders of one layer do
  not include each other.
"""
import os
import re
import sys

TOOLS = ["common", "section-prep", "fe-prep", "mbs-run"]
# mbs-run's layers, bottom up (docs/architecture.md); main.cpp sits on top.
LAYERS = [["model"], ["mechanics", "integrators"], ["constrained", "tree", "monitors"], ["run"],
          ["scene", "output"]]
RANK = {folder: k for k, layer in enumerate(LAYERS) for folder in layer}
TOP = len(LAYERS)
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def mbs_folder(path):
    """The layer folder of a path under mbs-run/ ("" for mbs-run/main.cpp)."""
    parts = path.split("/")
    return parts[1] if len(parts) > 2 else ""


def problems(repo):
    out = []
    for tool in TOOLS:
        for dirpath, _, files in os.walk(os.path.join(repo, tool)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.relpath(os.path.join(dirpath, name), repo).replace(os.sep, "/")
                with open(os.path.join(repo, path), encoding="utf-8") as f:
                    text = f.read()
                for m in INCLUDE.finditer(text):
                    inc = m.group(1)
                    line = text.count("\n", 0, m.start()) + 1
                    target = inc.split("/")[0]
                    if target not in TOOLS or target == tool:
                        if tool == "mbs-run" and target == "mbs-run":
                            a, b = mbs_folder(path), mbs_folder(inc)
                            ra, rb = RANK.get(a, TOP), RANK.get(b, TOP)
                            if a != b and rb >= ra:
                                out.append(f"{path}:{line}: includes {inc}: {b or 'main'} is not below {a or 'main'}")
                        continue
                    if target != "common":
                        out.append(f"{path}:{line}: includes {inc}: {tool} may include only common/ and its own files")
    return out


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else "."
    found = problems(repo)
    for p in found:
        print(p)
    print(f"includes against the layers: {len(found)} problem(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
