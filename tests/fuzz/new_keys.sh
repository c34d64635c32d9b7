#!/bin/bash
# Campaign on the keys and datasets added after the first fuzz seeds (session 6,
# docs/robustness.md): Craig-Bampton, distributed interfaces, static_error,
# static_correction, geometric_stiffness, joint limits, imex, sparse_schur,
# stresses, distances. Not a CTest: a few body files make some mutations slow.
#   new_keys.sh BUILD_DIR [WORK_DIR]     env: N_MBS (200), N_FE (150), SEED (401), H5_MAX (90)
set -u
BUILD=$(readlink -f "$1"); WORK=$(readlink -m "${2:-$(mktemp -d)}")
HERE=$(cd "$(dirname "$0")" && pwd); PY=${PYTHON:-/usr/bin/python3}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
FP=$BUILD/fe-prep/fe-prep MR=$BUILD/mbs-run/mbs-run SP=$BUILD/section-prep/section-prep
S=${SEED:-401}
mkdir -p "$WORK/aux" "$WORK/logs"; A=$WORK/aux
cp "$HERE"/seeds-new-keys/* "$HERE"/seeds/*.geo "$HERE"/seeds/body_beam_file.yaml "$A"/
(cd "$A" && for b in cb dist statcorr strength; do timeout 300 "$FP" body_$b.yaml -o $b.h5 -q > /dev/null || exit 1; done) \
  || { echo "a seed body failed"; exit 1; }
timeout 300 "$SP" "$HERE/../../examples/sar-antenna/sections/truss_d20.yaml" -o "$A/truss_d20.h5" -q > /dev/null || exit 1
nice $PY "$HERE/yamlfuzz.py" --build "$BUILD" --tool mbs-run --n "${N_MBS:-200}" --seed "$S" --work "$WORK/mbs" \
  --aux "$A" --log "$WORK/logs/yaml-mbs.jsonl" --timeout 30
nice $PY "$HERE/yamlfuzz.py" --build "$BUILD" --tool fe-prep --n "${N_FE:-150}" --seed $((S + 1)) --work "$WORK/fe" \
  --aux "$A" --log "$WORK/logs/yaml-fe.jsonl" --timeout 30
# The HDF5 fuzzer corrupts beam.h5/panel.h5 through scene_flex.yaml: here the statically
# corrected cantilever and the strength panel, carried by scene_stress.yaml.
H=$WORK/h5; mkdir -p "$H"
cp "$A/statcorr.h5" "$H/beam.h5"; cp "$A/strength.h5" "$H/panel.h5"; cp "$A/truss_d20.h5" "$A/body_beam_file.yaml" "$H"/
sed 's/statcorr.h5/beam.h5/; s/strength.h5/panel.h5/' "$A/scene_stress.yaml" > "$H/scene_flex.yaml"
(cd "$H" && "$MR" scene_flex.yaml -o res.h5 -q > /dev/null) || { echo "the seed scene failed"; exit 1; }
nice $PY "$HERE/h5fuzz.py" --build "$BUILD" --work "$H" --log "$WORK/logs/h5.jsonl" --max-per-src "${H5_MAX:-90}" --seed $((S + 6))
$PY "$HERE/summarize.py" "$WORK"/logs/*.jsonl
