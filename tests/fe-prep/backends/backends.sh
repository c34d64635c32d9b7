#!/usr/bin/env bash
# fe-prep's two programs (docs/fe-prep.md, "Two programs"):
# 1. the serial program's ELF needs no PETSc, SLEPc or gmsh (readelf NEEDED and
#    the whole ldd closure);
# 2. every reduction it builds gives the PETSc program's body (--backend serial
#    against --backend petsc; compare_bodies.py says the bounds and why);
# 3. it hands over, with the reason in the summary's solver line: under
#    mpirun -n 2 (the same body again), a gmsh-meshed panel, a body the serial
#    path does not build (backend_choice.cpp's list: gmsh), --backend petsc; and
#    --backend serial refuses a gmsh body with one message and exit 1.
# 4. HDF5 is a module of the serial program: its ELF needs no HDF5, `--version`
#    loads none, a body run loads it through libflexcomp_feprep_h5.so (for the
#    write), the module's calls into flexcomp_base bind to the program's copy
#    (one table of temporaries for the signal handler), and a program without
#    its module stops before any work, naming where it looked.
# Usage: backends.sh BUILD_DIR
set -uo pipefail
B=$1
HERE=$(cd "$(dirname "$0")" && pwd)
DATA=$HERE/../../data
FP=$B/fe-prep/fe-prep
PY=/usr/bin/python3
W=$(mktemp -d "${TMPDIR:-/tmp}/feprep_backends.XXXXXX")
trap 'rm -rf "$W"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
fails=0
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }

# 1. What the lean program links.
needed=$(readelf -d "$FP" | grep NEEDED)
echo "$needed" | grep -qiE "petsc|slepc|gmsh" && bad "fe-prep's ELF needs PETSc/SLEPc/gmsh: $needed"
closure=$(ldd "$FP")
echo "$closure" | grep -qiE "libpetsc|libslepc|libgmsh" && bad "fe-prep's ldd closure holds PETSc/SLEPc/gmsh"
[ -x "$B/fe-prep/fe-prep-mpi" ] || bad "fe-prep-mpi is not built beside fe-prep"
echo "fe-prep loads $(echo "$closure" | grep -c '=>') shared libraries, none of PETSc, SLEPc, gmsh"

# 2. Serial against PETSc, per reduction.
run() {  # run NAME BACKEND [launcher...]: the body of $HERE/NAME.yaml into $W/NAME-BACKEND.h5
  local name=$1 be=$2
  shift 2
  "$@" "$FP" "$HERE/$name.yaml" -o "$W/$name-$be.h5" --backend "$be" > "$W/$name-$be.log" 2>&1
}
for case in deck_free:--shifted deck_held: deck_held_patches: deck_cb_points: deck_cb_patches: imported_free:--shifted \
            deck_static_error: deck_static_correction:--shifted beam_free:--shifted beam_geometric:; do
  name=${case%%:*} opt=${case#*:}
  run "$name" serial || { bad "$name serial: $(tail -3 "$W/$name-serial.log")"; continue; }
  run "$name" petsc || { bad "$name petsc: $(tail -3 "$W/$name-petsc.log")"; continue; }
  grep -q "solver: serial" "$W/$name-serial.log" || bad "$name: --backend serial was not built by the serial program"
  grep -q "solver: petsc.*asked (--backend petsc)" "$W/$name-petsc.log" || bad "$name: --backend petsc was not handed over"
  if ! $PY "$HERE/compare_bodies.py" "$W/$name-serial.h5" "$W/$name-petsc.h5" $opt > "$W/$name.cmp"; then
    bad "$name: serial and PETSc bodies differ: $(cat "$W/$name.cmp")"
  fi
  echo "$name: $(grep -E '^(eigenvalues|shapes)' "$W/$name.cmp" | tr '\n' ' ')"
done

# 3. Hand-overs. Two ranks: fe-prep execs fe-prep-mpi on both, the same body.
if command -v mpirun > /dev/null; then
  "$FP" "$HERE/deck_cb_patches.yaml" -o "$W/mpi.h5" -q > /dev/null 2>&1 &&
    mpirun -n 2 "$FP" "$HERE/deck_cb_patches.yaml" -o "$W/mpi2.h5" > "$W/mpi2.log" 2>&1 ||
    bad "mpirun -n 2 fe-prep failed: $(tail -3 "$W/mpi2.log")"
  grep -q "solver: petsc.*2 MPI ranks" "$W/mpi2.log" || bad "mpirun -n 2: not handed to fe-prep-mpi: $(grep solver "$W/mpi2.log")"
  [ "$(grep -c 'fe-prep 0\|fe-prep [0-9]' "$W/mpi2.log")" = 1 ] || bad "mpirun -n 2: the summary is not printed once"
  $PY "$HERE/compare_bodies.py" "$W/mpi.h5" "$W/mpi2.h5" > "$W/mpi.cmp" || bad "serial and mpirun -n 2 bodies differ: $(cat "$W/mpi.cmp")"
fi
# A gmsh panel (auto): handed over, the reason said; --backend serial refuses it.
cat > "$W/strip.yaml" <<YAML
materials:
  al0: {type: isotropic, E: 70.0e9, nu: 0.0, rho: 2700}
body:
  name: strip
  shell: {rectangle: {length: 1.0, width: 0.1}, material: al0, thickness: 0.01, mesh: {size: 0.05}}
  interfaces:
    root: {point: [-0.5, 0, 0], coupling: rigid, nodes: {edge: edge_xmin}}
  reference: {clamp: [root]}
  modes: 4
YAML
"$FP" "$W/strip.yaml" -o "$W/strip.h5" > "$W/strip.log" 2>&1 || bad "gmsh strip (auto) failed: $(tail -3 "$W/strip.log")"
grep -q "solver: petsc.*the panel is meshed by gmsh" "$W/strip.log" || bad "gmsh strip: no hand-over said: $(grep solver "$W/strip.log")"
"$FP" "$W/strip.yaml" -o "$W/strip2.h5" --backend serial > "$W/strip2.log" 2>&1
rc=$?
[ $rc = 1 ] || bad "--backend serial on a gmsh body -> exit $rc, expected 1"
grep -q "fe-prep: error: --backend serial cannot build this body: the panel is meshed by gmsh" "$W/strip2.log" ||
  bad "--backend serial on a gmsh body: $(cat "$W/strip2.log")"
[ -e "$W/strip2.h5" ] && bad "--backend serial on a gmsh body left an output"
# 4. Out of memory in the serial program: under ever larger address-space limits
# (from below the libraries' floor up to the first success), every failure
# above the floor (where `fe-prep --version` runs) is fe-prep's own: exit 1,
# "out of memory in stage ...", no output; at least one such (MUMPS's -13,
# CHOLMOD's status, a refused estimate, HDF5's file creation).
clean=0
for kb in $(seq 20000 3000 200000); do
  rm -f "$W"/oom.*
  (ulimit -v $kb; exec "$FP" "$HERE/deck_cb_patches.yaml" -o "$W/oom.h5" -q) > "$W/oom.log" 2>&1
  rc=$?
  [ $rc = 0 ] && break
  # Below the floor nothing of fe-prep runs: the loader refuses a library, or
  # (measured at one 1 MB step) a library's initialiser crashes before main;
  # `fe-prep --version` under the same limit tells.
  (ulimit -v $kb; exec "$FP" --version) > /dev/null 2>&1 || continue
  if [ $rc = 1 ] && grep -q "fe-prep: error: out of memory in stage '.*no output was written" "$W/oom.log" && ! ls "$W"/oom.h5* > /dev/null 2>&1; then
    clean=$((clean + 1))
  else
    bad "ulimit -v $kb: exit $rc, not a clean out-of-memory stop: $(tail -c 300 "$W/oom.log")"
  fi
done
[ $clean -gt 0 ] || bad "no out-of-memory stop of the serial program was seen below its first success ($kb KB)"
echo "out of memory: $clean clean stops below ulimit -v $kb KB"
# 4. HDF5 as a module (docs/architecture.md, "fe-prep's two programs").
echo "$needed" | grep -qi hdf5 && bad "fe-prep's ELF needs HDF5: $needed"
echo "$closure" | grep -qi libhdf5 && bad "fe-prep's ldd closure holds HDF5"
[ -f "$B/fe-prep/libflexcomp_feprep_h5.so" ] || bad "the HDF5 module is not built beside fe-prep"
LD_DEBUG=files LD_DEBUG_OUTPUT="$W/ldv" "$FP" --version > /dev/null 2>&1
grep -qE "file=(libhdf5|.*libflexcomp_feprep_h5)" "$W"/ldv.* && bad "fe-prep --version loads HDF5 or its module"
LD_DEBUG=files,bindings LD_DEBUG_OUTPUT="$W/ld" "$FP" "$HERE/deck_cb_patches.yaml" -o "$W/lazy.h5" -q > "$W/lazy.log" 2>&1 ||
  bad "deck_cb_patches with LD_DEBUG: $(tail -3 "$W/lazy.log")"
grep -qE "file=libhdf5.*needed by .*libflexcomp_feprep_h5.so" "$W"/ld.* ||
  bad "HDF5 was not loaded through the module: $(grep 'file=libhdf5' "$W"/ld.* | head -2)"
grep -qE "binding file .*libflexcomp_feprep_h5.so \[0\] to .*/fe-prep \[0\]: normal symbol .*TemporaryRegistration" "$W"/ld.* ||
  bad "the module's temporary registration does not bind to fe-prep's: $(grep 'TemporaryRegistration' "$W"/ld.* | head -2)"
"$FP" --inspect "$W/lazy.h5" > "$W/inspect.txt" 2>&1 && grep -q "flexbody/1" "$W/inspect.txt" ||
  bad "fe-prep --inspect through the module: $(head -3 "$W/inspect.txt")"
mkdir -p "$W/alone"
cp "$FP" "$W/alone/fe-prep"
"$W/alone/fe-prep" "$HERE/deck_free.yaml" -o "$W/alone/x.h5" > "$W/alone.log" 2>&1
rc=$?
[ $rc = 1 ] && grep -q "fe-prep: error: fe-prep's HDF5 module libflexcomp_feprep_h5.so is in neither $W/alone/ nor" "$W/alone.log" &&
  ! grep -q "eigen" "$W/alone.log" || bad "fe-prep without its module: exit $rc, $(tail -c 300 "$W/alone.log")"
[ -e "$W/alone/x.h5" ] && bad "fe-prep without its module left an output"
echo "HDF5: loaded by the module at the write; $(grep -c 'binding file .*libflexcomp_feprep_h5.so .* to .*/fe-prep ' "$W"/ld.*) of the module's bindings reach the program"
if [ $fails -gt 0 ]; then
  echo "$fails failure(s)"
  exit 1
fi
echo "fe-prep backends: all checks passed"
