#!/usr/bin/env bash
# The README's test command (what CI runs): installs the dependencies, builds
# everything (Release) and runs the whole test suite.
# Every option is set explicitly: the quick start (examples/run-sar.sh) may have
# configured the same build directory with the tests off, and CMake's cache
# would keep that. ctest fails when it finds no test, so a suite that ran
# nothing never reports success.
# BUILD_DIR=DIR builds elsewhere; FLEXCOMP_CONFIGURE_ONLY=1 stops after the
# configuration (tests/ci/check_commands.sh uses it).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD_DIR:-build}
if [ -z "${FLEXCOMP_CONFIGURE_ONLY:-}" ]; then bash .ci/deps.sh --with-paraview --with-slurm; fi
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DFLEXCOMP_BUILD_TESTS=ON -DFLEXCOMP_BUILD_BENCH=ON \
  -DFLEXCOMP_WERROR=ON -DFLEXCOMP_OPENBLAS=OFF
if [ -n "${FLEXCOMP_CONFIGURE_ONLY:-}" ]; then exit 0; fi
cmake --build "$BUILD" -j"$(nproc)"
# OpenMPI refuses to run as root without these; PETSc initialises MPI in-process.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cd "$BUILD"
ctest --output-on-failure --no-tests=error -j"$(nproc)"
