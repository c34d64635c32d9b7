#!/bin/sh
# The stiff many-mode pendulum (docs/benchmarks.md, "Stiff beam pendulum"):
# the steel bar of tests/data/fe-prep/steel_bar_pendulum.yaml (1 m, 20 x 10
# mm, 100 Timoshenko elements, lumped mass, clamped at the pivot) on a
# spherical joint, released from the horizontal under gravity, 1 % modal
# damping, 2 s; 4, 16, 64 and 128 modes, each integrator at rtol 1e-4 and
# 1e-6. Prints one markdown row per run: CPU s (mbs-run's own figure: the
# machine is shared, so CPU, not wall time), steps, rejected steps,
# right-hand-side evaluations, projections, peak RSS, status, and the frame's
# end position (the bar's midpoint, m) for the accuracy columns.
# Usage: bench/mbs-run/stiff_beam.sh BUILD_DIR [MODES...] (env RTOLS,
# INTEGRATORS, T_END, LIMIT: CPU seconds before a run is stopped, default 150).
set -e
BUILD=${1:?build directory}
shift
MODES=${*:-4 16 64 128}
RTOLS=${RTOLS:-1e-4 1e-6}
INTEGRATORS=${INTEGRATORS:-auto imex trbdf2 dopri5}
T_END=${T_END:-2.0}
LIMIT=${LIMIT:-150}
SRC=$(cd "$(dirname "$0")/../.." && pwd)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "| modes | f_max [Hz] | integrator | rtol | CPU s | steps | rejected | rhs evals | projections | peak RSS [MB] | status | end position [m] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for m in $MODES; do
  sed "s/^  modes: 64/  modes: $m/" "$SRC/tests/data/fe-prep/steel_bar_pendulum.yaml" > "$OUT/bar.yaml"
  "$BUILD/fe-prep/fe-prep" "$OUT/bar.yaml" -o "$OUT/bar$m.h5" > "$OUT/fe.log" 2>&1
  fmax=$(awk '$1 == '"$m"' && NF == 2 {print $2; exit}' "$OUT/fe.log")
  for rtol in $RTOLS; do
    for integ in $INTEGRATORS; do
      cat > "$OUT/scene.yaml" <<EOT
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: bar
    flexible: {file: $OUT/bar$m.h5, modes: $m, damping_ratio: 0.01}
    position: [0.5, 0.0, 0.0]
joints:
  - {name: pivot, type: spherical, bodies: [ground, bar], points: [[0, 0, 0], root]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
simulation: {t_end: $T_END, output_step: 0.01, rtol: $rtol, integrator: $integ}
EOT
      ( ulimit -t "$LIMIT"; /usr/bin/time -f "%M" -o "$OUT/rss" "$BUILD/mbs-run/mbs-run" "$OUT/scene.yaml" -o "$OUT/run.h5" \
          --accept-inaccurate > "$OUT/run.log" 2>&1 ) || true
      status=$(sed -n 's/^  status: \([a-z]*\).*/\1/p' "$OUT/run.log")
      counts=$(sed -n 's/^  integrator [^:]*: \([0-9]*\) steps, \([0-9]*\) rejected, \([0-9]*\) evaluations, \([0-9]*\) projections.*/\1 | \2 | \3 | \4/p' "$OUT/run.log")
      cpu=$(sed -n 's/^  CPU \([0-9.e+-]*\) s.*/\1/p' "$OUT/run.log")
            # The last line: a run stopped at the limit has time's "Command terminated" line first.
      rss=$(awk 'END {printf "%.0f", $1 / 1024}' "$OUT/rss" 2>/dev/null || echo -)
      pos=-
      if [ "$status" = completed ] || [ "$status" = inaccurate ]; then
        rows=$(h5ls "$OUT/run.h5/time" | sed -n 's/.*{\([0-9]*\).*/\1/p')
        pos=$(h5dump -d /bodies/bar/position -s "$((rows - 1)),0" -c "1,3" -m "%.9f" "$OUT/run.h5" |
              sed -n 's/^ *([0-9]*,0): //p' | tr -d ' ,')
      fi
      echo "| $m | $fmax | $integ | $rtol | ${cpu:-> $LIMIT} | ${counts:-| | |} | $rss | ${status:-stopped} | $pos |"
    done
  done
done
