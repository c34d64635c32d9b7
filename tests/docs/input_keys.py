#!/usr/bin/env python3
"""Every YAML key the tools accept is in docs/input-reference.md, in the section of its tool.

  input_keys.py SOURCE_DIR

The keys are read from the parsers' sources, the way the parsers name them to
fc::InputNode (common/input.h): the lists given to allowKeys({...}) (every key a
block accepts: any other is refused) and the keys looked up with node["key"],
has("key"), get("key"), number("key", ...), string("key", ...), flag("key", ...).
flexcomp-study's factors are read from its factor check. A key is documented when
it appears in backticks (`key`) in the page's section for the tool that reads it.
Exit status 1 names every missing key, where it is read and where to add it.
"""
import pathlib
import re
import sys

src = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
page_path = src / "docs" / "input-reference.md"

# Which section of the page documents the keys read by which sources.
SECTIONS = {
    "## Shared blocks (all three tools)": ["common/input.cpp", "common/materials.cpp", "common/laminate.cpp"],
    "## section-prep": ["section-prep/**/*.cpp"],
    "## fe-prep": ["fe-prep/**/*.cpp"],
    "## mbs-run": ["mbs-run/**/*.cpp"],
}
# Lookups in these files that are not input keys (maps of other things).
NOT_INPUT_KEYS = {
    ("fe-prep/build_body.cpp", "triangles"): "the body's element groups (FlexBody::elements)",
    ("fe-prep/build_body.cpp", "beams"): "the body's element groups (FlexBody::elements)",
}

ACCESS = re.compile(
    r'allowKeys\(\s*\{(?P<list>[^}]*)\}'
    r'|\[\s*"(?P<index>[A-Za-z_][A-Za-z_0-9]*)"\s*\]'
    r'|\b(?:has|get|number|string|flag)\(\s*"(?P<call>[A-Za-z_][A-Za-z_0-9]*)"'
    r'|\bforEachEntry\([^,()]*,\s*"(?P<entry>[A-Za-z_][A-Za-z_0-9]*)"', re.S)


def keys_in(path):
    text = path.read_text(encoding="utf-8")
    if "InputNode" not in text:
        return {}
    found = {}
    for m in ACCESS.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        names = re.findall(r'"([^"]+)"', m.group("list")) if m.group("list") else \
            [m.group("index") or m.group("call") or m.group("entry")]
        for k in names:
            found.setdefault(k, line)
    return found


def section_text(page, heading):
    start = page.find("\n" + heading + "\n")
    if start < 0:
        return None
    end = page.find("\n## ", start + len(heading) + 2)
    return page[start:] if end < 0 else page[start:end]


page = page_path.read_text(encoding="utf-8")
missing, total = [], 0
for heading, patterns in SECTIONS.items():
    body = section_text(page, heading)
    if body is None:
        missing.append(f"docs/input-reference.md has no section '{heading}': restore it")
        continue
    documented = set(re.findall(r"`([A-Za-z_][A-Za-z_0-9]*)`", body))
    for pattern in patterns:
        for path in sorted(src.glob(pattern)):
            rel = str(path.relative_to(src))
            for key, line in sorted(keys_in(path).items()):
                if (rel, key) in NOT_INPUT_KEYS:
                    continue
                total += 1
                if key not in documented:
                    missing.append(f"key `{key}` (read at {rel}:{line}) is not in docs/input-reference.md, "
                                   f"section '{heading}': add a row | `{key}` | meaning | unit | default | "
                                   f"to the table of the block that holds it")

# flexcomp-study's factors: the names its factor check accepts.
study = (src / "tools" / "flexcomp-study").read_text(encoding="utf-8")
m = re.search(r"kind not in \(([^)]*)\)", study)
if not m:
    missing.append("tools/flexcomp-study: the factor check `kind not in (...)` was not found; update tests/docs/input_keys.py")
else:
    body = section_text(page, "## flexcomp-study") or ""
    for factor in re.findall(r'"([^"]+)"', m.group(1)):
        total += 1
        if f"`{factor}`" not in body:
            missing.append(f"factor `{factor}` (tools/flexcomp-study) is not in docs/input-reference.md, "
                           f"section '## flexcomp-study': add a row for it")

# The parsers read well over a hundred keys: far fewer means the extraction broke.
if total < 150:
    missing.append(f"only {total} keys found in the parsers' sources: the extraction in tests/docs/input_keys.py "
                   f"no longer matches how the parsers read keys")
for line in missing:
    print("FAIL  " + line)
print(f"{total} keys read by the parsers, {len(missing)} problem(s)")
sys.exit(1 if missing else 0)
