#!/bin/sh
# A rotary damper at a flexible interface against the same damper on the
# body's frame rotation (docs/benchmarks.md, "A damper at a flexible
# interface"): the SAR's crank B4 (CFRP rod, L = 0.273 m, d = 20 mm, two
# pinned-pinned bending modes near 1 kHz, 1 % damping) on a revolute joint
# R1 at its root interface, a 4 kg rigid arm welded to its tip, driven by a
# constant 25 N m (actuator B's kick-off) through a 50 N m s rotary damper (the v3 scene's first
# drive) until R1 latches at 0.8 rad. Variant R1: the force element acts on
# R1 (relative rotation at the interface, the crank's modal rotation
# included); variant R1D: on a stop-only revolute at the crank's frame (the
# SAR scenes' workaround). Prints one markdown row per run: CPU s (mbs-run's
# own figure; the machine is shared), steps, rejected, evaluations,
# projections, status, and the arm's end x (m).
# Usage: bench/mbs-run/interface_damper.sh BUILD_DIR (env RTOLS, INTEGRATORS,
# DAMPING, T_END).
set -e
BUILD=${1:?build directory}
RTOLS=${RTOLS:-1e-4 1e-6}
INTEGRATORS=${INTEGRATORS:-auto imex}
DAMPING=${DAMPING:-50.0}
T_END=${T_END:-3.0}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cat > "$OUT/crank.yaml" <<'EOT'
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  name: crank
  beam: {length: 0.273, elements: 2, section: {shape: solid_circle, diameter: 0.02, material: cfrp_iso}}
  interfaces:
    R1: [-0.1365, 0.0, 0.0]
    S5: [0.1365, 0.0, 0.0]
  reference: {pin: [end_min, end_max]}
  modes: 2
  mass: lumped
EOT
"$BUILD/fe-prep/fe-prep" "$OUT/crank.yaml" -o "$OUT/crank.h5" > "$OUT/fe.log" 2>&1
echo "| damper on | integrator | rtol | CPU s | steps | rejected | rhs evals | projections | status | arm end x [m] |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for rtol in $RTOLS; do
  for integ in $INTEGRATORS; do
    for joint in R1 R1D; do
      cat > "$OUT/scene.yaml" <<EOT
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: crank
    flexible: {file: $OUT/crank.h5, modes: 2, damping_ratio: 0.01}
    position: [0.1365, 0.0, 0.0]
  - name: arm
    rigid: {mass: 4.0, inertia: [[0.05,0,0],[0,0.6,0],[0,0,0.6]]}
    position: [0.773, 0.0, 0.0]
joints:
  - {name: R1, type: revolute, bodies: [ground, crank], points: [[0, 0, 0], R1], axes: [[0, 1, 0], [0, 1, 0]]}
  - {name: R1D, type: revolute, bodies: [ground, crank], points: [[0, 0, 0], [-0.1365, 0, 0]], axes: [[0, 1, 0], [0, 1, 0]], stop_only: true}
  - {name: weld, type: fixed, bodies: [crank, arm], points: [S5, [-0.5, 0, 0]]}
forces:
  - {name: B, type: rotational_spring_damper, joint: $joint, damping: $DAMPING, torque: {angle: [-1.0, 0.0], value: [-25.0, -25.0]}}
events:
  - {joint: R1, angle: 0.8, direction: rising, lock: [R1]}
simulation: {t_end: $T_END, output_step: 0.01, rtol: $rtol, integrator: $integ}
EOT
      "$BUILD/mbs-run/mbs-run" "$OUT/scene.yaml" -o "$OUT/run.h5" --accept-inaccurate > "$OUT/run.log" 2>&1 || true
      status=$(sed -n 's/^  status: \([a-z]*\).*/\1/p' "$OUT/run.log")
      counts=$(sed -n 's/^  integrator [^:]*: \([0-9]*\) steps, \([0-9]*\) rejected, \([0-9]*\) evaluations, \([0-9]*\) projections.*/\1 | \2 | \3 | \4/p' "$OUT/run.log")
      cpu=$(sed -n 's/^  CPU \([0-9.e+-]*\) s.*/\1/p' "$OUT/run.log")
      rows=$(h5ls "$OUT/run.h5/time" | sed -n 's/.*{\([0-9]*\).*/\1/p')
      x=$(h5dump -d /bodies/arm/position -s "$((rows - 1)),0" -c "1,1" -m "%.9f" "$OUT/run.h5" | sed -n 's/^ *([0-9]*,0): //p' | tr -d ' ,')
      echo "| $joint | $integ | $rtol | $cpu | $counts | $status | $x |"
    done
  done
done
