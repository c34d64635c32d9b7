#!/bin/bash
# Memory exhaustion ends cleanly (docs/robustness.md, "Memory limits"): each tool,
# run under an address-space limit (ulimit -v) that lets it start but not finish,
# exits 1 with one "error: out of memory in stage '...'" line naming the stage and
# what it needed, and leaves no output and no temporary; fe-prep prints MUMPS's
# estimate of the factorisation's memory in its progress line and refuses before
# factorising when the estimate exceeds what the limit leaves.
#   memory_limits.sh BUILD_DIR
# The limits are found on this machine, not hard-coded: PETSc/MPI/HDF5 start-up
# takes some hundreds of MB of address space, and how much depends on the
# machine. A ladder of limits finds the smallest that runs a small input (a pass
# or fail of one run under ulimit -v is deterministic for a binary); the large
# input then runs a fixed amount above it, far below what it needs.
set -u
B=$(readlink -f "$1")
SP=$B/section-prep/section-prep FP=$B/fe-prep/fe-prep MR=$B/mbs-run/mbs-run
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
W=$(mktemp -d); trap 'rm -rf "$W"' EXIT
cd "$W"
FAIL=0
bad() { echo "FAIL: $*"; FAIL=1; }
leftovers() { ls -A | grep -E '^out|\.tmp-'; }

# limited KB cmd...: runs cmd under ulimit -v KB, output in log.
limited() { local kb=$1; shift; timeout -k 5 120 bash -c 'ulimit -v '"$kb"'; exec "$@"' _ "$@" > log 2>&1; }

# smallest_limit cmd...: the smallest limit (KB) of a ladder (x1.15 from 64 MB)
# under which cmd succeeds, or 0.
smallest_limit() {
  local kb=${LADDER_START:-65536}
  while [ $kb -le 16777216 ]; do
    rm -f out*
    if limited $kb "$@"; then echo $kb; return; fi
    kb=$((kb * 115 / 100))
  done
  echo 0
}

# expect_oom TOOL STAGE_PATTERN KB cmd...: exit 1, one error line naming the
# tool, out of memory and the stage, no output, no temporary. MPI's start-up
# does not map its shared objects the same way on every run: a run that fails
# before the tool's own code (MPI/PETSc initialisation, no "out of memory in
# stage") is retried 32 MB higher, up to 8 times.
expect_oom() {
  local tool=$1 stage=$2 kb=$3; shift 3
  local tries=0 got
  while :; do
    rm -f out*
    limited "$kb" "$@"; got=$?
    grep -q "error: out of memory in stage" log && break
    [ $got = 0 ] && break
    grep -q "initiali[sz]ation failed\|failed to map segment\|out of dynamic memory\|mca_\|opal\|orte\|pmix" log || break
    tries=$((tries + 1))
    [ $tries -ge 8 ] && break
    echo "  $tool under ulimit -v $kb: did not start (exit $got), 32 MB more"
    kb=$((kb + 32768))
  done
  echo "  $tool under ulimit -v $kb: exit $got: $(grep 'error:' log | head -c 400)"
  [ "$got" = 1 ] || bad "$tool under ulimit -v $kb -> exit $got, expected 1: $(tail -c 600 log)"
  [ "$(grep -c 'error:' log)" = 1 ] || bad "$tool -> not one error line: $(tail -c 600 log)"
  grep -q "^$tool: error: out of memory in stage '$stage'" log ||
    bad "$tool -> message lacks \"out of memory in stage '$stage'\": $(tail -c 600 log)"
  grep -q "terminate called\|Segmentation\|PETSC ERROR" log && bad "$tool -> a crash or a library trace: $(tail -c 600 log)"
  [ -z "$(leftovers)" ] || bad "$tool -> left $(leftovers)"
}

mat='materials:
  steel: {type: isotropic, E: 2.1e11, nu: 0.3, rho: 7850}'

# --- section-prep: a solid circle, coarse (the ladder) and fine (~100k elements)
printf '%s\nsection: {shape: solid_circle, diameter: 0.006, material: steel}\n' "$mat" > small_sec.yaml
printf '%s\nsection: {shape: solid_circle, diameter: 0.006, mesh_size: 2.5e-5, material: steel}\n' "$mat" > big_sec.yaml
kb=$(smallest_limit $SP small_sec.yaml -o out.h5 -q)
[ "$kb" -gt 0 ] || bad "section-prep did not run a small section under any limit up to 16 GB: $(tail -c 400 log)"
echo "section-prep: a small section runs under ulimit -v $kb"
expect_oom section-prep "section analysis\|meshing" $((kb + 65536)) $SP big_sec.yaml -o out.h5 -q

# --- fe-prep: a beam (the ladder), a 40 000-triangle panel
printf '%s\nbody:\n  name: bar\n  beam: {length: 1.0, elements: 10, section: {shape: solid_circle, diameter: 0.02, material: steel}}\n  reference: free\n  modes: 2\n' "$mat" > small_body.yaml
printf '%s\nbody:\n  name: plate\n  shell: {rectangle: {length: 2.0, width: 1.0}, material: steel, thickness: 0.002, element: dkt, mesh: {triangles: TRIS}}\n  interfaces: {root: [-1.0, 0.0, 0.0]}\n  reference: {clamp: [root]}\n  modes: 4\n' "$mat" > big_body.tmpl
sed 's/TRIS/40000/' big_body.tmpl > big_body.yaml   # 123 438 DOF, MUMPS estimate ~300 MB
kb=$(smallest_limit $FP small_body.yaml -o out.h5 -q)
[ "$kb" -gt 0 ] || bad "fe-prep did not run a small body under any limit up to 16 GB: $(tail -c 400 log)"
echo "fe-prep: a small body runs under ulimit -v $kb"
expect_oom fe-prep "building the body / [a-z-]*" $((kb + 32768)) $FP big_body.yaml -o out.h5 -q

# fe-prep's estimate: under a generous limit the progress line gives MUMPS's
# estimate E and what the limit leaves H (limit - the process's size S at that
# point); under S + E/2 the same run refuses before factorising, naming E.
big=$((kb + 4194304))
rm -f out*
limited $big $FP big_body.yaml -o out.h5 || bad "fe-prep big_body under ulimit -v $big failed: $(tail -c 600 log)"
line=$(grep -m1 -o 'factorisation ~[0-9.]* [MG]B (MUMPS estimate, [0-9.]* [MG]B available)' log)
echo "fe-prep's progress line: $line"
[ -n "$line" ] || bad "fe-prep printed no factorisation estimate: $(tail -c 600 log)"
to_kb() { awk -v v="$1" -v u="$2" 'BEGIN { printf "%d", v * (u == "GB" ? 1048576 : 1024) }'; }
if [ -n "$line" ]; then
  set -- $(echo "$line" | sed 's/factorisation ~\([0-9.]*\) \([MG]B\) (MUMPS estimate, \([0-9.]*\) \([MG]B\) available)/\1 \2 \3 \4/')
  est=$(to_kb "$1" "$2"); avail=$(to_kb "$3" "$4")
  used=$((big - avail))
  [ "$est" -gt 8192 ] || bad "the estimate $est KB is too small for this check"
  expect_oom fe-prep "building the body / eigen-solve" $((used + est / 2)) $FP big_body.yaml -o out.h5 -q
  grep -q "needs about .* by MUMPS's estimate.*refused before starting it" log ||
    bad "fe-prep's refusal does not give the estimate: $(tail -c 600 log)"
fi

# --- mbs-run: a pendulum (the ladder); the same with a torque table of 190 000
# values (yaml-cpp's nodes: ~200 MB to parse; mbs-run itself stays near 50 MB).
cat > small_scene.yaml <<'YAML'
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: rod, rod: {length: 1.0, diameter: 0.02, density: 2700}, position: [0.5, 0, 0]}
joints:
  - {name: J1, type: revolute, bodies: [ground, rod], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
simulation: {t_end: 0.1, output_step: 0.05}
YAML
awk 'BEGIN { n = 95000 }
     /^forces:/ { print; printf "  - {name: sp, type: rotational_spring_damper, joint: J1, torque: {angle: ["
                  for (i = 0; i < n; i++) printf "%s%.6f", (i ? ", " : ""), -3.2 + 6.4 * i / (n - 1)
                  printf "], value: ["
                  for (i = 0; i < n; i++) printf "%s%.3f", (i ? ", " : ""), 0.001 * (i % 7)
                  print "]}}"; next }
     { print }' small_scene.yaml > big_scene.yaml
LADDER_START=16384
kb=$(smallest_limit $MR small_scene.yaml -o out.h5 -q)
[ "$kb" -gt 0 ] || bad "mbs-run did not run a pendulum under any limit up to 16 GB: $(tail -c 400 log)"
echo "mbs-run: a pendulum runs under ulimit -v $kb"
expect_oom mbs-run "reading the scene" $((kb + 32768)) $MR big_scene.yaml -o out.h5 -q
# Below the pendulum's limit: no segmentation fault (HDF5 1.10 dereferenced a
# failed malloc when it created the results file with a few MB left).
for low in $((kb * 100 / 115)) $((kb * 100 / 130)); do
  rm -f out*
  limited $low $MR small_scene.yaml -o out.h5 -q; got=$?
  echo "  mbs-run pendulum under ulimit -v $low: exit $got: $(grep 'error:' log | head -c 200)"
  [ $got = 1 ] || [ $got = 127 ] || bad "mbs-run under ulimit -v $low -> exit $got (1, or 127 when the loader cannot map the libraries): $(tail -c 400 log)"
  [ -z "$(leftovers)" ] || bad "mbs-run under ulimit -v $low -> left $(leftovers)"
done

[ $FAIL = 0 ] && echo "memory limits: all checks passed"
exit $FAIL
