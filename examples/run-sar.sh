#!/usr/bin/env bash
# Quick start: install the dependencies, build the three tools (Release) and run
# the SAR antenna example end to end (sections -> bodies -> scenes -> plots).
# Every option is set explicitly, so this and the test command (.ci/test.sh)
# share the build directory in either order: each sets what it needs, and the
# tools' compile flags are the same in both (a warning is an error in both, as
# in CI), so neither rebuilds the tools nor reruns the example after the other.
# BUILD_DIR=DIR builds elsewhere; FLEXCOMP_CONFIGURE_ONLY=1 stops after the
# configuration (tests/ci/check_commands.sh uses it).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD_DIR:-build}
if [ -z "${FLEXCOMP_CONFIGURE_ONLY:-}" ]; then bash .ci/deps.sh; fi
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DFLEXCOMP_BUILD_TESTS=OFF -DFLEXCOMP_BUILD_BENCH=OFF \
  -DFLEXCOMP_WERROR=ON
if [ -n "${FLEXCOMP_CONFIGURE_ONLY:-}" ]; then exit 0; fi
cmake --build "$BUILD" -j"$(nproc)" --target section-prep fe-prep mbs-run
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
BUILD_ABS=$(cd "$BUILD" && pwd)
make -C examples/sar-antenna BIN="$BUILD_ABS" -j"$(nproc)"
echo "Results, plots and the animation are in examples/sar-antenna/out/"
