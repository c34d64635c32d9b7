#!/usr/bin/python3
"""No function in the tools' sources runs over LIMIT lines, except those named in
ALLOWED with the reason they stay whole (sequential file-format readers, whose
cards or records are read in the file's own order).

    function_length.py REPO            # exit 1 on a long function not allowed,
                                       # or an allowed one that is no longer long

A simple scan: comments, strings and character literals are blanked, braces are
matched, and a `{` whose preceding text ends in a parameter list (`)` and its
qualifiers) outside any function body opens a function; its length is counted
from the line of its name to the line of its closing brace. Lambdas and local
classes count toward the function that holds them.
"""
import os
import re
import sys

LIMIT = 120
FOLDERS = ["section-prep", "fe-prep", "mbs-run", "common"]

# path::function -> why it stays one function. Each must still be over LIMIT
# (an entry that is not is reported, so the list stays true).
ALLOWED = {
    "fe-prep/import/matrix_files.cpp::symmetricLowerTriangle":
        "a sequential check of a matrix file's entries in their file order (storage, duplicates, symmetry), "
        "each refusal located at its lines",
    "section-prep/vabs_reader.cpp::parseVabs":
        "a sequential reader: the VABS input file's records in the file's own order, each checked where it is read",
    "fe-prep/mesh_files/nastran.cpp::Builder::readElements":
        "a sequential reader: one branch per Nastran element card (CQUAD4, CTRIA3, CBAR, CBEAM, CROD, CONM2, ...)",
    "fe-prep/mesh_files/gmsh_regions.cpp::readGmsh":
        "a sequential reader: the gmsh file's nodes, elements and physical groups, in the order the API gives them",
    "fe-prep/import/imported_body.cpp::importMatrices":
        "a sequential reader: the DOF list, the two matrices and the model file of one export, checked in turn",
    "common/dataset_docs.cpp::datasetDocs":
        "a table, not logic: one row per dataset of the three file formats (the --describe text)",
}

_QUALIFIERS = re.compile(r"\)\s*(const|noexcept|override|final|mutable|volatile|&|&&|\s)*(->\s*[\w:<>,\s*&]+)?$")
_NOT_FUNCTIONS = re.compile(r"\b(if|for|while|switch|catch|return)\s*\(")


def blank(text):
    """The source with comments, string and character literals replaced by spaces
    (newlines kept, so line numbers stay)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k)
            j = n if j < 0 else j + len(delim)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(c)  # a digit separator (1'000)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def function_name(signature):
    """The identifier before the parameter list: the first `(` outside template brackets."""
    depth = 0
    for k, c in enumerate(signature):
        if c == "<":
            depth += 1
        elif c == ">":
            depth = max(depth - 1, 0)
        elif c == "(" and depth == 0:
            m = re.search(r"([A-Za-z_~][\w:~]*(?:operator\s*\S+)?)\s*$", signature[:k])
            return m.group(1) if m else "?"
    return "?"


def functions(path):
    """(name, first line, last line) of every function body in the file."""
    text = blank(open(path, encoding="utf-8", errors="replace").read())
    found = []
    stack = []  # one entry per open brace: "function", "inner" (inside a function) or "scope"
    start = 0   # where the text before the next brace begins
    for i, c in enumerate(text):
        if c in ";}":
            if c == "}" and stack:
                kind = stack.pop()
                if kind[0] == "function":
                    found.append((kind[1], kind[2], text.count("\n", 0, i) + 1))
            start = i + 1
        elif c == "{":
            if stack and stack[-1][0] in ("function", "inner"):
                stack.append(("inner",))
            else:
                before = text[start:i]
                sig = before.strip()
                if _QUALIFIERS.search(sig) or re.search(r"\)\s*:\s*[\w:]+\s*[({]", sig) or re.search(r"\)\s*:.*[)}]$", sig, re.S):
                    if not _NOT_FUNCTIONS.search(sig) and not re.match(r"(namespace|class|struct|enum|union)\b", sig):
                        name = function_name(sig)
                        first = text.count("\n", 0, start + len(before) - len(before.lstrip())) + 1
                        stack.append(("function", name, first))
                        start = i + 1
                        continue
                stack.append(("scope",))
            start = i + 1
    return found


def main(repo):
    long_ones, seen = [], set()
    for folder in FOLDERS:
        for d, _, files in os.walk(os.path.join(repo, folder)):
            for f in sorted(files):
                if not f.endswith((".cpp", ".h", ".cc", ".hpp")):
                    continue
                path = os.path.join(d, f)
                rel = os.path.relpath(path, repo)
                for name, first, last in functions(path):
                    length = last - first + 1
                    key = "%s::%s" % (rel, name)
                    if length > LIMIT:
                        seen.add(key)
                        if key not in ALLOWED:
                            long_ones.append((length, key, first))
    problems = 0
    for length, key, first in sorted(long_ones, reverse=True):
        print("%s (line %d): %d lines, over %d: split it into its stages, or name it in ALLOWED with why"
              % (key, first, length, LIMIT))
        problems += 1
    for key in sorted(set(ALLOWED) - seen):
        print("%s: in ALLOWED but not over %d lines (or gone): drop it from the list" % (key, LIMIT))
        problems += 1
    print("functions over %d lines: %d allowed (%s), %d problem(s)"
          % (LIMIT, len(seen & set(ALLOWED)), "readers that say why", problems))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
