#!/usr/bin/env bash
# run_beam_paraview_check.sh PVPYTHON SECTION_PREP FE_PREP MBS_RUN CHECK.py WORK_DIR
# A composite tube cantilever through the three tools (section-prep's recovery
# basis -> fe-prep beam body -> mbs-run with outputs.stresses and an animation),
# then pvpython checks that the beam's cell field failure_index in the
# animation is, per beam element, the largest index of its stations and
# section elements in the results file, in two ParaView readers.
set -euo pipefail
pvpython=$1 section_prep=$2 fe_prep=$3 mbs_run=$4 check=$5 work=$6
if [ -z "$pvpython" ] || ! command -v "$pvpython" >/dev/null 2>&1; then
  pvpython=$(command -v pvpython || true)
fi
if [ -z "$pvpython" ]; then
  echo "pvpython not found (Debian package python3-paraview): skipped"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cat > tube.yaml <<'YAML'
materials:
  im6: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9, G12: 7.6e9, G13: 7.6e9,
        G23: 3.6e9, nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600,
        strength: {Xt: 2.5e9, Xc: 1.6e9, Yt: 60e6, Yc: 250e6, S12: 90e6}}
section:
  shape: tube
  outer_diameter: 0.02
  mesh_size: 0.001
  wall:
    plies:
      - {material: im6, thickness: 0.0005, angle_deg: 45}
      - {material: im6, thickness: 0.0005, angle_deg: -45}
YAML
cat > beam.yaml <<'YAML'
body:
  name: cantilever
  beam: {length: 1.0, elements: 6, section: {file: tube.h5}}
  interfaces: {root: [-0.5, 0, 0], tip: [0.5, 0, 0]}
  reference: {clamp: [end_min]}
  modes: 6
YAML
cat > scene.yaml <<'YAML'
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}, fixed: true}
  - {name: beam, flexible: {file: beam.h5, damping_ratio: 0.05}, position: [0.5, 0, 0]}
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
forces:
  - {type: force, body: beam, point: tip, force: [0, 3, -5]}
outputs: {stresses: [beam]}
simulation: {t_end: 0.05, output_step: 0.01}
YAML
"$section_prep" tube.yaml -o tube.h5 >/dev/null
"$fe_prep" beam.yaml -o beam.h5 >/dev/null
"$mbs_run" scene.yaml -o r.h5 --animation a.pvd -q
exec "$pvpython" --force-offscreen-rendering "$check" r.h5 a.pvd beam
