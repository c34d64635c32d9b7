#include "mbs-run/augmented_lagrangian.h"

namespace fc::mbs {

void AlSolver::factorize(const SparseMatrixd& M, const SparseMatrixd& Phi_v, double alpha,
                         bool same_pattern) {
  alpha_ = alpha;
  SparseMatrixd K = M;
  if (Phi_v.rows() > 0) K += alpha * SparseMatrixd(Phi_v.transpose() * Phi_v);
  if (!same_pattern || !analyzed_) {
    ldlt_.analyzePattern(K);
    analyzed_ = true;
  }
  ldlt_.factorize(K);
  ok_ = ldlt_.info() == Eigen::Success;
}

namespace {
// Generic multiplier iteration for  K x = b - Phi^T (mu + a g),  mu += a (Phi x + g):
// converges to x with Phi x + g = 0 (in the least-squares sense if inconsistent).
template <class Solver>
Eigen::VectorXd multiplierIteration(const Solver& ldlt, const SparseMatrixd& Phi, double a,
                                    const Eigen::VectorXd& b, const Eigen::VectorXd& g, double tol,
                                    int max_it, Eigen::VectorXd* mu_out, int* its, double* res) {
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(Phi.rows());
  Eigen::VectorXd x = ldlt.solve(b - a * (Phi.transpose() * g));
  double r_prev = std::numeric_limits<double>::infinity();
  int k = 0;
  double r = 0.0;
  Eigen::VectorXd e;
  for (;;) {
    e = Phi * x + g;
    r = e.size() ? e.cwiseAbs().maxCoeff() : 0.0;
    mu += a * e;
    // Stop when satisfied, or when the residual stalls (inconsistent equations
    // at a singular configuration: the least-squares part cannot vanish).
    if (r <= tol || k >= max_it || r > 0.5 * r_prev) break;
    r_prev = r;
    x = ldlt.solve(b - Phi.transpose() * (mu + a * g));
    ++k;
  }
  if (mu_out) *mu_out = mu;
  if (its) *its = k;
  if (res) *res = r;
  return x;
}
}  // namespace

AlResult AlSolver::accelerations(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                 const Eigen::VectorXd& Q, const Eigen::VectorXd& s, double tol,
                                 int max_iterations) const {
  AlResult r;
  r.vdot = multiplierIteration(ldlt_, Phi_v, alpha_, Q, s, tol, max_iterations, &r.lambda,
                               &r.iterations, &r.residual);
  return r;
}

Eigen::VectorXd AlSolver::projectVelocities(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                            const Eigen::VectorXd& v0, const Eigen::VectorXd& phit,
                                            double tol, int max_iterations) const {
  return multiplierIteration(ldlt_, Phi_v, alpha_, M * v0, phit, tol, max_iterations, nullptr,
                             nullptr, nullptr);
}

Eigen::VectorXd AlSolver::positionCorrection(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                             const Eigen::VectorXd& phi,
                                             const Eigen::VectorXd& accumulated, double tol,
                                             int max_iterations) const {
  // Unknown dq; constraint Phi_v dq + phi = 0; objective (d + dq)^T M (d + dq).
  return multiplierIteration(ldlt_, Phi_v, alpha_, -(M * accumulated), phi, tol, max_iterations,
                             nullptr, nullptr, nullptr);
}

}  // namespace fc::mbs
