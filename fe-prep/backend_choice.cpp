#include "fe-prep/backend_choice.h"

#include <cstdlib>

namespace fc::feprep {

long launcherRanks() {
  // mpirun (OpenMPI), MPICH's Hydra and PMI-2 launchers, MPICH's local count,
  // and srun's step (srun --mpi=pmix sets no PMI_SIZE).
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MPI_LOCALNRANKS", "SLURM_STEP_NUM_TASKS"}) {
    const char* s = std::getenv(v);
    if (s && std::atol(s) > 1) return std::atol(s);
  }
  return 1;
}

std::string petscReason(const std::string& backend, long ranks) {
  if (backend == "petsc") return "asked (--backend petsc)";
  if (ranks > 1) return std::to_string(ranks) + " MPI ranks";
  return "";
}

std::string petscReason(const BodySpec& spec) {
  // Meshing goes through gmsh, which only fe-prep-mpi links (its static
  // initialisers alone cost ~40 MB and 0.2 s: docs/fe-prep.md).
  if (spec.shell) return spec.shell->rectangle ? "the panel is meshed by gmsh" : "the .geo outline is meshed by gmsh";
  if (spec.general && !spec.general->deck_mesh) return "the mesh file is read by gmsh";
  return "";
}

}  // namespace fc::feprep
