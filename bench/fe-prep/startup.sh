#!/usr/bin/env bash
# fe-prep's fixed start against the floor of any program on the same libraries
# (docs/benchmarks.md, fe-prep against CalculiX): median and minimum CPU
# (user + system) and median peak RSS of REPEAT (default 7) runs each of
#   a C program that returns at once (the process itself),
#   startup_floor_slepc       MPI_Init + SlepcInitialize (Debian's PETSc/SLEPc 3.18),
#   startup_floor_slepc_gmsh  the same + gmsh::initialize (gmsh 4.8),
#   fe-prep --version         (loads its libraries, initialises nothing),
# with the shared libraries each loads and the relocations the dynamic loader
# makes before main (LD_DEBUG=statistics).
#   bench/fe-prep/startup.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:?usage: startup.sh BUILD_DIR}" && pwd)
repeat=${REPEAT:-7}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1} OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}
printf 'int main(void) { return 0; }\n' > "$work/empty.c"
cc -O2 "$work/empty.c" -o "$work/empty"
echo "| program | shared libraries | relocations | CPU s (median, min) | peak RSS MB (median) |"
echo "|---|---|---|---|---|"
for cmd in "$work/empty" "$build/bench/fe-prep/startup_floor_slepc" "$build/bench/fe-prep/startup_floor_slepc_gmsh" "$build/fe-prep/fe-prep --version"; do
  exe=${cmd%% *}
  libs=$(ldd "$exe" | grep -c '=>' || true)
  rel=$(LD_DEBUG=statistics $cmd 2>&1 >/dev/null | awk '/ number of relocations:/ && !/final/ { print $NF; exit }')
  : > "$work/t"
  for _ in $(seq "$repeat"); do /usr/bin/time -f "%U %S %M" -a -o "$work/t" $cmd > /dev/null 2>&1; done
  awk -v name="$(basename "$exe")${cmd#"$exe"}" -v libs="$libs" -v rel="$rel" '
    { c[NR] = $1 + $2; m[NR] = $3 / 1024 }
    END { n = NR
      for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) { if (c[j] < c[i]) { t = c[i]; c[i] = c[j]; c[j] = t } if (m[j] < m[i]) { t = m[i]; m[i] = m[j]; m[j] = t } }
      h = int((n + 1) / 2); printf "| %s | %s | %s | %.2f, %.2f | %.0f |\n", name, libs, rel, c[h], c[1], m[h] }' "$work/t"
done
echo "load average $(awk '{print $1}' /proc/loadavg)"
