#!/bin/sh
# Runs the cases of compare_results.py with two builds and compares what they
# write, bit for bit (HDF5 datasets and attributes, other files byte for byte,
# exit codes and messages): the proof that a refactoring changed no result.
#
#   tools/compare-results/identical.sh BUILD_BEFORE BUILD_AFTER [PATTERN ...]
#
# BUILD_* are CMake build trees (or copies holding section-prep/section-prep,
# fe-prep/fe-prep and mbs-run/mbs-run). PATTERNs select cases by name
# ('feprep_*' for fe-prep's bodies alone); without, every case runs (about
# two and a half minutes of CPU for each build). The outputs stay in
# $IDENTICAL_WORKDIR (default: a fresh temporary folder) for a look.
set -eu
if [ $# -lt 2 ]; then
  sed -n '2,13p' "$0"
  exit 2
fi
before=$1
after=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
work=${IDENTICAL_WORKDIR:-$(mktemp -d)}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
echo "== before: $before"
/usr/bin/python3 "$here/compare_results.py" run "$before" "$work/before" "$@"
echo "== after: $after"
/usr/bin/python3 "$here/compare_results.py" run "$after" "$work/after" "$@"
echo "== compare"
/usr/bin/python3 "$here/compare_results.py" compare "$work/before" "$work/after"
