// Beam frequencies through the whole tool path against Euler-Bernoulli and
// Timoshenko closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "fe-prep/body_spec.h"
#include "feprep_test_support.h"

namespace fc::feprep::test {
namespace {

std::string beamYaml(double L, double d, long elements, const std::string& reference, int modes,
                     const std::string& mass = "consistent") {
  std::ostringstream os;
  os << "materials:\n  alu: {type: isotropic, E: 70.0e9, nu: 0.3, rho: 2700}\n"
     << "body:\n  name: rod\n  beam: {length: " << L << ", elements: " << elements
     << ", section: {shape: solid_circle, diameter: " << d << ", material: alu}}\n"
     << "  reference: " << reference << "\n  modes: " << modes << "\n  mass: " << mass << "\n";
  return os.str();
}

// Euler-Bernoulli: omega = (beta L)^2 / L^2 sqrt(EI / rho A) (Blevins, Formulas for
// Natural Frequency and Mode Shape, table 8-1).
double eulerBernoulliHz(double betaL, double L, double d) {
  const double E = 70e9, rho = 2700, A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64;
  return betaL * betaL / (L * L) * std::sqrt(E * I / (rho * A)) / (2 * M_PI);
}

TEST(BeamModes, SlenderCantileverMatchesEulerBernoulli) {
  // L/d = 100: shear and rotary inertia change the first modes by < 0.05 %; 40
  // elements with consistent mass add < 0.01 %. Tolerance 0.1 %.
  // Round rod: bending about y and z are degenerate, so modes come in pairs.
  const BuildResult r = runYaml(beamYaml(1.0, 0.01, 40, "{clamp: [end_min]}", 6));
  EXPECT_EQ(r.rigid_removed, 0);
  const double betaL[3] = {1.87510407, 4.69409113, 7.85475744};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(r.body.frequencies_hz(2 * k + j) / eulerBernoulliHz(betaL[k], 1.0, 0.01), 1.0, 1e-3)
          << "mode " << 2 * k + j + 1;
}

TEST(BeamModes, SlenderFreeFreeMatchesEulerBernoulli) {
  const BuildResult r = runYaml(beamYaml(1.0, 0.01, 40, "free", 4));
  EXPECT_EQ(r.rigid_removed, 6);
  EXPECT_GT(r.rigid_share_removed_min, 1 - 1e-8);
  const double betaL[2] = {4.73004074, 7.85320462};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(r.body.frequencies_hz(2 * k + j) / eulerBernoulliHz(betaL[k], 1.0, 0.01), 1.0, 1e-3);
}

TEST(BeamModes, ThickPinnedBeamMatchesTimoshenko) {
  // L/d = 5 pinned at both ends: Timoshenko's equations with w = W sin(a x),
  // psi = P cos(a x), a = n pi / L, give exactly
  //   [[kGA a^2, -kGA a], [-kGA a, EI a^2 + kGA]] (W, P) = omega^2 diag(rho A, rho I) (W, P).
  // Pins leave the rotation about the axis free: one rigid mode removed.
  // Measured: 0.002 % (n = 1), 0.02 % (n = 2) with 40 elements; tolerance 0.1 %.
  const double L = 0.05 * 5, d = 0.05, E = 70e9, nu = 0.3, rho = 2700;
  const BuildResult r = runYaml(beamYaml(L, d, 40, "{pin: [end_min, end_max]}", 4));
  EXPECT_EQ(r.rigid_removed, 1);
  const SectionMatrices s = solidCircleSection(d, E, nu, rho);
  const double kGA = s.K(1, 1), EI = s.K(4, 4), rA = s.M(0, 0), rI = s.M(4, 4);
  for (int n = 1; n <= 2; ++n) {
    const double a = n * M_PI / L;
    Eigen::Matrix2d K, Mi;
    K << kGA * a * a, -kGA * a, -kGA * a, EI * a * a + kGA;
    Mi << 1 / std::sqrt(rA), 0, 0, 1 / std::sqrt(rI);
    const double w = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(Mi * K * Mi).eigenvalues()(0));
    const double f = w / (2 * M_PI);
    const double f_eb = n * n * M_PI * M_PI / (L * L) * std::sqrt(EI / rA) / (2 * M_PI);
    ASSERT_LT(f / f_eb, 0.97 - 0.05 * (n - 1));  // shear matters here
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(r.body.frequencies_hz(2 * (n - 1) + j) / f, 1.0, 1e-3) << "n = " << n;
  }
}

}  // namespace
}  // namespace fc::feprep::test
