#!/usr/bin/env python3
"""docs/ names the code that implements each equation; this checks that every such
name still exists, so a rename cannot leave the theory pointing at nothing.

Checked, in every docs/*.md and the README:
- C++ identifiers in backticks that can only be code: camelCase with an inner capital
  (`analyzeSection`), qualified names (`AtomicH5Writer::commit`), calls (`foo()`);
  each must occur as a word in the sources (common, section-prep, fe-prep, mbs-run,
  tools, tests, bench, examples).
- Source paths in backticks (`fe-prep/xdmf_writer.cpp`, `mbs-run/run/joint_limits.h`):
  each must exist in the repository.
usage: docs_names.py SOURCE_DIR
"""
import os
import re
import sys

root = sys.argv[1]
SRC_DIRS = ["common", "section-prep", "fe-prep", "mbs-run", "tools", "tests", "bench", "examples", "cmake"]
SRC_EXT = (".cpp", ".h", ".hpp", ".py", ".sh", ".txt", ".cmake", ".in", "Makefile")

words = set()
for d in SRC_DIRS:
    for dirpath, _, files in os.walk(os.path.join(root, d)):
        for f in files:
            if f.endswith(SRC_EXT) or f == "Makefile" or "." not in f:
                try:
                    with open(os.path.join(dirpath, f), encoding="utf-8", errors="replace") as fh:
                        words.update(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", fh.read()))
                except OSError:
                    pass

ident = re.compile(r"`([A-Za-z_][A-Za-z0-9_]*(?:::[A-Za-z_~][A-Za-z0-9_]*)*)(\(\))?`")
path = re.compile(r"`((?:common|section-prep|fe-prep|mbs-run|tools|tests|bench|examples|docs)/[A-Za-z0-9_./-]+\.(?:cpp|h|py|sh|md|yaml|geo))`")
docs = [os.path.join(root, "docs", f) for f in sorted(os.listdir(os.path.join(root, "docs"))) if f.endswith(".md")]
docs.append(os.path.join(root, "README.md"))

missing = []
checked = 0
for doc in docs:
    with open(doc, encoding="utf-8") as fh:
        for lineno, line in enumerate(fh, 1):
            for m in ident.finditer(line):
                name, call = m.group(1), m.group(2)
                parts = name.split("::")
                code_like = call or len(parts) > 1 or re.search(r"^[a-z]+[A-Z]", parts[-1])
                if not code_like or parts[0] in ("std", "Eigen", "H5", "PETSc"):
                    continue
                if parts[0].startswith("H5") or parts[0].startswith("MPI_"):
                    continue  # library calls, not ours
                checked += 1
                for p in parts:
                    if p.lstrip("~") not in words:
                        missing.append(f"{os.path.relpath(doc, root)}:{lineno}: `{name}` ({p} is not in the sources)")
                        break
            for m in path.finditer(line):
                checked += 1
                if not os.path.exists(os.path.join(root, m.group(1))):
                    missing.append(f"{os.path.relpath(doc, root)}:{lineno}: `{m.group(1)}` does not exist")

for m in missing:
    print(m)
print(f"{checked} names checked, {len(missing)} missing")
sys.exit(1 if missing else 0)
