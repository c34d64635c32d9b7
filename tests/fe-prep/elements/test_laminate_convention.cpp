// The elements take fc::LaminateStiffness from common/laminate.cpp; the tests
// above build it from textbook formulas in laminates.cpp. Both must agree for an
// unsymmetric angle-ply, so that the conventions the elements assume (ply angle
// positive about the normal, plies from the bottom, As in [xz, yz] order, I1
// sign) are those of the library that feeds them in fe-prep.
#include <gtest/gtest.h>

#include <cmath>

#include "common/laminate.h"
#include "laminates.h"

namespace fc::fe {
namespace {

TEST(LaminateConvention, CommonLaminateMatchesTextbookFormulas) {
  const double E1 = 177e9, E2 = 10.8e9, G12 = 7.6e9, G23 = 3.4e9, nu12 = 0.27, rho = 1600;
  const double nu23 = E2 / (2 * G23) - 1;  // transversely isotropic
  MaterialLibrary lib;
  lib["ply"] = makeOrthotropic("ply", E1, E2, E2, G12, G12, G23, nu12, nu12, nu23, rho);
  Laminate lam;
  lam.name = "t";
  std::vector<test::OrthoPly> ref_plies;
  const double t[3] = {0.0004, 0.0002, 0.0003}, ang[3] = {30.0, -60.0, 90.0};
  for (int k = 0; k < 3; ++k) {
    lam.plies.push_back({"ply", t[k], ang[k]});
    ref_plies.push_back({E1, E2, G12, G12, G23, nu12, rho, t[k], ang[k]});
  }
  // The explicit factor 5/6 on the summed ply shear (the textbook rule of
  // laminates.cpp) checks the [xz, yz] order and the rotation of the shear.
  const LaminateStiffness a = laminateStiffness(lam, lib, 5.0 / 6.0);
  const LaminateStiffness b = test::orthotropicLaminate(ref_plies);
  // The default, from the stacking, scales the same summed matrix by sqrt(k_a k_b).
  const TransverseShear st = transverseShearFromStacking(lam, lib);
  Eigen::Matrix2d scaled = b.As * (6.0 / 5.0);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) scaled(i, j) *= std::sqrt(st.factor(i) * st.factor(j));
  EXPECT_TRUE((laminateStiffness(lam, lib).As - scaled).cwiseAbs().maxCoeff() <= 1e-10 * scaled.cwiseAbs().maxCoeff());
  // Same formulas in double precision: agreement to ~1e-12 relative.
  auto close = [](const auto& x, const auto& y) {
    return (x - y).cwiseAbs().maxCoeff() <= 1e-10 * y.cwiseAbs().maxCoeff();
  };
  EXPECT_TRUE(close(a.A, b.A)) << a.A << "\n\n" << b.A;
  EXPECT_TRUE(close(a.B, b.B)) << a.B << "\n\n" << b.B;
  EXPECT_TRUE(close(a.D, b.D)) << a.D << "\n\n" << b.D;
  EXPECT_TRUE(close(a.As, b.As)) << a.As << "\n\n" << b.As;
  EXPECT_NEAR(a.thickness, b.thickness, 1e-15);
  EXPECT_NEAR(a.mass_per_area, b.mass_per_area, 1e-12 * b.mass_per_area);
  EXPECT_NEAR(a.first_moment, b.first_moment, 1e-12 * b.mass_per_area * b.thickness);
  EXPECT_NEAR(a.rotary_per_area, b.rotary_per_area, 1e-12 * b.rotary_per_area);
}

}  // namespace
}  // namespace fc::fe
