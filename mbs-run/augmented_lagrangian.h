#pragma once
// The augmented Lagrangian index-3-free formulation of Bayo, Garcia de Jalon &
// Serna (1988) and Bayo & Ledesma (1996, Nonlinear Dynamics 9:113-130):
//   (M + Phi_v^T a Phi_v) vdot_{k+1} = Q - Phi_v^T (lambda_k + a s),
//   lambda_{k+1} = lambda_k + a (Phi_v vdot_{k+1} + s),
//   s = c + 2 xi omega Phi_dot + omega^2 Phi          (stabilisation)
// starting from lambda_0 = 0. The leading matrix is positive definite whenever M
// is, whatever the rank of Phi_v, so redundant constraints and singular
// configurations never make the solve fail: the iteration converges to the
// least-squares-consistent accelerations, and lambda to one set of multipliers.
// After a step the state is projected mass-orthogonally onto the constraint
// manifold (positions) and its tangent (velocities) with the same matrix.
#include <Eigen/Sparse>

namespace fc::mbs {

using SparseMatrixd = Eigen::SparseMatrix<double>;

struct AlResult {
  Eigen::VectorXd vdot;
  Eigen::VectorXd lambda;
  int iterations = 0;
  double residual = 0.0;  // ||Phi_v vdot + s||_inf at the end
};

// Solves with a caller-owned factorisation object so the symbolic analysis can
// be reused while the sparsity pattern does not change.
class AlSolver {
 public:
  // Factorises M + alpha Phi_v^T Phi_v. `same_pattern` skips the symbolic step.
  void factorize(const SparseMatrixd& M, const SparseMatrixd& Phi_v, double alpha, bool same_pattern);
  // Factorises K = M + alpha Phi_v^T Phi_v assembled by the caller (block by
  // block is much cheaper than the general sparse product for small systems).
  void factorizeAssembled(const SparseMatrixd& K, double alpha, bool same_pattern);
  // The iteration above; stops when the constraint residual no longer improves
  // by a useful factor or is below tol.
  AlResult accelerations(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                         const Eigen::VectorXd& Q, const Eigen::VectorXd& s, double tol,
                         int max_iterations) const;
  // Mass-orthogonal velocity projection: min 1/2 (v - v0)^T M (v - v0)
  // subject to Phi_v v + Phi_t = 0, by the same multiplier iteration.
  Eigen::VectorXd projectVelocities(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                    const Eigen::VectorXd& v0, const Eigen::VectorXd& phit,
                                    double tol, int max_iterations) const;
  // One linearised position correction: dq minimising 1/2 (d + dq)^T M (d + dq)
  // with Phi + Phi_v dq = 0, d the correction accumulated so far.
  Eigen::VectorXd positionCorrection(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                     const Eigen::VectorXd& phi, const Eigen::VectorXd& accumulated,
                                     double tol, int max_iterations) const;
  double alpha() const { return alpha_; }
  bool ok() const { return ok_; }

 private:
  Eigen::SimplicialLDLT<SparseMatrixd> ldlt_;
  double alpha_ = 1.0;
  bool ok_ = false;
  bool analyzed_ = false;
};

}  // namespace fc::mbs
