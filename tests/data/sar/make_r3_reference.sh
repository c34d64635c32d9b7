#!/bin/sh
# Recomputes sar-cb-h0.0125-r3.csv, the rebuilt SAR model's phase-1 knee angle at element
# size 0.0125 m (tests/examples/check_sar_default.py's accuracy reference):
#   tests/data/sar/make_r3_reference.sh BUILD_DIR WORK_DIR > tests/data/sar/sar-cb-h0.0125-r3.csv
# In a copy of examples/sar-antenna, the example's own Makefile makes the sections, trusses and
# the two isotropic panels at CB_H = 0.0125 (8 fixed-interface modes, cb_model.py with the
# accuracy study's generator) and the derived scene (sar-isotropic.yaml with those panels,
# hold-down E and snubber pads included); the scene then runs phase 1 at rtol 1e-6 with
# Dormand-Prince, one row every 0.01 s, and R3 is written up to 0.3 s after it first falls
# to 0.1 rad. Needs ~2 GB and a few minutes of CPU (two fe-prep runs of ~2.4e5 DOF).
set -eu
BUILD=$(cd "$1" && pwd)
mkdir -p "$2"
WORK=$(cd "$2" && pwd)
SRC=$(cd "$(dirname "$0")/../../../examples/sar-antenna" && pwd)
cp "$SRC/Makefile" "$SRC/cb_model.py" "$SRC/study.py" "$SRC/sar-isotropic.yaml" "$WORK"
rm -rf "$WORK/bodies" "$WORK/sections"
cp -r "$SRC/bodies" "$SRC/sections" "$WORK"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
make -C "$WORK" --no-print-directory -s BIN="$BUILD" CB_H=0.0125 CB_MODES=8 bodies \
  out/bodies/panel2_iso_h0.0125_cb8.h5 out/scenes/sar-isotropic-cb.yaml >&2
/usr/bin/python3 - "$WORK/out/scenes/sar-isotropic-cb.yaml" "$WORK/out/scenes/r3-reference.yaml" <<'PY'
import sys, yaml
s = yaml.safe_load(open(sys.argv[1]))
s.pop("outputs", None)
s["simulation"] = {"t_end": 7.0, "output_step": 0.01, "rtol": 1.0e-6, "integrator": "dopri5"}
yaml.safe_dump(s, open(sys.argv[2], "w"), default_flow_style=None, sort_keys=False)
PY
"$BUILD/mbs-run/mbs-run" "$WORK/out/scenes/r3-reference.yaml" -o "$WORK/out/r3-reference.h5" -q >&2
/usr/bin/python3 - "$WORK/out/r3-reference.h5" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1]) as f:
    t, r3, cpu = f["time"][()], f["joints/R3/angle"][()], float(f.attrs["cpu_seconds"])
cut = t[np.argmax(r3 < 0.1)] + 0.3
print("# The SAR's rebuilt model at element size 0.0125 m, 8 fixed-interface modes per panel, 2 per truss,")
print("# phase 1 (R1 locked, actuator A; hold-down E and the snubber pads; the 40-mm hinge-2/3 gap), rtol 1e-6,")
print("# dopri5: the knee angle R3 [rad] every 0.01 s up to 0.3 s after it first falls to 0.1 rad.")
print(f"# Made by tests/data/sar/make_r3_reference.sh (mbs-run {cpu:.1f} s CPU). Reference for")
print("# tests/examples/check_sar_default.py (the default h = 0.025 m model's documented error).")
print("time,r3")
for ti, ri in zip(t, r3):
    if ti <= cut + 1e-9:
        print(f"{ti:.4f},{ri:.12g}")
PY
