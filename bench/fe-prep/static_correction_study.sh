#!/bin/sh
# Peak support force of a suddenly loaded panel against the number of free
# modes, with and without the static correction (docs/fe-prep.md, "Static
# correction"). The raised-pins panel of tests/fe-prep/test_calculix_couplings.cpp
# (1 x 0.65 m, 2 mm cfrp_iso, h = 0.04) clamped at its two raised distributing
# hinge points H1, H2 (the modes' reference; in the scene one fixed joint at H1
# holds the frame, H2 is held by the shapes), a 10 N step force along z at the
# raised point T at the far edge from t = 0, modal damping 2 %, 0.5 s (about
# two periods of the first mode, 3.6 Hz). Printed: the run's peak reaction force.
# Usage: static_correction_study.sh BUILD_DIR [WORK_DIR]
set -e
build=${1:?build directory}
work=${2:-$(mktemp -d)}
mkdir -p "$work"
body() {  # $1 = modes: value
  cat <<YAML
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  name: panel
  shell: {rectangle: {length: 1.0, width: 0.65}, material: cfrp_iso, thickness: 0.002, mesh: {size: 0.04}}
  interfaces:
    H1: {point: [-0.5, -0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}
    H2: {point: [-0.5, 0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}
    T: {point: [0.5, 0.0, 0.07], coupling: distributing, nodes: {within: 0.1}}
  reference: {clamp: [H1, H2]}
  modes: $1
YAML
}
scene() {  # $1 = body file
  cat <<YAML
bodies:
  - {name: ground, rigid: {mass: 1.0, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}, fixed: true}
  - {name: panel, flexible: {file: $1, modes: all, damping_ratio: 0.02}}
joints:
  - {name: hinge, type: fixed, bodies: [ground, panel], points: [[-0.5, -0.2, 0.07], H1]}
forces:
  - {type: force, body: panel, point: T, force: [0, 0, 10.0]}
simulation: {t_end: 0.5, output_step: 0.0005, rtol: 1.0e-8, integrator: imex}
YAML
}
printf "%-6s %-12s %-8s %s\n" modes correction shapes "peak support force [N]"
for n in 2 4 8 12 24 48; do
  for c in false true; do
    tag=${n}_$c
    body "{count: $n, static_correction: $c}" > "$work/panel_$tag.yaml"
    "$build/fe-prep/fe-prep" -q "$work/panel_$tag.yaml" -o "$work/panel_$tag.h5" > "$work/feprep_$tag.log" 2>&1
    scene "$work/panel_$tag.h5" > "$work/scene_$tag.yaml"
    "$build/mbs-run/mbs-run" "$work/scene_$tag.yaml" -o "$work/run_$tag.h5" > "$work/run_$tag.log" 2>&1
    shapes=$(grep -o '[0-9]* shapes' "$work/feprep_$tag.log" | tail -1 | cut -d' ' -f1)
    peak=$(grep "largest reaction force" "$work/run_$tag.log" | sed "s/.*force //")
    printf "%-6s %-12s %-8s %s\n" "$n" "$c" "$shapes" "$peak"
  done
done
