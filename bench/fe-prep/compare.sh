#!/usr/bin/env bash
# fe-prep (serial and mpirun -n 2) against CalculiX (*FREQUENCY, S8R shells) on
# the free-free benchmark panel: 2.0 x 1.3 m, 2 mm, E = 159 GPa, nu = 0.38,
# rho = 1610, 20 elastic modes. Prints one markdown table row per size: DOF,
# wall time and peak memory of each run, first and 20th elastic frequency.
#   bench/fe-prep/compare.sh BUILD_DIR [DOF ...]      (default sizes 1e3 .. 5e5)
# CalculiX runs up to CCX_MAX_DOF (default 70000): beyond, it needs far longer
# than fe-prep (see docs/fe-prep.md). Needs calculix-ccx (apt-get install calculix-ccx).
set -euo pipefail
build=${1:?usage: compare.sh BUILD_DIR [DOF ...]}
shift
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(1000 4000 16000 64000 256000 500000)
here=$(cd "$(dirname "$0")" && pwd)
feprep="$build/fe-prep/fe-prep"
ccx_max=${CCX_MAX_DOF:-70000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 FLEXCOMP_QUIET=1

# "wall_s cpu_s peak_MB" of a command (GNU time: CPU = user + system of the
# command and its children, the MPI ranks included), its stdout to $2. On a
# shared machine the CPU time is the comparable figure.
timed() { local out=$1; shift; /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$@" > "$out" 2>/dev/null; awk '{printf "%.2f %.2f %.0f", $1, $2 + $3, $4/1024}' "$work/time"; }

echo "| target DOF | fe-prep DOF | serial wall s | serial CPU s | serial MB | -n 2 wall s | -n 2 CPU s (both ranks) | -n 2 MB (max rank) | f1 Hz | f20 Hz | CalculiX DOF | CalculiX wall s | CalculiX CPU s | CalculiX MB | CalculiX f1 | CalculiX f20 |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for dof in "${sizes[@]}"; do
  # DOF ~ 6 nodes ~ 3 triangles; h from the equilateral-triangle area.
  h=$(awk -v d="$dof" 'BEGIN{n=d/3; printf "%.6g", sqrt(4*2.6/(sqrt(3)*n))}')
  cat > "$work/panel.yaml" <<YAML
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  name: bench
  shell: {rectangle: {length: 2.0, width: 1.3}, material: cfrp_iso, thickness: 0.002, element: dst, mesh: {size: $h}}
  reference: free
  modes: 20
YAML
  read -r s_wall s_cpu s_mem <<< "$(timed "$work/s.txt" "$feprep" -q "$work/panel.yaml" -o "$work/s.h5")"
  read -r p_wall p_cpu p_mem <<< "$(timed "$work/p.txt" mpirun -n 2 --oversubscribe "$feprep" -q "$work/panel.yaml" -o "$work/p.h5")"
  fdof=$(grep -o '[0-9]* DOF' "$work/s.txt" | head -1 | cut -d' ' -f1)
  f1=$(awk '$1=="1"{print $2}' "$work/s.txt"); f20=$(awk '$1=="20"{print $2}' "$work/s.txt")
  c_cols="- | - | - | - | - | -"
  if [ "$dof" -le "$ccx_max" ]; then
    # S8R: nodes = (2nx+1)(2ny+1) - nx ny ~ 3 nx ny, 6 DOF each; nx/ny = 2/1.3.
    read -r nx ny <<< "$(awk -v d="$dof" 'BEGIN{q=d/18; nx=int(sqrt(q*2/1.3)+0.5); ny=int(q/nx+0.5); print nx, ny}')"
    cdof=$(python3 "$here/calculix_panel.py" "$nx" "$ny" "$work/c.inp" | awk '{print $(NF-2)}')
    read -r c_wall c_cpu c_mem <<< "$(cd "$work" && OMP_NUM_THREADS=2 timed "$work/c.txt" ccx -i c)"
    cf=$(awk '/E I G E N V A L U E/{on=1} on && $1 ~ /^[0-9]+$/ && NF==5 {print $4}' "$work/c.dat" | sed -n '7p;26p' | awk '{printf "%.4f ", $1}')
    c_cols="$cdof | $c_wall | $c_cpu | $c_mem | $(echo "$cf" | awk '{print $1" | "$2}')"
  fi
  echo "| $dof | $fdof | $s_wall | $s_cpu | $s_mem | $p_wall | $p_cpu | $p_mem | $f1 | $f20 | $c_cols |"
done
