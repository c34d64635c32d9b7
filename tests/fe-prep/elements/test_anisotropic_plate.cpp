// Plates with bending-twist coupling (D16, D26 != 0: angle plies) against a
// reference nobody here wrote the theory of: the Ritz solution of classical
// lamination theory for anisotropic plates (Reddy, Mechanics of Laminated
// Composite Plates and Shells, 2nd ed., ch. 5; Leissa 1969), which keeps D16
// and D26 (closed_forms.h). These tests located where fe-prep's shell stood
// against CalculiX's solids on the stiffened panel's [0/45/-45/90]s skin
// (docs/validation.md): DKT and DST converge to the right limit at O(h^2),
// with an error constant that grows with D16/D11 (a 45-degree ply on 16 x 16
// cells is 1-4 % stiff, a cross-ply 0.1-0.2 %), and the frame the element
// works in does not move the result.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "closed_forms.h"
#include "laminates.h"
#include "plate_model.h"

namespace fc::fe {
namespace {

constexpr double kSide = 0.5;

// IM6 plies (those of the stiffened panel), 2 mm in all: a / h = 250.
LaminateStiffness im6(const std::vector<double>& angles) {
  std::vector<test::OrthoPly> plies;
  for (double a : angles)
    plies.push_back({177e9, 10.8e9, 7.6e9, 7.6e9, 3.6e9, 0.27, 1600, 0.002 / angles.size(), a});
  return test::orthotropicLaminate(plies);
}

// Square plate clamped on all edges: fe-prep's DKT and DST on 16 x 16 and 32 x 32
// cells, Richardson-extrapolated for an O(h^2) error, against the Ritz solution
// (Legendre degree 14 per direction; 12 and 16 agree to 1e-5).
// Measured (single 45-degree ply), DKT: 16 x 16 +1.0, +2.7, +2.1, +4.5 %,
// 32 x 32 +0.26, +0.66, +0.55, +1.1 % (the error falls 4x per halving),
// extrapolated 0.002, -0.02, +0.03, -0.03 %. DKT is Kirchhoff's plate, the
// Ritz solution's theory, so its limit must be the Ritz one: 0.1 % leaves room
// for the O(h^3) left after extrapolation. DST's limit is the shear-flexible
// plate's, below Kirchhoff by the transverse shear (E1 / G13 = 23; measured
// -0.1..-0.2 %): 0.4 %.
TEST(AnisotropicPlate, ClampedAnglePliesConvergeToTheRitzSolutionAtSecondOrder) {
  const std::vector<std::vector<double>> layups = {
      {45}, {45, -45, -45, 45}, {30, -60, -60, 30}, {0, 45, -45, 90, 90, -45, 45, 0}};
  for (const auto& angles : layups) {
    const LaminateStiffness lam = im6(angles);
    ASSERT_GT(std::fabs(lam.D(0, 2)), 0.05 * lam.D(0, 0));  // bending-twist coupling present
    const std::vector<double> ref = test::ritzClampedPlateOmegas(lam.D, lam.mass_per_area, kSide, kSide, 14, 4);
    for (ShellKind kind : {ShellKind::DKT, ShellKind::DST}) {
      const auto coarse = test::rectangleMesh(kSide, kSide, 16, 16), fine = test::rectangleMesh(kSide, kSide, 32, 32);
      const std::vector<double> w16 =
          test::lowestOmegasSparse(coarse, lam, kind, test::plateBendingDofs(coarse, 'A'), 4);
      const std::vector<double> w32 =
          test::lowestOmegasSparse(fine, lam, kind, test::plateBendingDofs(fine, 'A'), 4);
      for (std::size_t i = 0; i < 4; ++i) {
        const double e16 = w16[i] / ref[i] - 1, e32 = w32[i] / ref[i] - 1, extrapolated = (4 * e32 - e16) / 3;
        std::printf("[   info   ] [%g...] %s mode %zu: 16 %+.3f %%, 32 %+.3f %%, extrapolated %+.3f %%\n", angles[0],
                    kind == ShellKind::DKT ? "DKT" : "DST", i + 1, 100 * e16, 100 * e32, 100 * extrapolated);
        if (kind == ShellKind::DKT) {
          EXPECT_GT(e32, 0.0) << "DKT converges from above";
          EXPECT_NEAR(e16 / e32, 4.0, 1.0) << "second order";
          EXPECT_NEAR(extrapolated, 0.0, 1e-3) << "mode " << i + 1;
        } else {
          EXPECT_NEAR(extrapolated, 0.0, 4e-3) << "mode " << i + 1;
        }
      }
    }
  }
}

// The element works in the frame of the projected fibre axis (shellFrame). A
// mesh rotated by 30 degrees about the normal with the fibre axis rotated with
// it is the same plate in the same discretisation, so the frequencies must not
// move (rounding only); rotating the mesh alone turns the fibres against the
// plate's edges and must move them.
TEST(AnisotropicPlate, MeshRotatedWithItsFibresGivesTheSameFrequencies) {
  const LaminateStiffness lam = im6({0, 45, -45, 90, 90, -45, 45, 0});
  const test::PlateMesh mesh = test::rectangleMesh(kSide, kSide, 8, 8);
  test::PlateMesh turned = mesh;
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  for (auto& p : turned.nodes) p = Eigen::Vector3d(c * p(0) - s * p(1), s * p(0) + c * p(1), p(2));
  const std::vector<int> keep = test::plateBendingDofs(mesh, 'A');
  const Eigen::VectorXd base = test::eigenvalues(test::assembleShell(mesh, lam, ShellKind::DST, false), keep);
  const Eigen::VectorXd with_fibres = test::eigenvalues(
      test::assembleShell(turned, lam, ShellKind::DST, false, 1e-4, Eigen::Vector3d(c, s, 0)), keep);
  const Eigen::VectorXd alone = test::eigenvalues(test::assembleShell(turned, lam, ShellKind::DST, false), keep);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(with_fibres(i) / base(i), 1.0, 1e-9) << "mode " << i + 1;
  }
  EXPECT_GT(std::fabs(alone(0) / base(0) - 1), 1e-2);
}

}  // namespace
}  // namespace fc::fe
