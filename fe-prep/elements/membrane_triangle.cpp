#include "fe-prep/elements/membrane_triangle.h"

namespace fc::fe {

Eigen::Matrix<double, 3, 6> membraneStrain(const TriangleGeometry& g) {
  Eigen::Matrix<double, 3, 6> B = Eigen::Matrix<double, 3, 6>::Zero();
  for (int i = 0; i < 3; ++i) {
    B(0, 2 * i) = g.grad(i, 0);
    B(1, 2 * i + 1) = g.grad(i, 1);
    B(2, 2 * i) = g.grad(i, 1);
    B(2, 2 * i + 1) = g.grad(i, 0);
  }
  return B;
}

Eigen::Matrix<double, 9, 9> drillingPenalty(const TriangleGeometry& g, double c) {
  // e(L) = n(L) . q with q the 9 DOF; n = [-w_omega ..., L_i on theta_z,i].
  // int e^2 dA with linear L: int L_i L_j = A (1 + delta_ij) / 12, int L_i = A/3.
  Eigen::Matrix<double, 1, 9> omega = Eigen::Matrix<double, 1, 9>::Zero();
  for (int i = 0; i < 3; ++i) {
    omega(3 * i) = -0.5 * g.grad(i, 1);     // -u_,y / 2
    omega(3 * i + 1) = 0.5 * g.grad(i, 0);  //  v_,x / 2
  }
  Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero();
  const double A = g.area;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) K(3 * i + 2, 3 * j + 2) = A * (i == j ? 2.0 : 1.0) / 12.0;
    // cross terms -2 int L_i omega  ->  -A/3 omega (symmetrised below)
    K.row(3 * i + 2) -= (A / 3.0) * omega;
    K.col(3 * i + 2) -= (A / 3.0) * omega.transpose();
  }
  K += A * omega.transpose() * omega;
  return c * K;
}

}  // namespace fc::fe
