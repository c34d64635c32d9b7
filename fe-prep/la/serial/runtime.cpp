// The serial program's runtime: the decision to hand a run to fe-prep-mpi
// (backend_choice.h) and the hand-over itself (execv, the same arguments).
#include <omp.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/files.h"
#include "common/input.h"
#include "fe-prep/backend_choice.h"
#include "fe-prep/gmsh_mesh.h"
#include "la_backend.h"

namespace fc::feprep {
inline namespace serial {

namespace {

// fe-prep-mpi beside this program (the build tree's fe-prep/ and the
// install's bin/ both hold the two).
std::string petscProgram() { return programDirectory() + "fe-prep-mpi"; }

// Replaces this process by fe-prep-mpi with the same arguments; returns only
// on failure, with the reason.
std::string handOver(char** argv, const std::string& why) {
  const std::string path = petscProgram();
  setenv(kHandOverVariable, why.c_str(), 1);
  std::fflush(stdout);
  std::fflush(stderr);
  execv(path.c_str(), argv);
  return "cannot run " + path + " (" + std::strerror(errno) + "), which builds this body (" + why + ")";
}

}  // namespace

LinearAlgebraRuntime::LinearAlgebraRuntime(int, char** argv, const std::string& backend) : argv_(argv), backend_(backend) {
  // One thread, as the PETSc program's ranks: CHOLMOD's OpenMP regions ask for
  // 4 threads whatever OMP_NUM_THREADS says, and under an address-space limit
  // libgomp's thread creation failed with an abort of its own (not fe-prep's
  // out-of-memory message). No active parallel level runs every region on this thread.
  omp_set_max_active_levels(0);
  const long ranks = launcherRanks();
  if (backend == "serial" && ranks > 1) {
    std::fprintf(stderr, "fe-prep: error: --backend serial runs on one process, not %ld MPI ranks; run it without "
                         "mpirun, or choose --backend auto or petsc\n", ranks);
    failed_ = 2;
    return;
  }
  const std::string why = petscReason(backend, ranks);
  if (why.empty()) return;
  std::fprintf(stderr, "fe-prep: error: %s\n", handOver(argv, why).c_str());
  failed_ = 1;
}

void LinearAlgebraRuntime::handOverIfNeeded(const BodySpec& spec) const {
  const std::string why = petscReason(spec);
  if (why.empty()) return;
  if (backend_ == "serial")
    throw std::runtime_error("--backend serial cannot build this body: " + why + "; choose --backend auto or petsc");
  throw std::runtime_error(handOver(argv_, why));
}

}  // namespace serial

// The serial program meshes nothing with gmsh: petscReason hands every such
// body to fe-prep-mpi before the build starts, so this is never reached.
Mesh meshWithGmsh(const BodySpec&, const std::vector<std::string>&, bool) {
  throw std::logic_error("fe-prep (serial) links no gmsh: the body should have gone to fe-prep-mpi (backend_choice.h)");
}

}  // namespace fc::feprep
