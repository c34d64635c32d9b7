#pragma once
// fe-prep's linear algebra, PETSc backend (the program fe-prep-mpi): the types
// and the process-level calls the driver (build_body.cpp, import_stage.cpp,
// main.cpp ...) names, on PETSc/SLEPc/MUMPS over MPI. The serial backend
// (fe-prep/la/serial/la_backend.h, the program fe-prep) declares the same
// names on Eigen sparse matrices; a target picks one by its include path
// (fe-prep/CMakeLists.txt), never both (docs/architecture.md).
#include <mpi.h>
#include <petscmat.h>

#include <Eigen/Dense>
#include <string>

#include "fe-prep/petsc_handles.h"

namespace fc::feprep {

struct BodySpec;

// A communicator: the ranks that build one body together.
using Comm = MPI_Comm;
// K or M of the reduced system: a distributed PETSc matrix.
using SystemMatrix = Mat;
// A factorisation kept past the solve that made it (the fixed-interface K's
// MUMPS factor, reused by the constraint modes), and a borrowed reference to one.
using FactorHandle = OwnedMat;
using FactorRef = Mat;

// The linear-algebra library and what it was chosen for (the run's summary).
const char* backendName();

inline int commRank(Comm c) {
  int r = 0;
  MPI_Comm_rank(c, &r);
  return r;
}
// Rank 0's values to every rank.
inline void broadcast(Comm c, long* v, long n) { MPI_Bcast(v, static_cast<int>(n), MPI_LONG, 0, c); }
inline void broadcast(Comm c, int* v, long n) { MPI_Bcast(v, static_cast<int>(n), MPI_INT, 0, c); }
inline void broadcast(Comm c, double* v, long n) { MPI_Bcast(v, static_cast<int>(n), MPI_DOUBLE, 0, c); }
inline void broadcast(Comm c, char* v, long n) { MPI_Bcast(v, static_cast<int>(n), MPI_CHAR, 0, c); }

// The reduced K and M as PETSc MPIAIJ matrices (assembly.h).
struct AssembledSystem {
  Mat K = nullptr, M = nullptr;
  Eigen::VectorXd lumped;  // n_nodes * 6, summed over all ranks (every rank has it)
  long first_row = 0, local_rows = 0;
  ~AssembledSystem();
  AssembledSystem() = default;
  AssembledSystem(const AssembledSystem&) = delete;
  AssembledSystem& operator=(const AssembledSystem&) = delete;
};

// The process's linear-algebra runtime, for main(): PETSc and SLEPc started
// (their options from PETSC_OPTIONS only), PETSc's errors said once by
// fe-prep's checks; finalised on destruction. `backend` is the --backend
// choice: "serial" is refused here (it is the program fe-prep's).
class LinearAlgebraRuntime {
 public:
  LinearAlgebraRuntime(int argc, char** argv, const std::string& backend);
  ~LinearAlgebraRuntime();
  LinearAlgebraRuntime(const LinearAlgebraRuntime&) = delete;
  LinearAlgebraRuntime& operator=(const LinearAlgebraRuntime&) = delete;
  // Non-zero: the runtime could not start; main returns this.
  int failed() const { return failed_; }
  Comm world() const { return PETSC_COMM_WORLD; }
  // The serial program hands bodies it does not build to this one; here,
  // every body is built.
  void handOverIfNeeded(const BodySpec&) const {}

 private:
  int failed_ = 0;
  bool started_ = false;
};

}  // namespace fc::feprep
