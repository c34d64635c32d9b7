#include "fe-prep/mass_lumping.h"

#include <algorithm>

namespace fc::feprep {

MomentLumping momentConsistentMasses(const Eigen::MatrixXd& X, const Eigen::VectorXd& m0, double mass,
                                     const Eigen::Vector3d& first, const Eigen::Matrix3d& second) {
  const long n = X.rows();
  // Coordinates scaled by the body size so that the rows are of one magnitude.
  const double L = std::max((X.colwise().maxCoeff() - X.colwise().minCoeff()).norm(), 1e-300);
  const Eigen::MatrixXd Y = X / L;
  Eigen::MatrixXd C(10, n);
  for (long k = 0; k < n; ++k) {
    const double x = Y(k, 0), y = Y(k, 1), z = Y(k, 2);
    C.col(k) << 1, x, y, z, x * x, y * y, z * z, x * y, x * z, y * z;
  }
  const Eigen::Vector3d f = first / L;
  const Eigen::Matrix3d E = second / (L * L);
  Eigen::VectorXd b(10);
  b << mass, f.x(), f.y(), f.z(), E(0, 0), E(1, 1), E(2, 2), E(0, 1), E(0, 2), E(1, 2);

  const Eigen::MatrixXd G = C * m0.asDiagonal() * C.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(G);
  const Eigen::VectorXd ev = es.eigenvalues();
  const double tol = 1e-12 * ev.cwiseAbs().maxCoeff();
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(10);
  for (int i = 0; i < 10; ++i)
    if (ev(i) > tol) inv(i) = 1.0 / ev(i);
  const Eigen::VectorXd lambda = es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose() * (b - C * m0);

  MomentLumping out;
  out.masses = m0 + m0.asDiagonal() * (C.transpose() * lambda);
  out.min_ratio = (out.masses.array() / m0.array()).minCoeff();
  out.residual = (C * out.masses - b).norm() / b.norm();
  // Dependent rows whose targets disagree (a body whose exact moments no node
  // set on its plane or line can reproduce) leave a misfit: keep row sums then.
  out.applied = out.min_ratio >= 0.1 && out.residual < 1e-9;
  if (!out.applied) out.masses = m0;
  return out;
}

}  // namespace fc::feprep
