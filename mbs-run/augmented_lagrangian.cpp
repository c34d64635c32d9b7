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

void AlSolver::factorizeAssembled(const SparseMatrixd& K, double alpha, bool same_pattern) {
  alpha_ = alpha;
  if (!same_pattern || !analyzed_) {
    ldlt_.analyzePattern(K);
    analyzed_ = true;
  }
  ldlt_.factorize(K);
  ok_ = ldlt_.info() == Eigen::Success;
}

namespace {
// Multiplier iteration for  K x = b - Phi^T (mu + a g),  mu += a (Phi x + g),
// K = M + a Phi^T Phi, converging to M x = b - Phi^T mu with Phi x + g = 0 (in
// the least-squares sense if the equations are inconsistent). Written in
// correction form, x += K^-1 (b - M x - Phi^T (mu + a (Phi x + g))), so each
// pass also refines away the rounding of the solve: K is ill-conditioned by
// design (a large, light bodies' small inertias), and solving for x afresh
// would leave errors of eps cond(K) |x| in every acceleration.
Eigen::VectorXd multiplierIteration(const Eigen::SimplicialLDLT<SparseMatrixd>& ldlt, const SparseMatrixd& M,
                                    const SparseMatrixd& Phi, double a, const Eigen::VectorXd& b,
                                    const Eigen::VectorXd& g, double tol, int max_it, bool stop_on_stall,
                                    Eigen::VectorXd* mu_out, int* its, double* res) {
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(Phi.rows());
  Eigen::VectorXd x = ldlt.solve(b - a * (Phi.transpose() * g));
  Eigen::VectorXd e = Phi * x + g;
  double r = e.size() ? e.cwiseAbs().maxCoeff() : 0.0;
  int k = 0;
  double r_prev = std::numeric_limits<double>::infinity();
  while (k < max_it) {
    mu += a * e;
    const Eigen::VectorXd rhs = b - M * x - Phi.transpose() * (mu + a * e);
    const Eigen::VectorXd dx = ldlt.solve(rhs);
    x += dx;
    e = Phi * x + g;
    ++k;
    r = e.size() ? e.cwiseAbs().maxCoeff() : 0.0;
    const double d = dx.lpNorm<Eigen::Infinity>();
    const double xn = x.lpNorm<Eigen::Infinity>();
    if (r <= tol && d <= 1e-13 * xn) break;
    // Converged x with a residual that cannot vanish: inconsistent equations
    // at a singular configuration, where the least-squares accelerations are
    // the answer. Otherwise keep iterating up to max_it even when progress is
    // slow (near-singular): stopping at a variable, state-dependent point
    // would make f(y) rough at the tolerance level and stall the step control
    // (we measured 2500 rejected steps at the SAR toggle with such a rule).
    if (d <= 1e-13 * xn) break;
    // Projections stop when the residual stops improving fast: near a
    // singular configuration the nearly dependent rows are then enforced only
    // as a penalty, which lets a mechanism pass a toggle position instead of
    // having its velocity projected onto the tangent of whichever branch the
    // step happened to land nearest (that captured the SAR knee, losing all
    // its kinetic energy).
    if (stop_on_stall && r > 0.5 * r_prev) break;
    r_prev = r;
  }
  if (mu_out) *mu_out = mu + a * e;
  if (its) *its = k;
  if (res) *res = r;
  return x;
}
}  // namespace

AlResult AlSolver::accelerations(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                 const Eigen::VectorXd& Q, const Eigen::VectorXd& s, double tol,
                                 int max_iterations) const {
  AlResult r;
  r.vdot = multiplierIteration(ldlt_, M, Phi_v, alpha_, Q, s, tol, max_iterations, false, &r.lambda,
                               &r.iterations, &r.residual);
  return r;
}

Eigen::VectorXd AlSolver::projectVelocities(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                            const Eigen::VectorXd& v0, const Eigen::VectorXd& phit,
                                            double tol, int max_iterations) const {
  return multiplierIteration(ldlt_, M, Phi_v, alpha_, M * v0, phit, tol, max_iterations, true, nullptr,
                             nullptr, nullptr);
}

Eigen::VectorXd AlSolver::positionCorrection(const SparseMatrixd& M, const SparseMatrixd& Phi_v,
                                             const Eigen::VectorXd& phi,
                                             const Eigen::VectorXd& accumulated, double tol,
                                             int max_iterations) const {
  // Unknown dq; constraint Phi_v dq + phi = 0; objective (d + dq)^T M (d + dq).
  return multiplierIteration(ldlt_, M, Phi_v, alpha_, -(M * accumulated), phi, tol, max_iterations, true,
                             nullptr, nullptr, nullptr);
}

}  // namespace fc::mbs
