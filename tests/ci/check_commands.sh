#!/usr/bin/env bash
# The README's two commands share one checkout in either order: the quick start
# (examples/run-sar.sh) and the test command (.ci/test.sh) each configure the
# build directory with every option they need, so whichever ran before, the test
# command builds and lists the tests and the quick start builds the tools with
# the same compile flags (no rebuild, no rerun of the example after the other).
# And the test command fails when ctest finds no test.
#   check_commands.sh SOURCE_DIR SCRATCH_DIR
# Configures SCRATCH_DIR only (FLEXCOMP_CONFIGURE_ONLY=1: no dependencies, no
# build): four configurations, about 3 s of CPU each.
set -euo pipefail
src=$(readlink -f "$1") scratch=$(readlink -m "$2")
rm -rf "$scratch"
fail=0
check() { if eval "$1"; then echo "ok    $2"; else echo "FAIL  $2"; fail=1; fi; }
cache() { sed -n "s/^$1:[A-Z]*=//p" "$scratch/CMakeCache.txt"; }
configure() { mkdir -p "$(dirname "$scratch")"; BUILD_DIR="$scratch" FLEXCOMP_CONFIGURE_ONLY=1 bash "$src/$1" >"$scratch.log" 2>&1 || { cat "$scratch.log"; exit 1; }; }
# The flags that decide how the tools are compiled: the two commands must agree.
flags() { echo "$(cache CMAKE_BUILD_TYPE) $(cache FLEXCOMP_WERROR) $(cache CMAKE_CXX_FLAGS)"; }

# One directory, the commands in the sequence quick start, test, test, quick start: each
# order and each command twice in a row (the configuration is what differs between runs).
prev=fresh
for cmd in examples/run-sar.sh .ci/test.sh .ci/test.sh examples/run-sar.sh; do
  configure "$cmd"
  if [ "$cmd" = .ci/test.sh ]; then
    check '[ "$(cache FLEXCOMP_BUILD_TESTS)" = ON ]' "$cmd after $prev configures the tests"
    n=$(cd "$scratch" && ctest -N | sed -n 's/^Total Tests: //p')
    check '[ "${n:-0}" -gt 0 ]' "$cmd after $prev lists ${n:-0} tests"
    test_flags=$(flags)
  else
    check '[ -n "$(cache FLEXCOMP_BUILD_TESTS)" ]' "$cmd after $prev sets FLEXCOMP_BUILD_TESTS"
    sar_flags=$(flags)
  fi
  prev=$cmd
done
check '[ "$test_flags" = "$sar_flags" ]' "both compile the tools alike ($test_flags)"
check 'grep -q -- "--no-tests=error" "$src/.ci/test.sh"' ".ci/test.sh runs ctest with --no-tests=error"
rm -rf "$scratch" "$scratch.log"
exit $fail
