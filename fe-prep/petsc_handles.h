#pragma once
// PETSc plumbing shared by fe-prep's solvers (assembly, modal_solver,
// craig_bampton, static_response): an error check that throws, handles that
// release their object on every path (a thrown error included), whole
// vectors to and from a distributed Vec, and the MUMPS Cholesky solver that
// every factorisation in fe-prep uses.
#include <petscksp.h>

#include <Eigen/Dense>
#include <memory>
#include <string>

namespace fc::feprep {

// Throws std::runtime_error "PETSc error in WHAT (code N)" for a non-zero code;
// PETSc's allocation failure (PETSC_ERR_MEM) is fc::OutOfMemory (common/memory.h).
void check(PetscErrorCode ierr, const char* what);

// PETSc's error handler in fe-prep: returns the code as PetscReturnErrorHandler
// does (no trace printed; fe-prep's checks say what failed) and remembers an
// allocation failure (PETSC_ERR_MEM, with the size PETSc asked for and the
// function that asked), which check() then reports as fc::OutOfMemory. PETSc
// 3.18 does not always hand PETSC_ERR_MEM back up the call chain: the handler
// sees it where it starts.
PetscErrorCode recordingErrorHandler(MPI_Comm comm, int line, const char* fun, const char* file, PetscErrorCode n,
                                     PetscErrorType p, const char* mess, void* ctx);

// MUMPS's estimate of the memory a Cholesky factorisation of A needs, from its
// analysis alone (INFOG(16): the largest rank, INFOG(17): all ranks, MB; -1 if
// MUMPS gave none), in one line for the progress bar: "factorisation ~830 MB
// (MUMPS estimate; 11.2 GB available)". Throws fc::OutOfMemory before the
// factorisation starts when the estimate exceeds what is left (MemAvailable,
// the address-space limit).
std::string checkFactorisationMemory(Mat A, const std::string& what);

// After a failed solve through PC: when MUMPS ran out of memory (its
// factorisation error, INFOG(1) = -8, -9, -13 ...) or PETSc did (ierr is
// PETSC_ERR_MEM), throws fc::OutOfMemory with MUMPS's figures; otherwise returns.
void throwIfOutOfMemory(PC pc, PetscErrorCode ierr, const std::string& what);

// Owns a PETSc/SLEPc object: `&h` passes it to a Create call, `h` converts to
// the raw handle; the Destroy function runs once, on destruction or reassignment.
template <class T, PetscErrorCode (*Destroy)(T*)>
struct Owned {
  T h = nullptr;
  Owned() = default;
  explicit Owned(T x) : h(x) {}
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  Owned(Owned&& o) noexcept : h(o.h) { o.h = nullptr; }
  Owned& operator=(Owned&& o) noexcept {
    if (this != std::addressof(o)) {
      if (h) Destroy(&h);
      h = o.h;
      o.h = nullptr;
    }
    return *this;
  }
  ~Owned() {
    if (h) Destroy(&h);
  }
  T* operator&() { return &h; }
  operator T() const { return h; }
};
using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedKsp = Owned<KSP, KSPDestroy>;
using OwnedScatter = Owned<VecScatter, VecScatterDestroy>;

// Writes this rank's rows of the whole vector v into x.
void setLocal(Vec x, const Eigen::VectorXd& v);
// The whole of x on every rank.
Eigen::VectorXd gatherAll(Vec x);
// A v for a whole vector v on every rank; the whole product on every rank.
Eigen::VectorXd multiply(Mat A, const Eigen::VectorXd& v);
// A direct solver for the symmetric positive definite A: KSPPREONLY with a
// MUMPS Cholesky factorisation (command-line PETSc options still apply).
OwnedKsp choleskySolver(MPI_Comm comm, Mat A);

// MUMPS's own account of a factorisation's memory, in MiB (MUMPS reports
// millions of bytes: converted): estimated after the analysis (INFOG(17), all
// ranks), used by the factorisation (INFOG(22), all ranks; INFOG(21), the
// largest rank, which bounds one process's resident memory). Zeros when pc
// holds no MUMPS factor (not set up, or another solver chosen by options).
struct MumpsMemory {
  double estimated_mib = 0.0;
  double used_mib = 0.0;
  double used_max_rank_mib = 0.0;
  const char* library = "MUMPS";  // whose account (the serial backend also factorises with CHOLMOD)
};
MumpsMemory mumpsMemory(PC pc);
// The larger of two accounts, field by field (a stage with several factorisations).
MumpsMemory largerMumpsMemory(const MumpsMemory& a, const MumpsMemory& b);

}  // namespace fc::feprep
