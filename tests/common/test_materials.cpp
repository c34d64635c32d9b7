// Materials: admissibility and the stiffness transformations.
#include <gtest/gtest.h>

#include <cmath>

#include "common/materials.h"

namespace {
const double kPi = 3.14159265358979323846;
fc::Material im6() {
  return fc::makeOrthotropic("im6", 177e9, 10.8e9, 10.8e9, 7.6e9, 7.6e9, 8.504e9, 0.27, 0.27, 0.5,
                             1600);
}
}  // namespace

TEST(Materials, IsotropicLameConstants) {
  // Closed form: C11 = lambda + 2 mu, C12 = lambda, C44 = mu.
  const double E = 159e9, nu = 0.38;
  auto m = fc::makeIsotropic("cfrp_iso", E, nu, 1610);
  const double mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(m.C(0, 0), lambda + 2 * mu, 1e-9 * E);
  EXPECT_NEAR(m.C(0, 1), lambda, 1e-9 * E);
  EXPECT_NEAR(m.C(3, 3), mu, 1e-9 * E);
  EXPECT_NEAR(m.C(5, 5), mu, 1e-9 * E);
}

TEST(Materials, OrthotropicComplianceRoundTrip) {
  auto m = im6();
  fc::Matrix6d S = m.compliance();
  EXPECT_NEAR(1 / S(0, 0), 177e9, 1e-3);
  EXPECT_NEAR(-S(0, 1) / S(0, 0), 0.27, 1e-12);
  EXPECT_NEAR(1 / S(3, 3), 8.504e9, 1e-3);
  EXPECT_NEAR(1 / S(5, 5), 7.6e9, 1e-3);
}

TEST(Materials, RejectsInadmissible) {
  EXPECT_THROW(fc::makeIsotropic("x", 1e9, 0.5, 1), std::invalid_argument);
  EXPECT_THROW(fc::makeIsotropic("x", 1e9, -1.2, 1), std::invalid_argument);
  EXPECT_THROW(fc::makeIsotropic("x", -1e9, 0.3, 1), std::invalid_argument);
  EXPECT_THROW(fc::makeIsotropic("x", 1e9, 0.3, 0), std::invalid_argument);
  // |nu12| must stay below sqrt(E1/E2) = 2 here.
  EXPECT_THROW(fc::makeOrthotropic("x", 4e9, 1e9, 1e9, 1e9, 1e9, 1e9, 2.1, 0.2, 0.2, 1),
               std::invalid_argument);
  // Each pair admissible, but the determinant condition fails.
  EXPECT_THROW(fc::makeOrthotropic("x", 1e9, 1e9, 1e9, 1e9, 1e9, 1e9, 0.9, 0.9, 0.9, 1),
               std::invalid_argument);
  fc::Matrix6d C = fc::Matrix6d::Identity();
  C(0, 0) = -1;
  EXPECT_THROW(fc::makeAnisotropic("x", C, 1), std::invalid_argument);
}

TEST(Materials, PlyAt90DegreesSwapsAxes) {
  auto m = im6();
  fc::Matrix6d C90 = fc::plyStiffnessInLaminateAxes(m.C, kPi / 2);
  EXPECT_NEAR(C90(0, 0), m.C(1, 1), 1e-6 * m.C(0, 0));
  EXPECT_NEAR(C90(1, 1), m.C(0, 0), 1e-6 * m.C(0, 0));
  EXPECT_NEAR(C90(3, 3), m.C(4, 4), 1e-6 * m.C(0, 0));  // yz <- xz
  EXPECT_NEAR(C90(4, 4), m.C(3, 3), 1e-6 * m.C(0, 0));
  EXPECT_NEAR(C90(0, 5), 0.0, 1e-6 * m.C(0, 0));
}

TEST(Materials, OffAxisModulusMatchesTransformationFormula) {
  // Jones, Mechanics of Composite Materials, eq. (2.98):
  // 1/Ex = c^4/E1 + (1/G12 - 2 nu12/E1) s^2 c^2 + s^4/E2.
  auto m = im6();
  for (double deg : {15.0, 30.0, 45.0, 60.0}) {
    const double a = deg * kPi / 180, c = std::cos(a), s = std::sin(a);
    fc::Matrix6d S = fc::plyStiffnessInLaminateAxes(m.C, a).inverse();
    const double inv_ex = std::pow(c, 4) / 177e9 + (1 / 7.6e9 - 2 * 0.27 / 177e9) * s * s * c * c +
                          std::pow(s, 4) / 10.8e9;
    EXPECT_NEAR(1 / S(0, 0), 1 / inv_ex, 1e-9 / inv_ex) << deg;
  }
}

TEST(Materials, RotationPreservesStrainEnergy) {
  // C' = T C T^T must give the same energy for the same physical strain.
  auto m = im6();
  Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  fc::Matrix6d Cp = fc::rotateStiffness(m.C, R);
  Eigen::Matrix3d eps;
  eps << 1e-3, 2e-4, -3e-4, 2e-4, -5e-4, 1e-4, -3e-4, 1e-4, 7e-4;
  auto voigt = [](const Eigen::Matrix3d& e) {
    Eigen::Matrix<double, 6, 1> v;
    v << e(0, 0), e(1, 1), e(2, 2), 2 * e(1, 2), 2 * e(0, 2), 2 * e(0, 1);
    return v;
  };
  const Eigen::Matrix<double, 6, 1> v = voigt(eps), vp = voigt(R * eps * R.transpose());
  EXPECT_NEAR(v.dot(m.C * v), vp.dot(Cp * vp), 1e-9 * v.dot(m.C * v));
}

TEST(Materials, PhysicalRangesAreEnforced) {
  // E = 1e-300 used to give an all-NaN section stiffness; GPa typed as Pa is the
  // common mistake the lower bound catches.
  EXPECT_THROW(fc::makeIsotropic("a", 1e-300, 0.3, 1600), std::invalid_argument);
  EXPECT_THROW(fc::makeIsotropic("a", 70, 0.3, 2700), std::invalid_argument);
  EXPECT_THROW(fc::makeIsotropic("a", 1e300, 0.3, 2700), std::invalid_argument);
  EXPECT_THROW(fc::makeIsotropic("a", 70e9, 0.3, 1e-30), std::invalid_argument);
  EXPECT_THROW(fc::makeIsotropic("a", 70e9, std::nan(""), 2700), std::invalid_argument);
  EXPECT_THROW(fc::makeOrthotropic("b", 177e9, 10.8e9, 10.8e9, 7.6e9, 7.6e9, 1e-200, 0.27, 0.27,
                                   0.5, 1600),
               std::invalid_argument);
  EXPECT_THROW(fc::makeAnisotropic("c", fc::Matrix6d::Identity() * 1e-100, 1600), std::invalid_argument);
  fc::Matrix6d C = im6().C;
  C(0, 0) = std::nan("");
  EXPECT_THROW(fc::makeAnisotropic("c", C, 1600), std::invalid_argument);
  try {
    fc::makeIsotropic("alu", 70, 0.3, 2700);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("physical range"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(fc::makeIsotropic("foam", 1e5, 0.3, 30));
  EXPECT_NO_THROW(fc::makeAnisotropic("im6a", im6().C, 1600));
}
