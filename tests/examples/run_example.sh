#!/usr/bin/env bash
# Runs one example as a user would (its Makefile, the tools on PATH) in a copy
# under the build tree, then checks what it produced:
#   run_example.sh EXAMPLE_DIR WORK_DIR BUILD_DIR PYTHON CHECK.py
set -euo pipefail
src=$1 work=$2 build=$3 python=$4 check=$5
rm -rf "$work"
mkdir -p "$work"
# The example's own files only (never a stale out/ of the source tree).
find "$src" -maxdepth 1 -type f -exec cp {} "$work"/ \;
export PATH="$build/section-prep:$build/fe-prep:$build/mbs-run:$PATH"
make -C "$work" --no-print-directory
cd "$work"
exec "$python" "$check" out
