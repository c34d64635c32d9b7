#!/usr/bin/env bash
# An example as an installed user runs it: `cmake --install` into a scratch prefix,
# then `make` in the installed copy P/share/flexcomp/examples/EXAMPLE with only
# P/bin (and the system) on PATH; then the same example from the build tree with
# `make BIN=BUILD_DIR` and nothing of the tools on PATH. Both outputs are checked.
#   run_installed_example.sh BUILD_DIR WORK_DIR EXAMPLE PYTHON CHECK.py
set -euo pipefail
build=$(readlink -f "$1") work=$(readlink -m "$2") example=$3 python=$4 check=$5
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
installed="$work/prefix/share/flexcomp/examples/$example"
[ -f "$installed/Makefile" ] || { echo "FAIL: $installed/Makefile not installed"; exit 1; }
[ -f "$work/prefix/share/doc/flexcomp/input-reference.md" ] || { echo "FAIL: the input reference is not installed"; exit 1; }
clean_path=/usr/local/bin:/usr/bin:/bin
PATH="$work/prefix/bin:$clean_path" make -C "$installed" --no-print-directory
(cd "$installed" && "$python" "$check" out)
# The build tree, named with BIN= (no tool on PATH).
copy="$work/bin-copy"
mkdir -p "$copy"
find "$(dirname "$0")/../../examples/$example" -maxdepth 1 -type f -exec cp {} "$copy"/ \;
PATH="$clean_path" make -C "$copy" --no-print-directory BIN="$build"
cd "$copy"
exec "$python" "$check" out
