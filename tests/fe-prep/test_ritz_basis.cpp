// ritzEigen (fe-prep/ritz_basis.h) on a spring chain with a massless node and
// a dependent basis vector, against the closed form of the condensed chain:
// ground -k1- m1 -k2- (no mass) -k3- m3. Condensing the massless node leaves
// m1 and m3 joined by k2 and k3 in series (k23 = k2 k3 / (k2 + k3)), whose
// two eigenvalues solve det([k1 + k23, -k23; -k23, k23] - lambda diag(m1, m3)) = 0,
// and the static compliance at m3 stays 1/k1 + 1/k2 + 1/k3.
#include <gtest/gtest.h>

#include <cmath>

#include "fe-prep/ritz_basis.h"

namespace fc::feprep::test {
namespace {

TEST(RitzBasis, CondensesMasslessDirectionsAndDropsDependentOnes) {
  const double k1 = 3.0e4, k2 = 5.0e4, k3 = 2.0e4, m1 = 2.0, m3 = 0.5;
  Eigen::Matrix3d K, M = Eigen::Matrix3d::Zero();
  K << k1 + k2, -k2, 0, -k2, k2 + k3, -k3, 0, -k3, k3;
  M(0, 0) = m1;
  M(2, 2) = m3;
  // Basis: the three unit vectors (scaled differently) and a fourth that
  // repeats the first plus the third.
  Eigen::Matrix<double, 3, 4> B;
  B << 2.0, 0, 0, 2.0,
       0, 0.1, 0, 0,
       0, 0, 5.0, 5.0;
  const RitzSolution s = ritzEigen(B.transpose() * K * B, B.transpose() * M * B);
  EXPECT_EQ(s.massless, 1);
  EXPECT_EQ(s.dependent, 1);
  ASSERT_EQ(s.eigenvalues.size(), 2);
  const double k23 = k2 * k3 / (k2 + k3);
  // lambda^2 m1 m3 - lambda ((k1 + k23) m3 + k23 m1) + k1 k23 = 0
  const double b = (k1 + k23) * m3 + k23 * m1, disc = std::sqrt(b * b - 4 * m1 * m3 * k1 * k23);
  const double l1 = (b - disc) / (2 * m1 * m3), l2 = (b + disc) / (2 * m1 * m3);
  // Rounding of 4 x 4 dense solves: 1e-12 relative.
  EXPECT_NEAR(s.eigenvalues(0), l1, 1e-12 * l2);
  EXPECT_NEAR(s.eigenvalues(1), l2, 1e-12 * l2);
  const Eigen::MatrixXd Kr = B.transpose() * K * B, Mr = B.transpose() * M * B;
  EXPECT_LT((s.X.transpose() * Mr * s.X - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((s.X.transpose() * Kr * s.X - Eigen::Matrix2d(s.eigenvalues.asDiagonal())).cwiseAbs().maxCoeff(), 1e-12 * l2);
  // Static compliance at m3 from the kept vectors: sum_j (B x_j)_3^2 / lambda_j.
  const Eigen::MatrixXd shapes = B * s.X;
  const double compliance = (shapes.row(2).array().square() / s.eigenvalues.transpose().array()).sum();
  EXPECT_NEAR(compliance, 1 / k1 + 1 / k2 + 1 / k3, 1e-12 * compliance);
}

}  // namespace
}  // namespace fc::feprep::test
