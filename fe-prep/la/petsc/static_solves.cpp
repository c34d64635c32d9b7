// The PETSc backend's direct solves (fe-prep-mpi): static responses and
// Craig-Bampton constraint modes on one MUMPS Cholesky factorisation through
// PETSc's KSP, one right-hand side at a time.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "fe-prep/craig_bampton.h"
#include "fe-prep/petsc_handles.h"
#include "fe-prep/static_response.h"

namespace fc::feprep {

Eigen::MatrixXd solveReduced(MPI_Comm comm, Mat K, const Eigen::MatrixXd& rhs, const char* singular,
                             const std::vector<long>& held, double* kmax_out) {
  OwnedMat Ks;
  if (!held.empty()) {
    check(MatDuplicate(K, MAT_COPY_VALUES, &Ks), "MatDuplicate");
    PetscInt lo = 0, hi = 0;
    check(MatGetOwnershipRange(Ks, &lo, &hi), "MatGetOwnershipRange");
    std::vector<PetscInt> local;
    for (long i : held)
      if (i >= lo && i < hi) local.push_back(static_cast<PetscInt>(i));
    OwnedVec diag;
    check(MatCreateVecs(K, &diag, nullptr), "MatCreateVecs");
    check(MatGetDiagonal(K, diag), "MatGetDiagonal");
    PetscReal kmax = 0.0;
    check(VecNorm(diag, NORM_INFINITY, &kmax), "VecNorm");
    if (kmax_out) *kmax_out = kmax;
    check(MatZeroRowsColumns(Ks, static_cast<PetscInt>(local.size()), local.data(), kmax, nullptr, nullptr),
          "MatZeroRowsColumns");
  }
  const Mat A = held.empty() ? K : Ks.h;
  OwnedKsp ksp = choleskySolver(comm, A);
  OwnedVec b, x;
  check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
  Eigen::MatrixXd out(rhs.rows(), rhs.cols());
  for (long j = 0; j < rhs.cols(); ++j) {
    setLocal(b, rhs.col(j));
    check(KSPSolve(ksp, b, x), "KSPSolve");
    KSPConvergedReason why;
    check(KSPGetConvergedReason(ksp, &why), "KSPGetConvergedReason");
    if (why < 0) {
      PC pc;
      check(KSPGetPC(ksp, &pc), "KSPGetPC");
      throwIfOutOfMemory(pc, 0, "the stiffness");
      throw std::runtime_error(singular);
    }
    out.col(j) = gatherAll(x);
  }
  return out;
}

CraigBamptonBasis constraintModes(MPI_Comm comm, const ConstraintModeInput& in) {
  const long nb = in.n_boundary, nk = in.normal ? in.normal->cols() : 0, N = 6 * in.n_nodes;
  CraigBamptonBasis out;
  out.n_boundary = nb;
  out.B.resize(N, nb + nk);
  // Constraint modes: one factorisation of the fixed-interface K (the
  // eigen-solve's when given), nb solves;
  // each right-hand side and solution is one vector at a time.
  {
    OwnedKsp ksp;
    if (!in.factored) ksp = choleskySolver(comm, in.K_fixed);
    OwnedVec b, x;
    check(MatCreateVecs(in.K_fixed, &x, &b), "MatCreateVecs");
    for (long j = 0; j < nb; ++j) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(N);
      for (const auto& [node, rows] : in.K_lifts) f.segment<6>(6 * node) = rows.col(j);
      setLocal(b, -reduceForce(*in.fixed, f));
      if (in.factored) {
        // A factor the eigen-solve completed: K_fixed is not singular.
        check(MatSolve(in.factored, b, x), "MatSolve");
      } else {
        check(KSPSolve(ksp, b, x), "KSPSolve");
        KSPConvergedReason why;
        check(KSPGetConvergedReason(ksp, &why), "KSPGetConvergedReason");
        PC pc;
        check(KSPGetPC(ksp, &pc), "KSPGetPC");
        if (why < 0) {
          // MUMPS out of memory fails the factorisation the same way: said as such.
          throwIfOutOfMemory(pc, 0, "the fixed-interface stiffness");
          throw std::runtime_error("craig_bampton: the fixed-interface stiffness is singular (the reference leaves "
                                   "rigid motions free: clamp the boundary interfaces, or pin at least three)");
        }
        if (j == 0) out.factorisation = mumpsMemory(pc);
      }
      out.B.col(j) = in.fixed->expand(gatherAll(x));
      for (const auto& [node, rows] : in.lifts) out.B.col(j).segment<6>(6 * node) += rows.col(j);
    }
  }
  for (long j = 0; j < nk; ++j) out.B.col(nb + j) = in.fixed->expand(in.normal->col(j));
  return out;
}

}  // namespace fc::feprep
