// The PETSc backend's process runtime (fe-prep-mpi): PETSc and SLEPc started
// and finalised around the run.
#include <slepcsys.h>

#include <cstdio>
#include <cstdlib>

#include "fe-prep/petsc_handles.h"
#include "la_backend.h"

namespace fc::feprep {

const char* backendName() { return "petsc (PETSc/SLEPc, MUMPS; program fe-prep-mpi)"; }

LinearAlgebraRuntime::LinearAlgebraRuntime(int, char**, const std::string& backend) {
  if (backend == "serial") {
    std::fprintf(stderr, "fe-prep-mpi: error: --backend serial is the one-process program's: run fe-prep "
                         "(without mpirun) for it\n");
    failed_ = 2;
    return;
  }
  // PETSc options come from PETSC_OPTIONS only: the command line belongs to CLI11.
  if (SlepcInitialize(nullptr, nullptr, nullptr, nullptr)) {
    std::fprintf(stderr, "fe-prep: error: SLEPc/PETSc initialisation failed\n");
    failed_ = 1;
    return;
  }
  started_ = true;
  // PETSc's errors come back as codes, each said once as a sentence by
  // fe-prep's checks (an allocation failure as out of memory, with the stage),
  // not as PETSc's multi-line trace; FLEXCOMP_PETSC_TRACE=1 keeps the trace.
  if (!std::getenv("FLEXCOMP_PETSC_TRACE")) PetscPushErrorHandler(recordingErrorHandler, nullptr);
}

LinearAlgebraRuntime::~LinearAlgebraRuntime() {
  if (started_) SlepcFinalize();
}

}  // namespace fc::feprep
