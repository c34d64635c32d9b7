#!/usr/bin/env bash
# fe-prep against CalculiX 2.20 (`ccx`, S8R shells, SPOOLES) on the benchmark
# panel, free-free and Craig-Bampton, side by side at each size
# (docs/benchmarks.md, fe-prep against CalculiX). The panel: 2.0 x 1.3 m, 2 mm,
# E = 159 GPa, nu = 0.38, rho = 1610. Both codes get their mesh as a file
# written by `calculix_panel.py` before the timed runs: CalculiX a structured
# S8R grid (its deck), fe-prep a structured grid of DST triangles with as many
# nodes as the S8R grid has (equal shell DOF, 6 a node): MESH=nastran (the
# default) as a Nastran bulk-data deck (GRID, CTRIA3, PSHELL, MAT1) that
# fe-prep reads with its own parser, MESH=file as a gmsh 2.2 .msh read through
# gmsh (the same nodes and triangles: the same body). MESH=gmsh instead has
# fe-prep mesh the rectangle itself inside its timed run (gmsh, unstructured
# DST at the requested DOF), as the earlier tables did. The sizes are the
# user's model sizes, and both are converged to < 0.1 % in f1 from 1e4 DOF up
# (the table shows it).
#   free-free:     fe-prep `reference: free`, 20 elastic modes;
#                  ccx *FREQUENCY, 26 modes (its 6 rigid ones + 20).
#   Craig-Bampton: 8 `distributing` interfaces on the mid-surface nodes within
#                  R of (+-0.9 / +-0.3, +-0.55), pinned (24 boundary DOF),
#                  8 fixed-interface modes; fe-prep `reduction: craig_bampton`;
#                  ccx: *FREQUENCY with the 8 points fixed (8 modes), then
#                  *SUBSTRUCTURE GENERATE retaining their 24 translations
#                  (the constraint modes' static solves on one factorisation).
#                  R = 0.05 m (0.2 m at 1e3 DOF, whose elements are larger).
# Each job runs alone in its own process under GNU time (CPU = user + system;
# peak RSS); one thread each (OMP_NUM_THREADS=1). Jobs that may pass ~3 GB
# (fe-prep from FEPREP_LOCK_DOF = 4e5 DOF, ~6.5 kB a DOF; CalculiX from
# CCX_LOCK_DOF = 2e5, ~13 kB a DOF) run under `flock $BIGRUN_LOCK` (default
# /work/tmp/bigrun.lock if that directory exists) so that big runs on a shared
# machine queue; BIGRUN_LOCK=none when the whole script already runs under that
# lock. CalculiX runs up to CCX_MAX_DOF (default 4e5; at 1e6 it needs
# ~13 GB); beyond, its row is an estimate from a power-law fit of its measured
# sizes >= 1e4 DOF, marked "est.". The 1-minute load average is printed with
# each row: on a loaded machine CPU seconds are the figure, not wall time.
#   bench/fe-prep/compare.sh BUILD_DIR [DOF ...]   (default 1e3 1e4 1e5 3e5 1e6)
#   unattended at the large sizes, CalculiX measured too (~13 GB at 1e6):
#   CCX_MAX_DOF=2000000 bench/fe-prep/compare.sh build 300000 1000000
#   REDUCTIONS="free craig_bampton" (default both), MESH=nastran|file|gmsh (default nastran),
#   KEEP=DIR keeps the outputs
#   (and the CalculiX rows the 1e6 estimate is fitted to, across calls).
set -euo pipefail
build=${1:?usage: compare.sh BUILD_DIR [DOF ...]}
shift
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(1000 10000 100000 300000 1000000)
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "$build" && pwd)
feprep="$build/fe-prep/fe-prep"
py=/usr/bin/python3
ccx_max=${CCX_MAX_DOF:-400000}
feprep_lock_dof=${FEPREP_LOCK_DOF:-400000}
ccx_lock_dof=${CCX_LOCK_DOF:-200000}
lock=${BIGRUN_LOCK:-}
[ -z "$lock" ] && [ -d /work/tmp ] && lock=/work/tmp/bigrun.lock
[ "$lock" = none ] && lock=""   # the caller holds the lock already (a nested flock would wait forever)
reductions=${REDUCTIONS:-free craig_bampton}
mesh_mode=${MESH:-nastran}
case "$mesh_mode" in nastran|file|gmsh) ;; *) echo "compare.sh: MESH=$mesh_mode: expected nastran, file or gmsh" >&2; exit 2 ;; esac
if [ -n "${KEEP:-}" ]; then work=$KEEP; mkdir -p "$work"; else work=$(mktemp -d); trap 'rm -rf "$work"' EXIT; fi
export OMP_NUM_THREADS=1 FLEXCOMP_QUIET=1
# Both codes on the same BLAS: fe-prep links serial OpenBLAS when it is
# installed (CMake option FLEXCOMP_OPENBLAS); Debian's ccx is linked to the
# system's libblas.so.3 (the reference BLAS by default) and then gets the same
# OpenBLAS by LD_PRELOAD. Without OpenBLAS both run on the system's BLAS.
blas=$(ldd "$feprep" | awk '/libopenblas/ { print $3; exit }')
ccx_env=(env)
[ -n "$blas" ] && ccx_env=(env LD_PRELOAD="$blas")
echo "BLAS: ${blas:-system libblas.so.3} (both codes)"
case "$mesh_mode" in
  nastran) echo "fe-prep's mesh: structured DST grid read from a Nastran deck written before the run (equal DOF to the S8R deck)" ;;
  file) echo "fe-prep's mesh: structured DST grid read from a .msh (through gmsh) written before the run (equal DOF to the S8R deck)" ;;
  gmsh) echo "fe-prep's mesh: gmsh, inside fe-prep's run" ;;
esac
echo

# "wall_s cpu_s peak_MB" of a command run in directory $1, stdout to $2.
timed() {
  local dir=$1 out=$2 big=$3; shift 3
  local pre=()
  [ "$big" = 1 ] && [ -n "$lock" ] && pre=(flock "$lock")
  (cd "$dir" && "${pre[@]}" /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$@" > "$out" 2>&1)
  awk '{printf "%.2f %.2f %.0f", $1, $2 + $3, $4 / 1024}' "$work/time"
}
load() { awk '{print $1}' /proc/loadavg; }

feprep_yaml() {  # dof reduction radius
  local h
  h=$(awk -v d="$1" 'BEGIN{n=d/3; printf "%.6g", sqrt(4*2.6/(sqrt(3)*n))}')  # DOF ~ 6 nodes ~ 3 triangles
  if [ "$mesh_mode" != nastran ]; then
    echo "materials:"
    echo "  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}"
  fi
  echo "body:"
  echo "  name: bench"
  if [ "$mesh_mode" = nastran ]; then
    echo "  mesh: {file: panel.bdf}"   # its own PSHELL and MAT1: the material of the other modes
  elif [ "$mesh_mode" = file ]; then
    echo "  mesh: {file: panel.msh}"
    echo "  regions:"
    echo "    panel: {shell: {material: cfrp_iso, thickness: 0.002, element: dst}}"
  else
    echo "  shell: {rectangle: {length: 2.0, width: 1.3}, material: cfrp_iso, thickness: 0.002, element: dst, mesh: {size: $h, max_triangles: 5000000}}"
  fi
  if [ "$2" = free ]; then
    echo "  reference: free"
    echo "  modes: 20"
  else
    echo "  interfaces:"
    local k=0 x y
    for x in -0.9 -0.3 0.3 0.9; do for y in -0.55 0.55; do
      echo "    P$k: {point: [$x, $y, 0.0], coupling: distributing, nodes: {within: $3}}"; k=$((k + 1))
    done; done
    echo "  reference: {pin: [P0, P1, P2, P3, P4, P5, P6, P7]}"
    echo "  reduction: craig_bampton"
    echo "  modes: 8"
  fi
}

# Power-law fit y = a x^b over the measured CalculiX rows (x >= 1e4) of one
# reduction, evaluated at $2: "cpu MB".
estimate() {
  awk -v red="$1" -v x="$2" '$1 == red && $2 >= 10000 && $3 > 0 {
      n++; lx = log($2); sx += lx; sxx += lx * lx
      sc += log($3); sxc += lx * log($3); sm += log($4); sxm += lx * log($4) }
    END { if (n < 2) { print "- -"; exit }
      d = n * sxx - sx * sx; bc = (n * sxc - sx * sc) / d; bm = (n * sxm - sx * sm) / d
      ac = (sc - bc * sx) / n; am = (sm - bm * sx) / n
      printf "%.0f %.0f %.2f %.2f", exp(ac + bc * log(x)), exp(am + bm * log(x)), bc, bm }' "$work/ccx_fit"
}
# With KEEP, the measured CalculiX rows accumulate over invocations (sizes run
# one call at a time still feed the fit).
touch "$work/ccx_fit"

echo "| target DOF | reduction | fe-prep DOF | fe-prep CPU s | fe-prep wall s | fe-prep MB | fe-prep stages CPU s (mesh / assembly / eigen / constraints / reduction) | CalculiX DOF | CalculiX CPU s | CalculiX wall s | CalculiX MB | CPU ratio | memory ratio | fe-prep f1, f_last Hz | CalculiX f1, f_last Hz | load |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for dof in "${sizes[@]}"; do
  big_fe=0; [ "$dof" -ge "$feprep_lock_dof" ] && big_fe=1
  big_ccx=0; [ "$dof" -ge "$ccx_lock_dof" ] && big_ccx=1
  radius=0.05; [ "$dof" -lt 5000 ] && radius=0.2
  # S8R: nodes = (2nx+1)(2ny+1) - nx ny ~ 3 nx ny, 6 DOF each; nx/ny = 2/1.3.
  read -r nx ny <<< "$(awk -v d="$dof" 'BEGIN{q=d/18; nx=int(sqrt(q*2/1.3)+0.5); ny=int(q/nx+0.5); print nx, ny}')"
  for red in $reductions; do
    d="$work/$dof-$red"; mkdir -p "$d"
    feprep_yaml "$dof" "$red" "$radius" > "$d/panel.yaml"
    # Both meshes (the S8R deck, fe-prep's .msh) written before either timed run.
    cb_arg=(); [ "$red" = free ] || cb_arg=(--craig-bampton "$radius")
    msh_arg=()
    [ "$mesh_mode" = file ] && msh_arg=(--msh "$d/panel.msh")
    [ "$mesh_mode" = nastran ] && msh_arg=(--bdf "$d/panel.bdf")
    cdof=$($py "$here/calculix_panel.py" "$nx" "$ny" "$d/c.inp" "${cb_arg[@]}" "${msh_arg[@]}" | awk 'NR == 1 {print $(NF-2)}')
    l0=$(load)
    read -r f_wall f_cpu f_mem <<< "$(timed "$d" "$d/fe.txt" "$big_fe" "$feprep" -q panel.yaml -o panel.h5)"
    fdof=$(grep -o '[0-9]* DOF,' "$d/fe.txt" | head -1 | cut -d' ' -f1)
    stages=$(awk '$2 ~ /^[0-9.]+$/ && $3 == "s" && /CPU/ { c[$1] = $5 }
      END { printf "%s / %s / %s / %s / %s", c["meshing"], c["assembly"], c["eigensolve"], (c["constraints"] == "" ? "-" : c["constraints"]), (c["reduction"] == "" ? "-" : c["reduction"]) }' "$d/fe.txt")
    if [ "$red" = free ]; then
      ff=$(awk '$1 == "1" { a = $2 } $1 == "20" { b = $2 } END { printf "%.4f, %.3f", a, b }' "$d/fe.txt")
    else
      ff=$($py -c "import h5py, numpy as np; l = np.sqrt(h5py.File('$d/panel.h5')['reduction/kept_eigenvalues'][:]) / (2 * np.pi); print(f'{l[0]:.4f}, {l[-1]:.3f}')")
    fi
    rm -f "$d/panel.h5" "$d/panel.xdmf" "$d/panel.msh" "$d/panel.bdf"
    if [ "$dof" -le "$ccx_max" ]; then
      read -r c_wall c_cpu c_mem <<< "$(timed "$d" "$d/c.txt" "$big_ccx" "${ccx_env[@]}" ccx -i c)"
      # Eigenvalue table of the .dat: the first step's modes (free: skip the 6 rigid ones).
      cf=$(awk -v red="$red" '/E I G E N V A L U E   O U T P U T/ { on++ } /P A R T I C/ { on = (on == 1 ? -1 : on) }
        on == 1 && $1 ~ /^[0-9]+$/ && NF == 5 { f[$1] = $4 }
        END { if (red == "free") printf "%.4f, %.3f", f[7], f[26]; else printf "%.4f, %.3f", f[1], f[8] }' "$d/c.dat")
      echo "$red $cdof $c_cpu $c_mem" >> "$work/ccx_fit"
      rm -f "$d/c.frd" "$d/c.12d"
      ratio=$(awk -v a="$f_cpu" -v b="$c_cpu" -v m="$f_mem" -v n="$c_mem" 'BEGIN{printf "%.3f | %.3f", a / b, m / n}')
      ccols="$cdof | $c_cpu | $c_wall | $c_mem | $ratio | $ff | $cf"
    else
      read -r e_cpu e_mem bc bm <<< "$(estimate "$red" "$cdof")"
      ratio=$(awk -v a="$f_cpu" -v b="$e_cpu" -v m="$f_mem" -v n="$e_mem" 'BEGIN{ if (b == "-") print "- | -"; else printf "%.3f (est.) | %.3f (est.)", a / b, m / n}')
      ccols="$cdof | $e_cpu (est., DOF^$bc) | - | $e_mem (est., DOF^$bm) | $ratio | $ff | not run"
    fi
    echo "| $dof | $red | $fdof | $f_cpu | $f_wall | $f_mem | $stages | $ccols | $l0 |"
  done
done
