#!/usr/bin/env bash
# run_paraview_check.sh PVPYTHON EXAMPLE_WORK_DIR MBS_RUN CHECK.py
# Uses the hinged-panel example's body file and results (test example_hinged_panel),
# writes an animation of every 3rd output time beside them, and lets pvpython check both.
set -euo pipefail
pvpython=$1 work=$2 mbs_run=$3 check=$4
if [ -z "$pvpython" ] || ! command -v "$pvpython" >/dev/null 2>&1; then
  pvpython=$(command -v pvpython || true)
fi
if [ -z "$pvpython" ]; then
  echo "pvpython not found (Debian package python3-paraview): skipped"
  exit 77
fi
cd "$work"
"$mbs_run" scene.yaml -o out/every3.h5 --animation out/every3.pvd --animation-every 3 -q
# Off-screen: no display is needed.
exec "$pvpython" --force-offscreen-rendering "$check" out/panel.h5 out/panel.xdmf out/every3.h5 out/every3.pvd 3 panel
