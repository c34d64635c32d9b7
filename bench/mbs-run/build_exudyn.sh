#!/bin/sh
# Builds Exudyn (1.11, no graphics) from its sources with Debian packages only
# (python3-dev, pybind11-dev, python3-numpy; no pip), for the side by side of
# bench/mbs-run/exudyn_chains.py. Not part of flexcomp's build or CI.
#   build_exudyn.sh EXUDYN_SOURCE_DIR OUT_DIR
# EXUDYN_SOURCE_DIR: the repository's `main` folder (src/, include/,
# pythonDev/exudyn/, setup.py). OUT_DIR receives the build tree and
# OUT_DIR/pkg/exudyn, the Python package with exudynCPPfast*.so in it
# (pass OUT_DIR/pkg to exudyn_chains.py --exudyn).
# Flags as Exudyn's setup.py for Linux: -O3, EXUDYN_RELEASE, __NOGLFW,
# __FAST_EXUDYN_LINALG (its "fast" module without range checks); pybind11
# links with LTO. About 40 min CPU on one core.
set -eu
SRC=$(cd "$1" && pwd)
OUT=$(mkdir -p "$2" && cd "$2" && pwd)
PY=/usr/bin/python3
PYVER=$($PY -c 'import sys; print(f"{sys.version_info.major}{sys.version_info.minor}")')
# The C++ files setup.py compiles (its list, not a glob: some sources are
# experimental and excluded there).
$PY - "$SRC/setup.py" "$OUT/files.txt" <<'EOF'
import re, sys
src = open(sys.argv[1]).read()
block = src[src.index('cppFiles = ['):src.index('#some specific include directories for exudyn')]
open(sys.argv[2], 'w').write('\n'.join(re.findall(r"'(src/[^']+\.cpp)'", block)))
EOF
cat > "$OUT/CMakeLists.txt" <<EOF
cmake_minimum_required(VERSION 3.16)
project(exudyn_local CXX)
set(CMAKE_CXX_STANDARD 17)
find_package(Python3 REQUIRED COMPONENTS Interpreter Development)
find_package(pybind11 REQUIRED)
file(STRINGS \${CMAKE_CURRENT_SOURCE_DIR}/files.txt SRC)
list(TRANSFORM SRC PREPEND $SRC/)
pybind11_add_module(exudynCPPfast \${SRC})
target_include_directories(exudynCPPfast PRIVATE $SRC/src $SRC/include $SRC/include/lest)
target_compile_definitions(exudynCPPfast PRIVATE EXUDYN_RELEASE __EXUDYN__PYTHON$PYVER __NOGLFW
  __FAST_EXUDYN_LINALG VERSION_INFO="1.11.0")
target_compile_options(exudynCPPfast PRIVATE -O3 -g0 -w)
target_link_libraries(exudynCPPfast PRIVATE stdc++fs)
EOF
cmake -S "$OUT" -B "$OUT/b" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=$PY
nice -n 10 cmake --build "$OUT/b" -j2
mkdir -p "$OUT/pkg"
rm -rf "$OUT/pkg/exudyn"
cp -r "$SRC/pythonDev/exudyn" "$OUT/pkg/"
cp "$OUT"/b/exudynCPPfast*.so "$OUT/pkg/exudyn/"
echo "Exudyn package: $OUT/pkg"
