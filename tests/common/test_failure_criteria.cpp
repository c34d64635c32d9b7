// Hashin's criteria (common/failure_criteria.h) against values summed by hand
// from Hashin 1980's formulas, and the uniaxial strengths landing exactly on 1.
#include <gtest/gtest.h>

#include "common/failure_criteria.h"

namespace fc {
namespace {

// Strengths in MPa-like round numbers (Pa), S_T = Yc / 2 = 100 MPa.
const PlyStrength kStrength{2000e6, 1200e6, 50e6, 200e6, 80e6};

Eigen::Matrix<double, 6, 1> voigt(double s11, double s22, double s33, double s23, double s13, double s12) {
  Eigen::Matrix<double, 6, 1> v;
  v << s11, s22, s33, s23, s13, s12;
  return v;
}

TEST(Hashin, TensionStateByHand) {
  // s = [1000, 20, 10, 15, 5, 40] MPa:
  //   FT = (1000/2000)^2 + (40^2 + 5^2)/80^2 = 0.25 + 1625/6400 = 0.50390625
  //   MT = (30/50)^2 + (15^2 - 20*10)/100^2 + 1625/6400 = 0.36 + 0.0025 + 0.25390625 = 0.61640625
  const HashinIndices h = hashinIndices(kStrength, voigt(1000e6, 20e6, 10e6, 15e6, 5e6, 40e6));
  // Rounding of a few products of O(1) numbers.
  EXPECT_NEAR(h.fibre_tension, 0.50390625, 1e-15);
  EXPECT_EQ(h.fibre_compression, 0.0);
  EXPECT_NEAR(h.matrix_tension, 0.61640625, 1e-15);
  EXPECT_EQ(h.matrix_compression, 0.0);
  EXPECT_NEAR(h.max(), 0.61640625, 1e-15);
}

TEST(Hashin, CompressionStateByHand) {
  // s = [-600, -100, -20, 30, 0, 40] MPa, S_T = 100 MPa so (Yc/2S_T)^2 - 1 = 0:
  //   FC = (600/1200)^2 = 0.25
  //   MC = 0 + 120^2/(4 100^2) + (30^2 - 100*20)/100^2 + 40^2/80^2 = 0.36 - 0.11 + 0.25 = 0.5
  const HashinIndices h = hashinIndices(kStrength, voigt(-600e6, -100e6, -20e6, 30e6, 0, 40e6));
  EXPECT_EQ(h.fibre_tension, 0.0);
  EXPECT_NEAR(h.fibre_compression, 0.25, 1e-15);
  EXPECT_EQ(h.matrix_tension, 0.0);
  EXPECT_NEAR(h.matrix_compression, 0.5, 1e-15);
}

TEST(Hashin, UniaxialStrengthsFailAtOne) {
  // Each strength alone reaches its mode's index 1 (Hashin's calibration).
  const double tol = 1e-15;
  EXPECT_NEAR(hashinIndices(kStrength, Eigen::Vector3d(2000e6, 0, 0)).fibre_tension, 1.0, tol);
  EXPECT_NEAR(hashinIndices(kStrength, Eigen::Vector3d(-1200e6, 0, 0)).fibre_compression, 1.0, tol);
  EXPECT_NEAR(hashinIndices(kStrength, Eigen::Vector3d(0, 50e6, 0)).matrix_tension, 1.0, tol);
  EXPECT_NEAR(hashinIndices(kStrength, Eigen::Vector3d(0, -200e6, 0)).matrix_compression, 1.0, tol);
  // Pure in-plane shear: both the fibre-tension (s11 = 0 >= 0) and matrix-tension modes read (t/S12)^2.
  const HashinIndices s = hashinIndices(kStrength, Eigen::Vector3d(0, 0, 80e6));
  EXPECT_NEAR(s.fibre_tension, 1.0, tol);
  EXPECT_NEAR(s.matrix_tension, 1.0, tol);
  // Transverse shear s23 = S_T alone: matrix tension at 1 (s22 + s33 = 0).
  EXPECT_NEAR(hashinIndices(kStrength, voigt(0, 0, 0, 100e6, 0, 0)).matrix_tension, 1.0, tol);
}

TEST(Hashin, PlaneFormIsTheThreeDimensionalWithTheOutOfPlaneStressesZero) {
  const Eigen::Vector3d p(-300e6, 25e6, -35e6);
  const HashinIndices a = hashinIndices(kStrength, p), b = hashinIndices(kStrength, voigt(p(0), p(1), 0, 0, 0, p(2)));
  EXPECT_EQ(a.fibre_compression, b.fibre_compression);
  EXPECT_EQ(a.matrix_tension, b.matrix_tension);
  // (25/50)^2 + (35/80)^2 = 0.25 + 0.19140625
  EXPECT_NEAR(a.matrix_tension, 0.44140625, 1e-15);
  EXPECT_NEAR(a.fibre_compression, 0.0625, 1e-15);
}

}  // namespace
}  // namespace fc
