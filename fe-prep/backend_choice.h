#pragma once
// Which program builds a body (docs/fe-prep.md, "Two programs"): fe-prep, the
// serial backend (one process; Eigen, MUMPS, ARPACK; no PETSc, SLEPc, gmsh or
// MPI_Init: a small body costs what its work costs), or fe-prep-mpi, the PETSc
// backend (MPI ranks, gmsh meshing). fe-prep decides before any work and
// hands a run it does not build to fe-prep-mpi with the same arguments
// (execv), so that users see one command, one set of messages, one exit code.
#include <string>

#include "fe-prep/body_spec.h"

namespace fc::feprep {

// The environment variable the serial program sets, for fe-prep-mpi, to the
// reason it handed the run over (printed in the summary's solver line).
constexpr const char* kHandOverVariable = "FLEXCOMP_FEPREP_HANDOVER";

// The number of ranks the launcher started (mpirun/mpiexec/srun's environment:
// OMPI_COMM_WORLD_SIZE, PMI_SIZE, MPI_LOCALNRANKS, SLURM_STEP_NUM_TASKS), 1
// when none says more.
long launcherRanks();

// Why fe-prep-mpi must build this run, or "" when the serial program does.
// `backend`: the --backend choice (auto, serial, petsc); `ranks`: launcherRanks().
// The one list of what the serial path does not (yet) build is here.
std::string petscReason(const std::string& backend, long ranks);
std::string petscReason(const BodySpec& spec);

}  // namespace fc::feprep
