#pragma once
// fe-prep's linear algebra, serial backend (the program fe-prep): the names
// the driver uses (fe-prep/la/petsc/la_backend.h declares the same on PETSc)
// on Eigen sparse matrices in one process, with sequential MUMPS (LDL^T with
// pivoting, so the held patches' saddle point factorises as in the PETSc
// path) and ARPACK (shift-invert, mode 3). It loads neither PETSc, SLEPc nor
// gmsh and never starts MPI: its floor is what a small body costs
// (docs/fe-prep.md, "Two programs"). Everything is in the inline namespace
// `serial`, so that no symbol of it can be mistaken for the PETSc backend's.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cstddef>
#include <memory>
#include <string>

namespace fc::feprep {

struct BodySpec;

inline namespace serial {

// One process: no communicator to speak of.
struct Comm {};
inline int commRank(Comm) { return 0; }
inline void broadcast(Comm, long*, long) {}
inline void broadcast(Comm, int*, long) {}
inline void broadcast(Comm, double*, long) {}
inline void broadcast(Comm, char*, long) {}

const char* backendName();

// K and M of the reduced system, the upper triangle only (symmetric; MUMPS
// reads one triangle, products go through selfadjointView).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// A matrix as the driver passes it: a reference to the assembled one.
class SystemMatrix {
 public:
  SystemMatrix() = default;
  SystemMatrix(std::nullptr_t) {}
  SystemMatrix(SparseMatrix& a) : a_(&a) {}
  SparseMatrix& operator*() const { return *a_; }
  SparseMatrix* operator->() const { return a_; }
  explicit operator bool() const { return a_ != nullptr; }

 private:
  SparseMatrix* a_ = nullptr;
};

// A factorisation's own account of its memory, in MiB (as the PETSc
// backend's, named for MUMPS there: INFOG(17) estimated, INFOG(22) used,
// INFOG(21) the largest process's, one process here; CHOLMOD: its peak).
struct MumpsMemory {
  double estimated_mib = 0.0;
  double used_mib = 0.0;
  double used_max_rank_mib = 0.0;
  const char* library = "MUMPS";  // MUMPS or CHOLMOD
};
MumpsMemory largerMumpsMemory(const MumpsMemory& a, const MumpsMemory& b);

class Factorisation;  // fe-prep/la/serial/factorisation.h
// A factorisation kept past the solve that made it, and a borrowed reference.
class FactorHandle {
 public:
  FactorHandle() = default;
  explicit FactorHandle(std::shared_ptr<Factorisation> f) : f_(std::move(f)) {}
  operator const Factorisation*() const { return f_.get(); }

 private:
  std::shared_ptr<Factorisation> f_;
};
using FactorRef = const Factorisation*;

struct AssembledSystem {
  SparseMatrix K, M;
  Eigen::VectorXd lumped;  // n_nodes * 6
  long first_row = 0, local_rows = 0;
};

// A v for the symmetric A (upper triangle stored).
Eigen::VectorXd multiply(SystemMatrix A, const Eigen::VectorXd& v);

// MUMPS's estimate of the factorisation of A from its analysis alone, as one
// progress line; throws fc::OutOfMemory before any factorisation when the
// estimate exceeds what is left (as the PETSc backend's).
std::string checkFactorisationMemory(SystemMatrix A, const std::string& what);

// main()'s runtime. The constructor hands the whole run to fe-prep-mpi
// (execv, the same arguments) before any work when the run has more than one
// rank or `backend` is "petsc"; handOverIfNeeded does so for a body the serial
// path does not build (backend_choice.h). Neither returns then.
class LinearAlgebraRuntime {
 public:
  LinearAlgebraRuntime(int argc, char** argv, const std::string& backend);
  int failed() const { return failed_; }
  Comm world() const { return {}; }
  void handOverIfNeeded(const BodySpec& spec) const;

 private:
  char** argv_ = nullptr;
  std::string backend_;
  int failed_ = 0;
};

}  // namespace serial
}  // namespace fc::feprep
