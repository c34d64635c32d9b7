#!/bin/sh
# Peak hinge reaction of an elastically free rod under a step tip force
# against the number of free-free modes, with and without the static
# correction with inertia relief (docs/fe-prep.md, "Free bodies: inertia
# relief"). The 2 m steel rod (d = 20 mm, 40 elements) of
# tests/fe-prep/test_free_static_correction.cpp, `reference: free` (its modes
# are the free rod's), hung on a revolute joint about z at its root interface,
# a 1 N step force along y at its tip from rest, modal damping $DAMPING
# (default 0.02), 0.2 s (4.6 periods of the first free-free mode, 23 Hz).
# Printed: the run's largest hinge reaction force (a rigid rod: 0.5 N).
# Usage: free_correction_study.sh BUILD_DIR [WORK_DIR]
set -e
build=${1:?build directory}
work=${2:-$(mktemp -d)}
damping=${DAMPING:-0.02}
mkdir -p "$work"
body() {  # $1 = modes: value
  cat <<YAML
materials:
  steel: {type: isotropic, E: 210.0e9, nu: 0.3, rho: 7850}
body:
  name: rod
  beam: {length: 2.0, elements: 40, section: {shape: solid_circle, diameter: 0.02, material: steel}}
  interfaces: {root: [-1.0, 0, 0], tip: [1.0, 0, 0]}
  reference: free
  modes: $1
YAML
}
scene() {  # $1 = body file
  cat <<YAML
bodies:
  - {name: ground, rigid: {mass: 1.0, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}, fixed: true}
  - {name: rod, flexible: {file: $1, modes: all, damping_ratio: $damping}}
joints:
  - {name: hinge, type: revolute, bodies: [ground, rod], points: [[-1, 0, 0], root], axes: [[0, 0, 1], [0, 0, 1]]}
forces:
  - {type: force, body: rod, point: tip, force: [0, 1.0, 0]}
simulation: {t_end: 0.2, output_step: 0.0001, rtol: 1.0e-9, integrator: imex}
YAML
}
printf "%-38s %-8s %-36s %s\n" modes shapes "peak hinge force [N]" "CPU [s]"
for m in 2 "{count: 2, static_correction: true}" "{count: 2, static_correction: [tip]}" \
         4 "{count: 4, static_correction: true}" "{count: 4, static_correction: [tip]}" \
         8 "{count: 8, static_correction: true}" "{count: 8, static_correction: [tip]}" 24 48 96; do
  tag=$(echo "$m" | tr -dc '0-9a-z')
  body "$m" > "$work/rod_$tag.yaml"
  "$build/fe-prep/fe-prep" -q "$work/rod_$tag.yaml" -o "$work/rod_$tag.h5" > "$work/feprep_$tag.log" 2>&1
  scene "$work/rod_$tag.h5" > "$work/scene_$tag.yaml"
  "$build/mbs-run/mbs-run" "$work/scene_$tag.yaml" -o "$work/run_$tag.h5" > "$work/run_$tag.log" 2>&1
  shapes=$(grep -o '[0-9]* shapes' "$work/feprep_$tag.log" | tail -1 | cut -d' ' -f1)
  peak=$(grep "largest reaction force" "$work/run_$tag.log" | sed "s/.*force //")
  cpu=$(grep -o "CPU [0-9.]* s" "$work/run_$tag.log" | head -1)
  printf "%-38s %-8s %-36s %s\n" "$m" "$shapes" "$peak" "$cpu"
done
