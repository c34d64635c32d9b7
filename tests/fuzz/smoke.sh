#!/bin/bash
# Fuzz smoke test (CTest `fuzz_smoke`, labels slow;fuzz): a few hundred mutated
# inputs with fixed seeds against the three tools. Fails on any crash, hang,
# NaN/inf in an output, damaged output, output or temporary left after an error.
#   smoke.sh BUILD_DIR SOURCE_DIR [WORK_DIR]
# Counts: N_SEC, N_FE, N_MBS, N_SG, H5_MAX (defaults below: ~4 minutes on 2 cores);
# SEED_OFFSET (default 0) shifts every seed, for a campaign with other seeds.
set -u
BUILD=$(readlink -f "$1"); SRC=$(readlink -f "$2")
WORK=$(readlink -m "${3:-$(mktemp -d)}")
HERE=$(cd "$(dirname "$0")" && pwd)
PY=${PYTHON:-/usr/bin/python3}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
SP=$BUILD/section-prep/section-prep FP=$BUILD/fe-prep/fe-prep MR=$BUILD/mbs-run/mbs-run
N_SEC=${N_SEC:-80} N_FE=${N_FE:-50} N_MBS=${N_MBS:-100} N_SG=${N_SG:-50} H5_MAX=${H5_MAX:-30}
$PY -c "import yaml, h5py, numpy" || { echo "fuzz_smoke needs python3 with yaml, h5py, numpy (.ci/deps.sh)"; exit 1; }
rm -rf "$WORK"; mkdir -p "$WORK/logs" "$WORK/aux"
A=$WORK/aux
cp "$HERE"/seeds/* "$A"/
# Real files the seeds refer to and the HDF5 fuzzer corrupts.
timeout 300 "$SP" "$SRC/examples/sar-antenna/sections/truss_d20.yaml" -o "$A/truss_d20.h5" -q || exit 1
(cd "$A" && timeout 300 "$FP" body_beam.yaml -o beam.h5 -q && timeout 300 "$FP" body_panel.yaml -o panel.h5 -q \
  && timeout 300 "$MR" scene_flex.yaml -o res.h5 -q) || { echo "a seed input failed"; exit 1; }
FUZZER_FAILED=0
fuzz() {  # tool n seed
  local w=$WORK/$1-$3
  mkdir -p "$w"; cp "$A"/* "$w"/
  nice $PY "$HERE/yamlfuzz.py" --build "$BUILD" --tool "$1" --n "$2" --seed "$3" --work "$w" \
    --aux "$A" --log "$WORK/logs/yaml-$1-$3.jsonl" --timeout 30
}
O=${SEED_OFFSET:-0}
fuzz section-prep "$N_SEC" $((21 + O)) & P1=$!
fuzz mbs-run "$N_MBS" $((11 + O)) & P2=$!
wait $P1 || FUZZER_FAILED=1
fuzz fe-prep "$N_FE" $((31 + O)) || FUZZER_FAILED=1
wait $P2 || FUZZER_FAILED=1
mkdir -p "$WORK/sg"; cp "$SRC"/tests/data/vabs/*.sg "$WORK/sg/" 2>/dev/null
rm -f "$WORK"/sg/mh104*.sg   # 54k lines: too slow for a smoke test
nice $PY "$HERE/sgfuzz.py" --build "$BUILD" --seeds "$WORK/sg" --work "$WORK/sg-run" \
  --log "$WORK/logs/sg.jsonl" --n "$N_SG" --seed $((5 + O)) --timeout 60 || FUZZER_FAILED=1
mkdir -p "$WORK/h5"; cp "$A"/* "$WORK/h5"/
nice $PY "$HERE/h5fuzz.py" --build "$BUILD" --work "$WORK/h5" --log "$WORK/logs/h5.jsonl" --max-per-src "$H5_MAX" --seed $((7 + O)) \
  || FUZZER_FAILED=1
[ $FUZZER_FAILED = 0 ] || { echo "a fuzzer itself failed (see above)"; exit 1; }
$PY "$HERE/summarize.py" "$WORK"/logs/*.jsonl
# The verdict: these outcomes are defects, whatever the tool.
$PY - "$WORK"/logs/*.jsonl <<'PYEOF'
import json, sys
bad = {"crash", "hang", "nan_output", "bad_output", "output_on_error"}
n = 0; found = []
for path in sys.argv[1:]:
    for line in open(path):
        r = json.loads(line); n += 1
        if r.get("outcome") in bad or r.get("tmp_left"):
            found.append(r)
print(f"fuzz smoke: {n} cases, {len(found)} defects")
for r in found[:40]:
    print("  ", r.get("outcome"), "tmp_left=%s" % r.get("tmp_left", 0), r.get("tool", ""), r.get("input", r.get("case", "")), r.get("desc", "")[:120])
sys.exit(1 if found or n == 0 else 0)
PYEOF
