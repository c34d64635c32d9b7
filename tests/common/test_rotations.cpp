// Euler-parameter identities (Nikravesh 1988, section 6.3).
#include <gtest/gtest.h>

#include "common/rotations.h"

namespace {
fc::Vector4d randomUnit(int seed) {
  std::srand(seed);
  fc::Vector4d p = fc::Vector4d::Random();
  return p.normalized();
}
}  // namespace

TEST(Rotations, MatrixIsOrthonormalAndProperForAnyUnitP) {
  for (int s = 1; s < 20; ++s) {
    auto p = randomUnit(s);
    Eigen::Matrix3d A = fc::rotationMatrix(p);
    EXPECT_LT((A * A.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-14);
    EXPECT_NEAR(A.determinant(), 1.0, 1e-14);
  }
}

TEST(Rotations, GLIdentities) {
  for (int s = 1; s < 20; ++s) {
    auto p = randomUnit(s);
    auto G = fc::Gmatrix(p);
    auto L = fc::Lmatrix(p);
    Eigen::Matrix3d A = fc::rotationMatrix(p);
    // A = G L^T, G p = L p = 0, G G^T = L L^T = I.
    EXPECT_LT((A - G * L.transpose()).norm(), 1e-14);
    EXPECT_LT((G * p).norm(), 1e-15);
    EXPECT_LT((L * p).norm(), 1e-15);
    EXPECT_LT((G * G.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-14);
    EXPECT_LT((L * L.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-14);
    // G^T G = L^T L = I4 - p p^T.
    Eigen::Matrix4d P = Eigen::Matrix4d::Identity() - p * p.transpose();
    EXPECT_LT((G.transpose() * G - P).norm(), 1e-14);
    EXPECT_LT((L.transpose() * L - P).norm(), 1e-14);
  }
}

TEST(Rotations, AngularVelocityFromParameterRate) {
  // omega~ = Adot A^T (global) and omega'~ = A^T Adot (body); check against
  // finite differences of A along pdot = 1/2 L^T omega'.
  auto p = randomUnit(7);
  Eigen::Vector3d w_body(0.3, -1.2, 0.8);
  fc::Vector4d pd = fc::eulerParameterRate(p, w_body);
  EXPECT_NEAR(p.dot(pd), 0.0, 1e-15);  // the constraint p^T p = 1 is kept
  const double h = 1e-6;
  Eigen::Matrix3d Adot =
      (fc::rotationMatrix(p + h * pd) - fc::rotationMatrix(p - h * pd)) / (2 * h);
  Eigen::Matrix3d A = fc::rotationMatrix(p);
  EXPECT_LT((A.transpose() * Adot - fc::skew(w_body)).norm(), 1e-8);
  EXPECT_LT((2 * fc::Gmatrix(p) * pd - A * w_body).norm(), 1e-14);
}

TEST(Rotations, MatrixRoundTrip) {
  for (int s = 1; s < 40; ++s) {
    auto p = randomUnit(s);
    if (p(0) < 0) p = -p;
    EXPECT_LT((fc::eulerParametersFromMatrix(fc::rotationMatrix(p)) - p).norm(), 1e-13);
  }
  // Rotation by pi (e0 = 0) is handled (Shepperd's branch).
  Eigen::Matrix3d A = fc::rotationMatrix(fc::Vector4d(0, 0, 1, 0));
  EXPECT_LT((fc::rotationMatrix(fc::eulerParametersFromMatrix(A)) - A).norm(), 1e-14);
}

TEST(Rotations, AxisAngleAndExpMap) {
  Eigen::Vector3d axis(1, 2, 2);
  const double angle = 0.9;
  auto p = fc::eulerParametersFromAxisAngle(axis, angle);
  Eigen::Matrix3d ref = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  EXPECT_LT((fc::rotationMatrix(p) - ref).norm(), 1e-14);
  EXPECT_LT((fc::expRotation(angle * axis.normalized()) - ref).norm(), 1e-14);
  EXPECT_LT((fc::rotationVector(ref) - angle * axis.normalized()).norm(), 1e-13);
}

TEST(Rotations, ProductComposesRotations) {
  auto a = randomUnit(3), b = randomUnit(4);
  EXPECT_LT((fc::rotationMatrix(fc::quatProduct(a, b)) - fc::rotationMatrix(a) * fc::rotationMatrix(b)).norm(),
            1e-14);
  EXPECT_LT((fc::rotationMatrix(fc::quatConjugate(a)) - fc::rotationMatrix(a).transpose()).norm(),
            1e-14);
}
