// The start-up floor of a PETSc/SLEPc program (docs/benchmarks.md, fe-prep
// against CalculiX, the fixed start): MPI_Init + SlepcInitialize and nothing
// else, and with FLEXCOMP_FLOOR_GMSH also gmsh's initialisation (the library
// fe-prep's rectangle and .geo panels mesh with). Built as two executables so
// that each loads only the shared libraries it links: what no program built on
// Debian's PETSc 3.18 / SLEPc (and gmsh 4.8) can start below. Measured by
// `bench/fe-prep/startup.sh BUILD_DIR` against `fe-prep --version`.
#include <slepcsys.h>
#ifdef FLEXCOMP_FLOOR_GMSH
#include <gmsh.h>
#endif

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  if (SlepcInitialize(&argc, &argv, nullptr, nullptr)) return 1;
#ifdef FLEXCOMP_FLOOR_GMSH
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::finalize();
#endif
  if (SlepcFinalize()) return 1;
  MPI_Finalize();
  return 0;
}
