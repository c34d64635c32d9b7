#!/usr/bin/env bash
# fe-prep's Craig-Bampton memory against the mesh size (docs/benchmarks.md,
# fe-prep Craig-Bampton memory): the 2.0 x 1.3 m, 2 mm benchmark panel with 8
# distributing interfaces (nodes within 0.05 m of their points, pinned: 24
# boundary DOF) and 8 fixed-interface modes; per size one fe-prep run in its
# own process (getrusage's peak is per process). Prints one markdown row per
# size: DOF, CPU seconds, the peak RSS after assembly, after the eigen-solve, of
# the reduction and of the whole run (GNU time), MUMPS's own factor figure
# (INFOG(21)), and what the reduction adds beyond assembly + factor in blocks of
# the basis' size 8 N (b + k) bytes; and the stored entries of the held K and
# of M (PETSc's -mat_view ::ascii_info on the first two assembled matrices).
#   bench/fe-prep/cb_memory.sh BUILD_DIR [DOF ...]    (default 1e4 3e4 1e5 3e5)
#   REDUCTION=free bench/fe-prep/cb_memory.sh ...     the same mesh free-free, 20 modes
#   LOG_DIR=DIR ...      keeps each run's fe-prep output (stage lines) as DIR/cb_DOF_REDUCTION.log
#   PETSC_EXTRA="-mat_mumps_icntl_7 0" ...   more PETSc options for every run (MUMPS ordering etc.)
# Run sizes one at a time on a shared machine; 1e6 DOF needs ~6 GB and ~10 min CPU.
set -euo pipefail
build=${1:?usage: cb_memory.sh BUILD_DIR [DOF ...]}
shift
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(10000 30000 100000 300000)
reduction=${REDUCTION:-craig_bampton}
feprep="$build/fe-prep/fe-prep"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| target DOF | DOF | reduction | CPU s | assembly MB | eigen-solve MB | reduction MB | whole run MB | MUMPS factor MB | basis block MB | (reduction - assembly - factor) / block | K entries | M entries |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for dof in "${sizes[@]}"; do
  # DOF ~ 6 nodes ~ 3 triangles; h from the equilateral-triangle area.
  h=$(awk -v d="$dof" 'BEGIN{n=d/3; printf "%.6g", sqrt(4*2.6/(sqrt(3)*n))}')
  {
    echo "materials:"
    echo "  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}"
    echo "body:"
    echo "  name: bench"
    echo "  shell:"
    echo "    rectangle: {length: 2.0, width: 1.3}"
    echo "    material: cfrp_iso"
    echo "    thickness: 0.002"
    echo "    element: dst"
    echo "    mesh: {size: $h, max_triangles: 5000000}"
    echo "  interfaces:"
    k=0
    for x in -0.9 -0.3 0.3 0.9; do for y in -0.55 0.55; do
      echo "    P$k: {point: [$x, $y, 0.0], coupling: distributing, nodes: {within: 0.05}}"; k=$((k + 1))
    done; done
    if [ "$reduction" = free ]; then
      echo "  reference: free"
      echo "  modes: 20"
    else
      echo "  reference: {pin: [P0, P1, P2, P3, P4, P5, P6, P7]}"
      echo "  reduction: craig_bampton"
      echo "  modes: 8"
    fi
  } > "$work/panel.yaml"
  PETSC_OPTIONS="-mat_view ::ascii_info ${PETSC_EXTRA:-}" /usr/bin/time -f "%U %S %M" -o "$work/time" "$feprep" -q "$work/panel.yaml" -o "$work/panel.h5" > "$work/out"
  [ -n "${LOG_DIR:-}" ] && cp "$work/out" "$LOG_DIR/cb_${dof}_${reduction}.log"
  awk -v target="$dof" -v red="$reduction" -v timefile="$work/time" '
    BEGIN { getline t < timefile; split(t, a, " "); cpu = a[1] + a[2]; whole = a[3] / 1024 }
    / DOF, / { for (i = 1; i <= NF; ++i) if ($i == "DOF,") n = $(i - 1) }
    /total: nonzeros=/ { if (++mats <= 2) { v = $2; sub(/nonzeros=/, "", v); sub(/,/, "", v); nnz[mats] = v } }
    /basis: craig_bampton:/ { cols = $3 + $7 }
    /basis: free:/ { cols = $3 }
    /peak RSS/ && !/write/ {
      match($0, /peak RSS [0-9]+/); mb = substr($0, RSTART + 9, RLENGTH - 9)
      if ($1 == "assembly") asm = mb
      if ($1 == "eigensolve") eig = mb
      if ($1 == "constraints" || $1 == "reduction") red_mb = (mb > red_mb ? mb : red_mb)
      if (match($0, /MUMPS factor [0-9]+/)) { f = substr($0, RSTART + 13, RLENGTH - 13); if (f + 0 > fac) fac = f + 0 }
    }
    END {
      block = 8 * n * cols / 1048576
      if (red_mb == "") { red_mb = eig; extra = "-" } else extra = sprintf("%.2f", (red_mb - asm - fac) / block)
      printf "| %d | %d | %s | %.1f | %d | %d | %d | %.0f | %d | %.1f | %s | %.3g | %.3g |\n", target, n, red, cpu, asm, eig, red_mb, whole, fac, block, extra, nnz[1], nnz[2]
    }' "$work/out"
done
