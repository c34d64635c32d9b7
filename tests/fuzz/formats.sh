#!/bin/bash
# Campaign on the input formats added after the first fuzzers (docs/robustness.md,
# "Format fuzzing"): gmsh .msh with regions, matrix files (CalculiX, Matrix Market,
# Abaqus), units: on every YAML input, flexcomp-study's --sample options.
#   formats.sh BUILD_DIR [WORK_DIR]     env: N (cases per target, 80), SEED (2811)
# Fails on any crash, hang, NaN output, damaged output, output or temporary left
# after an error, or nonsense accepted; prints the table.
set -u
BUILD=$(readlink -f "$1"); WORK=$(readlink -m "${2:-$(mktemp -d)}")
HERE=$(cd "$(dirname "$0")" && pwd); PY=${PYTHON:-/usr/bin/python3}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
N=${N:-80} S=${SEED:-2811}
mkdir -p "$WORK/logs"
for t in msh matrix units study; do
  nice $PY "$HERE/formatfuzz.py" --build "$BUILD" --target $t --n "$N" --seed "$S" --work "$WORK/$t" \
    --log "$WORK/logs/format-$t.jsonl" --timeout 60 || exit 1
done
$PY "$HERE/summarize.py" "$WORK"/logs/format-*.jsonl
$PY - "$WORK"/logs/format-*.jsonl <<'PYEOF'
import json, sys
bad = {"crash", "hang", "nan_output", "bad_output", "output_on_error", "silent_accept"}
n = 0; found = []
for path in sys.argv[1:]:
    for line in open(path):
        r = json.loads(line); n += 1
        if r.get("outcome") in bad or r.get("tmp_left"):
            found.append(r)
print(f"format fuzzing: {n} cases, {len(found)} defects")
for r in found[:40]:
    print("  ", r["outcome"], r["target"], r["case"], r["desc"][:140])
sys.exit(1 if found or n == 0 else 0)
PYEOF
