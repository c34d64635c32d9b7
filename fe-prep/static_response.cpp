#include "fe-prep/static_response.h"

#include "fe-prep/petsc_handles.h"

#include <algorithm>
#include <stdexcept>
#include <string>

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

Eigen::MatrixXd solveStatic(MPI_Comm comm, Mat K, const DofMap& map, const Eigen::MatrixXd& forces) {
  OwnedKsp ksp = choleskySolver(comm, K);
  OwnedVec b, x;
  check(MatCreateVecs(K, &x, &b), "MatCreateVecs");
  Eigen::MatrixXd out(forces.rows(), forces.cols());
  for (long j = 0; j < forces.cols(); ++j) {
    setLocal(b, reduceForce(map, forces.col(j)));
    check(KSPSolve(ksp, b, x), "KSPSolve");
    KSPConvergedReason why;
    check(KSPGetConvergedReason(ksp, &why), "KSPGetConvergedReason");
    if (why < 0) throw std::runtime_error("the stiffness with the reference conditions is singular (rigid motions left free)");
    out.col(j) = map.expand(gatherAll(x));
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
