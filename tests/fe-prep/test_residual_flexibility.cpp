// Residual-flexibility (static) correction of free-interface bases (issue 16,
// modes: {count: N, static_correction: ...}; fe-prep/residual_flexibility.h)
// against references nobody here wrote:
//  - a steel cantilever's tip compliance, Timoshenko's L^3/3EI + L/(kappa G A),
//    held by 2 modes + the correction to rounding (6 modes alone miss 0.3 %);
//  - Rayleigh-Ritz: the augmented basis's eigenvalues bound the full model's
//    from above, and the kept modes' (exact eigenvectors) are unchanged;
//  - CalculiX 2.20's compliance of a raised distributing point on a panel
//    (tests/data/calculix/raised_pins_panel), reached with 2 modes + the
//    correction where 2 modes alone are far off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "feprep_test_support.h"

namespace fc::feprep::test {
namespace {

// The compliance the file's modes carry at an interface: sum_j s_jk^2 / lambda_j.
Eigen::VectorXd modalCompliance(const FlexBody& b, const std::string& name) {
  const Eigen::MatrixXd& s = b.interface(name).shapes;
  return (s.array().square().colwise() / b.eigenvalues.array()).colwise().sum().transpose();
}

TEST(ResidualFlexibility, CantileverTipComplianceIsExactAndFrequenciesAreUpperBounds) {
  const BuildResult plain = runYaml(steelCantileverYaml("2"));
  const BuildResult corrected = runYaml(steelCantileverYaml("{count: 2, static_correction: true}"));
  const BuildResult full = runYaml(steelCantileverYaml("24"));
  // The root is clamped (its unit loads, in held directions, are left out);
  // the tip's six unit loads add six vectors.
  EXPECT_EQ(corrected.body.reduction, "free + static correction: 2 modes + 6 unit loads - 0 in the span = 8 shapes");
  ASSERT_EQ(corrected.body.modeCount(), 8);
  const double E = 210e9, nu = 0.3, d = 0.02, L = 2.0, A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64;
  const double G = E / (2 * (1 + nu)), J = 2 * I, kappa = 6 * (1 + nu) / (7 + 6 * nu);
  const double bend = L * L * L / (3 * E * I) + L / (kappa * G * A);
  // Timoshenko (force), L/EA (axial), L/GJ (torsion), L/EI (end moment).
  const Eigen::Matrix<double, 6, 1> exact = (Eigen::Matrix<double, 6, 1>() << L / (E * A), bend, bend, L / (G * J), L / (E * I), L / (E * I)).finished();
  const Eigen::VectorXd c_plain = modalCompliance(plain.body, "tip"), c_corr = modalCompliance(corrected.body, "tip");
  const Eigen::VectorXd err = corrected.body.interface("tip").static_error;
  for (int k = 0; k < 6; ++k) {
    std::printf("[   info   ] tip direction %d: exact %.6e, 2 modes %.6e (%+.2e), 2 modes + correction %.6e (%+.2e), "
                "static_error %.1e\n", k, exact(k), c_plain(k), c_plain(k) / exact(k) - 1, c_corr(k), c_corr(k) / exact(k) - 1, err(k));
    // The beam elements are nodally exact for end loads (1e-6 as in
    // test_static_error.cpp); the correction leaves only rounding of the
    // dense 8 x 8 problem (1e-9 of the static deflection).
    EXPECT_NEAR(c_corr(k) / exact(k), 1.0, 1e-6) << k;
    EXPECT_LT(std::abs(err(k)), 1e-9) << k;
  }
  // Without the correction the two bending modes hold 97 % of the tip force's
  // deflection and none of the axial and torsional ones.
  EXPECT_GT(1 - c_plain(1) / exact(1), 0.02);
  EXPECT_LT(c_plain(0), 1e-3 * exact(0));

  // Rayleigh-Ritz: the kept modes are exact eigenvectors, so they stay
  // (solver tolerance 1e-10 on the residual; 1e-8 relative); every further
  // eigenvalue of the augmented basis lies at or above the full model's of
  // the same rank (Poincare's separation theorem).
  const Eigen::VectorXd& la = corrected.body.eigenvalues;
  const Eigen::VectorXd& lf = full.body.eigenvalues;
  for (int j = 0; j < 2; ++j) EXPECT_NEAR(la(j) / plain.body.eigenvalues(j), 1.0, 1e-8) << j;
  for (int j = 0; j < 8; ++j) {
    std::printf("[   info   ] eigenvalue %d: augmented %.6e, full model %.6e (%+.2e)\n", j, la(j), lf(j), la(j) / lf(j) - 1);
    EXPECT_GE(la(j), lf(j) * (1 - 1e-8)) << j;
  }
  // The shapes stay an ordinary modal basis: unit modal mass with the file's
  // nodal masses (the invariants mbs-run builds from them).
  const FlexBody& b = corrected.body;
  Eigen::VectorXd m(6 * b.nodeCount());
  for (long k = 0; k < b.nodeCount(); ++k) {
    m.segment<3>(6 * k).setConstant(b.nodal_mass(k, 0));
    m.segment<3>(6 * k + 3) = b.nodal_mass.block<1, 3>(k, 1).transpose();
  }
  EXPECT_LT((b.shapes.transpose() * m.asDiagonal() * b.shapes - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-9);
  // Section resultants exist for every shape (stress recovery).
  EXPECT_EQ(b.stress.beam_resultants.cols(), 8);
}

TEST(ResidualFlexibility, KeyErrors) {
  auto fails = [](const std::string& yaml, const std::string& what) {
    try {
      runYaml(yaml);
      ADD_FAILURE() << "no error for " << what;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fails(steelCantileverYaml("{count: 2, static_correction: [tpi]}"), "did you mean 'tip'");
  fails(steelCantileverYaml("{static_correction: true}"), "either count: N or static_error: E");
  std::string free = steelCantileverYaml("{count: 2, static_correction: true}");
  free.replace(free.find("reference: {clamp: [root]}"), 26, "reference: free");
  fails(free, "static_correction needs a reference that holds the body");
}

// CalculiX's compliance of the raised point T (a distributing patch) on the
// panel hung at two raised distributing hinge points (the panel of
// test_calculix_couplings.cpp, the same tolerances and their reasons).
TEST(ResidualFlexibility, RaisedPinsPanelReachesCalculixComplianceWithTwoModes) {
  const auto all = raisedPinsPanelCalculix();
  ASSERT_EQ(all.count("compliance_distributing 160"), 1u);
  const std::vector<double>& ccx = all.at("compliance_distributing 160");
  ASSERT_EQ(ccx.size(), 6u);
  const BuildResult r = runYaml(raisedPinsPanelYaml("distributing", "{count: 2, static_correction: [T]}"));
  EXPECT_EQ(r.body.reduction, "free + static correction: 2 modes + 6 unit loads - 0 in the span = 8 shapes");
  const Eigen::VectorXd c = modalCompliance(r.body, "T");
  // The two lowest shapes are the two modes unchanged (exact eigenvectors,
  // Rayleigh-Ritz), so their participation is what the modes alone carry.
  const char* dir[6] = {"ux/Fx", "uy/Fy", "uz/Fz", "rx/Mx", "ry/My", "rz/Mz"};
  for (int k = 0; k < 6; ++k) {
    const double two = r.body.interface("T").static_participation.topRows(2).col(k).sum();
    std::printf("[   info   ] T %s: 2 modes + correction %.6e, CalculiX %.6e (%+.3f %%); the 2 modes alone carry %.1f %%\n",
                dir[k], c(k), ccx[static_cast<std::size_t>(k)], 100 * (c(k) / ccx[static_cast<std::size_t>(k)] - 1), 100 * two);
    EXPECT_NEAR(c(k) / ccx[static_cast<std::size_t>(k)], 1.0, k == 5 ? 0.02 : 0.01) << dir[k];
    EXPECT_LT(two, 0.97) << dir[k];  // without the correction every direction is off by more than the tolerance
  }
}

}  // namespace
}  // namespace fc::feprep::test
