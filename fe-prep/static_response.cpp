#include "fe-prep/static_response.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace fc::feprep {

Eigen::VectorXd reduceForce(const DofMap& map, const Eigen::VectorXd& f) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(map.reduced);
  for (std::size_t n = 0; n < map.T.size(); ++n) {
    const auto& ix = map.idx[n];
    if (ix.empty()) continue;
    const Eigen::VectorXd g = map.T[n].transpose() * f.segment<6>(6 * static_cast<long>(n));
    for (std::size_t j = 0; j < ix.size(); ++j) r(ix[j]) += g(static_cast<long>(j));
  }
  return r;
}

Eigen::MatrixXd solveStatic(Comm comm, SystemMatrix K, const DofMap& map, const Eigen::MatrixXd& forces) {
  Eigen::MatrixXd rhs(map.reduced, forces.cols());
  for (long j = 0; j < forces.cols(); ++j) rhs.col(j) = reduceForce(map, forces.col(j));
  const Eigen::MatrixXd x =
      solveReduced(comm, K, rhs, "the stiffness with the reference conditions is singular (rigid motions left free)");
  Eigen::MatrixXd out(forces.rows(), forces.cols());
  for (long j = 0; j < forces.cols(); ++j) out.col(j) = map.expand(x.col(j));
  return out;
}

Eigen::MatrixXd solveInertiaRelief(Comm comm, SystemMatrix K, SystemMatrix M, const DofMap& map,
                                   const Eigen::MatrixXd& rigid, const Eigen::MatrixXd& forces) {
  const long r = rigid.cols(), n = map.reduced;
  Eigen::MatrixXd MR(n, r);
  for (long i = 0; i < r; ++i) MR.col(i) = multiply(M, rigid.col(i));
  const Eigen::LDLT<Eigen::MatrixXd> G(rigid.transpose() * MR);
  // The support: r DOF whose rows of R are independent (the pivots of R^T's
  // column-pivoted QR, columns scaled to unit length so translations and
  // rotations weigh alike); holding them removes every rigid motion and
  // nothing more, so it is statically determinate.
  Eigen::MatrixXd Rn = rigid;
  for (long i = 0; i < r; ++i) Rn.col(i).normalize();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Rn.transpose());
  if (qr.rank() < r) throw std::logic_error("inertia relief: the rigid modes are not independent");
  std::vector<long> support;
  for (long i = 0; i < r; ++i) support.push_back(static_cast<long>(qr.colsPermutation().indices()(i)));
  Eigen::MatrixXd rhs(n, forces.cols());
  for (long j = 0; j < forces.cols(); ++j) {
    const Eigen::VectorXd f = reduceForce(map, forces.col(j));
    rhs.col(j) = f - MR * G.solve(rigid.transpose() * f);  // P f: balanced by the rigid-body inertia forces
    for (long i : support) rhs(i, j) = 0.0;
  }
  // The held DOF keep a diagonal of K's size (the factorisation's pivots stay alike).
  double kmax = 0.0;
  const Eigen::MatrixXd us = solveReduced(comm, K, rhs,
                                          "the stiffness on a statically determinate support is singular (the body "
                                          "has a mechanism beyond its rigid motions)",
                                          support, &kmax);
  Eigen::MatrixXd out(forces.rows(), forces.cols());
  for (long j = 0; j < forces.cols(); ++j) {
    const Eigen::VectorXd u = us.col(j) - rigid * G.solve(MR.transpose() * us.col(j));  // P^T u_s
    // The support's reactions vanish only if the load was equilibrated and K's
    // null space is the rigid modes': K u must be P f on every DOF.
    Eigen::VectorXd fe = reduceForce(map, forces.col(j));
    fe -= MR * G.solve(rigid.transpose() * fe);
    // (Rounding of the direct solve: relative to |K| |u|, not |f|.)
    const double res = (multiply(K, u) - fe).norm();
    if (!(res <= 1e-8 * (kmax * u.norm() + fe.norm())))
      throw std::runtime_error("inertia relief: the support carries a reaction (relative residual " + std::to_string(res / fe.norm()) +
                               "): the body has a mechanism beyond its rigid motions");
    out.col(j) = map.expand(u);
  }
  return out;
}

StaticTruncation staticTruncation(const Eigen::VectorXd& compliance, const Eigen::MatrixXd& shapes,
                                  const Eigen::VectorXd& eigenvalues, const Eigen::Vector2d& scale) {
  StaticTruncation t;
  t.compliance = compliance;
  t.participation = Eigen::MatrixXd::Zero(shapes.rows(), 6);
  t.error = Eigen::VectorXd::Zero(6);
  for (int k = 0; k < 6; ++k) {
    // Held directions (the point cannot move that way) have no deflection to miss.
    t.held[static_cast<std::size_t>(k)] = !(compliance(k) > 1e-9 * scale(k / 3));
    if (t.held[static_cast<std::size_t>(k)]) continue;
    for (long j = 0; j < shapes.rows(); ++j) t.participation(j, k) = shapes(j, k) * shapes(j, k) / (eigenvalues(j) * compliance(k));
    t.error(k) = 1.0 - t.participation.col(k).sum();
  }
  return t;
}

long modesForStaticError(const std::vector<StaticTruncation>& ts, double target, double* worst_out) {
  const long nm = ts.empty() ? 0 : ts.front().participation.rows();
  auto worst = [&](long n) {
    double w = 0.0;
    for (const auto& t : ts)
      for (int k = 0; k < 3; ++k)
        if (!t.held[static_cast<std::size_t>(k)]) w = std::max(w, 1.0 - t.participation.col(k).head(n).sum());
    return w;
  };
  long n = 1;
  while (n < nm && worst(n) > target) ++n;
  if (worst_out) *worst_out = worst(n);
  return n;
}

}  // namespace fc::feprep
