#!/usr/bin/env bash
# Installs every Debian 12 package the build, the tests, the example and the plots need.
set -euo pipefail
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
PKGS=(cmake g++ make pkg-config
      libeigen3-dev petsc-dev slepc-dev libsuitesparse-dev libhdf5-openmpi-dev openmpi-bin
      libgmsh-dev libcli11-dev libyaml-cpp-dev libssl-dev
      libgtest-dev libgmock-dev libbenchmark-dev
      hdf5-tools python3-matplotlib python3-h5py python3-numpy python3-yaml
      libmumps-seq-dev libarpack2-dev   # fe-prep's serial program: sequential MUMPS and ARPACK (docs/architecture.md)
      python3-scipy python3-mpi4py)   # flexcomp-study: Sobol' designs (scipy.stats.qmc), --executor mpi (docs/studies.md)
# --with-openblas: libopenblas0-serial, serial OpenBLAS for MUMPS's dense kernels
# inside fe-prep built with -DFLEXCOMP_OPENBLAS=ON (opt-in: OpenBLAS hangs instead
# of failing when its work buffer cannot be allocated; fe-prep/CMakeLists.txt)
# (half of a fe-prep run was Debian's reference BLAS; docs/benchmarks.md, fe-prep
# against CalculiX). fe-prep links the library itself. Installing it in apt's
# auto mode also makes it the system's libblas.so.3 for every program; to keep
# the reference BLAS elsewhere set that alternative by hand (update-alternatives
# --set libblas.so.3-x86_64-linux-gnu /usr/lib/x86_64-linux-gnu/blas/libblas.so.3).
# --with-paraview (what CI uses, .ci/test.sh): pvpython, so that the test loading
# BODY.xdmf and the animation in ParaView runs instead of being skipped
# (python3-paraview pulls in paraview, about 0.5 GB).
# --with-slurm: a Slurm controller, node daemon and munge, so that the sampling study's
# Slurm route runs end to end in tests/examples/check_study_executors.py (it starts a
# private controller on localhost; without these packages the test runs the array's
# scripts by hand and says the submission was skipped).
for arg in "$@"; do
  case "$arg" in
    --with-paraview) PKGS+=(python3-paraview) ;;
    --with-slurm) PKGS+=(slurmctld slurmd slurm-client munge) ;;
    --with-openblas) PKGS+=(libopenblas0-serial) ;;
  esac
done
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "Installing: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
