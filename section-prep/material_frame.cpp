#include "section-prep/material_frame.h"

#include <cmath>

namespace fc::section {

Eigen::Matrix3d materialAxes(double theta1, double theta3) {
  const Eigen::Vector3d x1(1, 0, 0);
  const Eigen::Vector3d y2(0, std::cos(theta1), std::sin(theta1));
  const Eigen::Vector3d y3(0, -std::sin(theta1), std::cos(theta1));
  Eigen::Matrix3d R;
  R.col(0) = std::cos(theta3) * x1 + std::sin(theta3) * y2;
  R.col(1) = -std::sin(theta3) * x1 + std::cos(theta3) * y2;
  R.col(2) = y3;
  return R;
}

Matrix6d rotateVoigtStiffness(const Matrix6d& C, const Eigen::Matrix3d& R) {
  static const int pair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  Matrix6d T;
  for (int I = 0; I < 6; ++I) {
    const int i = pair[I][0], j = pair[I][1];
    for (int J = 0; J < 6; ++J) {
      const int k = pair[J][0], l = pair[J][1];
      T(I, J) = (k == l) ? R(i, k) * R(j, l) : R(i, k) * R(j, l) + R(i, l) * R(j, k);
    }
  }
  return T * C * T.transpose();
}

}  // namespace fc::section
