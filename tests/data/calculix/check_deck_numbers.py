#!/usr/bin/env python3
"""Every number in the CalculiX decks is read by CalculiX as written.

CalculiX reads each number of a data line from the first 20 characters of
its field, blanks removed (read(textpart(i)(1:20),'(f20.0)') in its
orientations.f, nodes.f and the other keyword readers), so a longer field is
cut: '%.17g' of cos(90 deg), 6.123233995736766e-17, was read as 0.612 and
turned the stiffened panel's 90-degree plies into 58.5-degree plies
(docs/validation.md, the stiffened-panel row). This check reads every data
field of the committed decks (tests/data/**/*.inp) and of the decks the
stiffened panel's generators write (make_decks.py, make_solid.py, into a
scratch directory) as CalculiX would and as Python does, and fails on any
field whose two values differ by more than 1e-12 of its size (a cut last
digit of a 17-digit coordinate is 1e-18 and passes).

  python3 check_deck_numbers.py <project root> <scratch dir>
"""
import glob
import os
import subprocess
import sys


def misread(path):
    """(line number, field, value as written, value CalculiX reads) of each
    field CalculiX would read differently."""
    bad = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            if line.startswith("*"):
                continue  # keyword and comment lines
            for tok in line.replace(" ", "").replace("\t", "").rstrip("\n").split(","):
                try:
                    full = float(tok)
                except ValueError:
                    continue  # names and empty fields
                try:
                    cut = float(tok[:20])
                except ValueError:
                    cut = float("nan")
                if not abs(cut - full) <= 1e-12 * max(1.0, abs(full)):
                    bad.append((n, tok, full, cut))
    return bad


def main():
    root, scratch = sys.argv[1], sys.argv[2]
    decks = sorted(glob.glob(os.path.join(root, "tests", "data", "**", "*.inp"), recursive=True))
    gen = os.path.join(root, "tests", "data", "calculix", "stiffened_panel")
    os.makedirs(scratch, exist_ok=True)
    py = sys.executable
    for args in (["make_decks.py", "ccx", "16", "32"], ["make_decks.py", "skin", "32"],
                 ["make_decks.py", "ccx-crossply", "32"],
                 ["make_decks.py", "stringer", "32"],
                 ["make_solid.py", "32", "20", "0,45,-45,90,90,-45,45,0", "qi32", "C3D20"],
                 ["make_solid.py", "32", "20", "0,45,-45,90,90,-45,45,0", "qis32", "C3D20", "stringers"]):
        subprocess.run([py, os.path.join(gen, args[0])] + args[1:], cwd=scratch, check=True,
                       stdout=subprocess.DEVNULL)
    decks += sorted(glob.glob(os.path.join(scratch, "*.inp")))
    failed = 0
    for d in decks:
        for n, tok, full, cut in misread(d)[:5]:
            print("%s:%d: '%s' is %.17g, CalculiX reads %.17g (its first 20 characters)" % (d, n, tok, full, cut))
            failed += 1
    print("%d decks checked, %d fields misread" % (len(decks), failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
