#!/usr/bin/env bash
# Quick start: install the dependencies, build the three tools (Release) and run
# the SAR antenna example end to end (sections -> bodies -> scenes -> plots).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/deps.sh
BUILD=${BUILD_DIR:-build}
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DFLEXCOMP_BUILD_TESTS=OFF -DFLEXCOMP_BUILD_BENCH=OFF
cmake --build "$BUILD" -j"$(nproc)" --target section-prep fe-prep mbs-run
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
make -C examples/sar-antenna BUILD="$(pwd)/$BUILD" -j"$(nproc)"
echo "Results, plots and the animation are in examples/sar-antenna/out/"
