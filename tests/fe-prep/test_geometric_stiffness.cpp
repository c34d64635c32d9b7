// Geometric stiffness of fe-prep: the beam element's geometric
// stiffness against Euler's buckling load, the inertial load cases' axial forces
// against statics, and the modal data of a cantilever spinning about its root
// against an independent rotating-beam eigen-analysis and published tables.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "../mbs-run/rotating_beam_reference.h"
#include "common/flexbody.h"
#include "fe-prep/elements/beam_element.h"
#include "fe-prep/elements/beam_geometric_stiffness.h"
#include "fe-prep/geometric_stiffness.h"
#include "fe-prep/body_spec.h"
#include "feprep_test_support.h"

namespace fc::feprep::test {
namespace {

// Section of a steel rod, closed forms (sections.h).
const double kE = 210e9, kNu = 0.3, kRho = 7850, kD = 0.02;

TEST(GeometricStiffness, CantileverBucklesAtEulersLoad) {
  // Cantilever column of n elements along x under compression P: det(K - P K_G1) = 0
  // at P_cr = pi^2 EI / (4 L^2) (Euler; Timoshenko & Gere, Theory of Elastic
  // Stability, sec. 2.1). Shear lowers it by P_cr/(kGA) (Engesser) ~ 1e-5 here.
  const SectionMatrices s = solidCircleSection(kD, kE, kNu, kRho);
  const double L = 2.0, EI = kE * M_PI * std::pow(kD, 4) / 64;
  const int n = 20;
  const int nd = 6 * (n + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd), G = Eigen::MatrixXd::Zero(nd, nd);
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector3d a(L * e / n, 0, 0), b(L * (e + 1) / n, 0, 0);
    K.block<12, 12>(6 * e, 6 * e) += fe::timoshenkoBeam(a, b, Eigen::Vector3d::UnitY(), s.K, s.M).K;
    G.block<12, 12>(6 * e, 6 * e) += fe::beamGeometricStiffness(a, b, Eigen::Vector3d::UnitY(), s.K, -1.0);
  }
  // Clamp node 0; buckling: K x = P (-G) x, smallest P.
  const Eigen::MatrixXd Kr = K.bottomRightCorner(nd - 6, nd - 6), Gr = -G.bottomRightCorner(nd - 6, nd - 6);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Gr + 1e-12 * Eigen::MatrixXd::Identity(nd - 6, nd - 6) * Gr.norm(), Kr);
  // Largest 1/P of Gr x = (1/P) K x.
  const double Pcr = 1.0 / es.eigenvalues().maxCoeff();
  const double euler = M_PI * M_PI * EI / (4 * L * L);
  std::printf("[   info   ] cantilever buckling load %.6e N, Euler %.6e N\n", Pcr, euler);
  // Consistent geometric stiffness: O(h^4) from above (Hermite cubics), 20
  // elements ~1e-7; shear (Engesser) ~1e-5 below; the regularisation 1e-12.
  EXPECT_NEAR(Pcr / euler, 1.0, 1e-4);
  // Both bending planes buckle at the same load (the rod is round): the second
  // largest 1/P is the other plane's (the signs of the th2 plane are right).
  const Eigen::VectorXd ev = es.eigenvalues();
  EXPECT_NEAR(ev(ev.size() - 2) / ev(ev.size() - 1), 1.0, 1e-9);
}

TEST(GeometricStiffness, InertialCasesAreRigidBodyAccelerations) {
  // omega x (omega x s) + alpha x s + a0 rebuilt from the unit cases for a random state.
  const Eigen::Vector3d s(0.3, -1.2, 0.7), w(0.4, -2.0, 1.3), al(0.2, 0.5, -0.9), a0(1.0, -2.0, 3.0);
  Eigen::Matrix<double, kInertialCases, 1> p;
  p << a0, w.x() * w.x(), w.y() * w.y(), w.z() * w.z(), w.x() * w.y(), w.y() * w.z(), w.z() * w.x(), al;
  const Eigen::Vector3d exact = a0 + al.cross(s) + w.cross(w.cross(s));
  EXPECT_LT((inertialCaseAccelerations(s) * p - exact).norm(), 1e-14 * exact.norm());
}

// The shared bodies (tests/data/fe-prep, also read by tests/mbs-run/test_geometric_stiffening.cpp).
std::string spinningRod(int elements, int modes) {
  return dataBodyYaml("spinning_rod.yaml", {{"elements", std::to_string(elements)}, {"modes", std::to_string(modes)}});
}

// A narrow plate strip of DST shells, clamped along its root edge: a beam of
// EI = E b t^3 / 12 (nu = 0, so no anticlastic plate stiffening), rho A = rho b t.
std::string spinningStrip(double size, int modes) {
  return dataBodyYaml("spinning_strip.yaml", {{"size", std::to_string(size)}, {"modes", std::to_string(modes)}});
}

TEST(GeometricStiffness, SpinningCantileverFlapFrequenciesMatchRotatingBeamTheory) {
  const BuildResult r = runYaml(spinningRod(40, 6));
  const FlexBody& b = r.body;
  ASSERT_EQ(static_cast<int>(b.geometric_stiffness.size()), kInertialCases);
  const double L = 2.0, A = M_PI * kD * kD / 4, rhoA = kRho * A, EI = kE * M_PI * std::pow(kD, 4) / 64;
  const double w0 = 1.8751040687 * 1.8751040687 * std::sqrt(EI / (rhoA * std::pow(L, 4)));
  for (const auto& k : b.geometric_stiffness) EXPECT_LT((k - k.transpose()).norm(), 1e-12 * (1 + k.norm()));
  // Spin Omega about the z axis through the root (x = -L/2): the frame origin (the
  // rod's centre) accelerates by -Omega^2 L/2 along x, so p = [a_x = -Omega^2 L/2,
  // w_z w_z = Omega^2]. The flapwise (z) modal stiffness is Lambda + K_G (no
  // centrifugal softening out of the plane of rotation); the round rod's y modes
  // get the same K_G, so the eigenvalues come in equal pairs.
  for (double ratio : {1.0, 2.0}) {
    const double Om = ratio * w0;
    Eigen::MatrixXd Kt = b.eigenvalues.asDiagonal();
    Kt += Om * Om * (b.geometric_stiffness[5] - 0.5 * L * b.geometric_stiffness[0]);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Kt);
    const Eigen::VectorXd f = es.eigenvalues().cwiseSqrt();
    const Eigen::VectorXd ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, Om, false, 80, 2);
    std::printf("[   info   ] Omega = %.0f omega_0: flap 1 %.5f (reference %.5f), flap 2 %.5f (reference %.5f) rad/s\n",
                ratio, f(0), ref(0), f(2), ref(1));
    // 40 elements with lumped masses: frequencies O(h^2) low (measured 4e-4 at
    // Omega = 0 for mode 1) plus shear/rotary inertia (r/L = 0.005: ~1e-4) and 6 modes'
    // truncation of the stiffened shape (~1e-4): 2e-3 for mode 1, 5e-3 for mode 2
    // (its h^2 error is 6 times larger). The issue asks for 1 %.
    EXPECT_NEAR(f(0) / ref(0), 1.0, 2e-3);
    EXPECT_NEAR(f(1) / ref(0), 1.0, 2e-3);
    EXPECT_NEAR(f(2) / ref(1), 1.0, 5e-3);
  }
}

TEST(GeometricStiffness, RotatingBeamReferenceMatchesPublishedTables) {
  // The reference of these tests, checked three ways.
  // (1) Its own convergence: 60 and 120 Hermite elements agree at every speed
  //     (O(h^4) for the frequencies), so it is the converged rotating beam.
  // (2) At rest, the cantilever's closed form: omega = (beta_n L)^2 with
  //     cos(beta L) cosh(beta L) = -1, beta_1 L = 1.875104069, beta_2 L = 4.694091133.
  // (3) The flapwise values, in omega / sqrt(EI / (rho A L^4)) at the
  //     nondimensional speed Omega sqrt(rho A L^4 / EI) = 0, 1, 2, 3, 4:
  //     3.5160, 3.6816, 4.1373, 4.7973, 5.5850 (mode 1) and 22.0345, 22.1810,
  //     22.6149, 23.3203, 24.2734 (mode 2), the values tabulated for the
  //     uniform cantilever without hub radius by Wright, Smith, Thresher & Wang
  //     (J. Appl. Mech. 49 (1982) 197-202) and Hodges & Rutkowski (AIAA J. 19
  //     (1981) 1459-1466), as quoted from memory by the session that wrote this
  //     test. The tables themselves could not be found in the reference
  //     material searched  (public pages, code and documentation
  //     corpora, and an exact search for the values): only the speed-0 column
  //     was found in print, 3.51602 / 22.0345 / 61.6972 (Int. J. Mech. Mater.
  //     Eng. 10 (2015), doi 10.1186/s40712-015-0040-0, table 1, uniform beam).
  //     So (1) and (2) are the primary checks; (3) stays as a consistency check
  //     of the reference against the widely reproduced values (5 digits: 3e-5).
  for (int k = 0; k < 5; ++k) {
    const Eigen::VectorXd a = fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, k, false, 60, 2);
    const Eigen::VectorXd b = fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, k, false, 120, 2);
    if (k == 4) std::printf("[   info   ] reference 60 vs 120 elements at speed 4: %+.2e, %+.2e\n", a(0) / b(0) - 1, a(1) / b(1) - 1);
    // Measured 2e-8 at speed 4: the discretisation error (O(h^4)) is below the
    // dense eigen-solver's rounding (condition ~1e10 at 120 elements: ~1e-7); 2e-7.
    EXPECT_NEAR(a(0) / b(0), 1.0, 2e-7) << "speed " << k;
    EXPECT_NEAR(a(1) / b(1), 1.0, 2e-7) << "speed " << k;
  }
  {
    // Measured -1.2e-9 and +2.6e-8 at 60 elements (O(h^4) plus the dense
    // eigen-solver's rounding, ~1e-8 at condition ~1e9): 2e-8 and 1e-7.
    const Eigen::VectorXd f = fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, 0.0, false, 60, 2);
    std::printf("[   info   ] reference at rest vs the closed form: %+.2e, %+.2e\n",
                f(0) / std::pow(1.875104068711961, 2) - 1, f(1) / std::pow(4.694091132974175, 2) - 1);
    EXPECT_NEAR(f(0) / std::pow(1.875104068711961, 2), 1.0, 2e-8);
    EXPECT_NEAR(f(1) / std::pow(4.694091132974175, 2), 1.0, 1e-7);
  }
  const double m1[5] = {3.5160, 3.6816, 4.1373, 4.7973, 5.5850};
  const double m2[5] = {22.0345, 22.1810, 22.6149, 23.3203, 24.2734};
  for (int k = 0; k < 5; ++k) {
    const Eigen::VectorXd f = fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, k, false, 60, 2);
    EXPECT_NEAR(f(0), m1[k], 3e-4) << "speed " << k;
    EXPECT_NEAR(f(1), m2[k], 2e-3) << "speed " << k;
    // Lead-lag: the same operator minus Omega^2 M, so omega_lag^2 = omega_flap^2 - Omega^2
    // exactly; the dense generalized eigen-solver's rounding on K (condition ~1e9
    // with 60 Hermite elements) is ~1e-8 relative.
    const Eigen::VectorXd g = fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, k, true, 60, 2);
    EXPECT_NEAR(g(0) * g(0), f(0) * f(0) - k * k, 1e-7 * f(0) * f(0));
  }
  // Southwell's slope: omega^2 = omega_0^2 + K Omega^2 as Omega -> 0, K = 1.193
  // (flap) and 0.193 (lag) for the first mode.
  const double w0 = fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, 0.0, false, 60, 1)(0);
  // eps = 0.1: the slope's own change (K at speed 1 is 1.192) is ~1e-5 there, the
  // eigenvalues' rounding (1e-8 of 12.4) over eps^2 ~1e-5 too.
  const double eps = 0.1;
  const double kf = (std::pow(fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, eps, false, 60, 1)(0), 2) - w0 * w0) / (eps * eps);
  const double kl = (std::pow(fc::test::rotatingBeamFrequencies(1.0, 1.0, 1.0, eps, true, 60, 1)(0), 2) - w0 * w0) / (eps * eps);
  std::printf("[   info   ] Southwell coefficients flap %.4f, lag %.4f\n", kf, kl);
  // Quoted to 3 decimals.
  EXPECT_NEAR(kf, 1.193, 5e-4);
  EXPECT_NEAR(kl, 0.193, 5e-4);
}

TEST(GeometricStiffness, TipForceStiffensLikeATensionedBeam) {
  // The rod clamped at its root with an axial force P at its tip interface: the
  // modal stiffness Lambda + P K_{force_x} against the tensioned-beam
  // eigen-analysis (T(x) = P) of rotating_beam_reference.h, in tension and in
  // compression below Euler's load (P_cr = pi^2 EI / (4 L^2) = 2.47 EI / L^2).
  const BuildResult r = runYaml(spinningRod(40, 12));
  const FlexBody& b = r.body;
  const FlexInterface& tip = b.interface("tip");
  ASSERT_EQ(tip.geometric_stiffness.size(), 6u);
  EXPECT_TRUE(b.interface("root").geometric_stiffness.empty()) << "the clamped interface carries no load case";
  const double L = 2.0, A = M_PI * kD * kD / 4, rhoA = kRho * A, EI = kE * M_PI * std::pow(kD, 4) / 64;
  // A transverse tip force or a moment leaves the rod without axial force: no
  // geometric stiffness (to rounding of the static solve).
  const double scale = (EI / (L * L)) * tip.geometric_stiffness[0].norm();
  for (int c = 1; c < 6; ++c) EXPECT_LT((EI / (L * L)) * tip.geometric_stiffness[c].norm(), 1e-9 * scale) << "case " << c;
  for (double P : {10.0 * EI / (L * L), -1.5 * EI / (L * L)}) {
    Eigen::MatrixXd Kt = b.eigenvalues.asDiagonal();
    Kt += P * tip.geometric_stiffness[0];
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Kt);
    const Eigen::VectorXd f = es.eigenvalues().cwiseSqrt();
    const Eigen::VectorXd ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 2, 0.0, P);
    const Eigen::VectorXd ref0 = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 2);
    std::printf("[   info   ] tip force %+.0f N: bending 1 %.5f (reference %.5f, unloaded %.5f), bending 2 %.5f "
                "(reference %.5f) rad/s\n", P, f(0), ref(0), ref0(0), f(2), ref(1));
    // The error budget of the spinning rod above (40 lumped-mass elements: O(h^2)
    // 4e-4 low for mode 1, ~6 times that for mode 2; shear ~1e-4): 2e-3 mode 1,
    // 5e-3 mode 2 (measured 3e-4 and 1.4e-3). 12 modes: the tensioned shape
    // needs more of the unloaded ones than the spinning rod's (6 modes left
    // 1.8e-3 at +10 EI/L^2). The force moves mode 1 by +104 % and -36 %, so the
    // check is far from the unloaded frequency.
    EXPECT_NEAR(f(0) / ref(0), 1.0, 2e-3);
    EXPECT_NEAR(f(1) / ref(0), 1.0, 2e-3);
    EXPECT_NEAR(f(2) / ref(1), 1.0, 5e-3);
  }
}

TEST(GeometricStiffness, SpinningPlateStripFlapsAsTheRotatingBeam) {
  // The shells' membrane-stress geometric stiffness (shell_geometric_stiffness.h):
  // the strip (spinning_strip.yaml: 2 m x 0.1 m x 0.01 m, aluminium with nu = 0)
  // spun at Omega about z (its normal) through the root; flapwise is w.
  const double L = 2.0, b = 0.1, t = 0.01, EI = 70e9 * b * t * t * t / 12, rhoA = 2700 * b * t;
  const double w0 = 1.8751040687 * 1.8751040687 * std::sqrt(EI / (rhoA * std::pow(L, 4)));
  double err[2] = {0, 0};
  int k = 0;
  for (double h : {0.1, 0.05}) {
    const BuildResult r = runYaml(spinningStrip(h, 8));
    const FlexBody& B = r.body;
    ASSERT_EQ(static_cast<int>(B.geometric_stiffness.size()), kInertialCases);
    const Eigen::MatrixXd Psi = B.interface("tip").shapes.leftCols(3).transpose();
    for (double ratio : {0.0, 1.0, 2.0}) {
      const double Om = ratio * w0;
      Eigen::MatrixXd Kt = B.eigenvalues.asDiagonal();
      Kt += Om * Om * (B.geometric_stiffness[5] - 0.5 * L * B.geometric_stiffness[0]);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Kt);
      // The lowest mode that moves the tip along z (the in-plane ones are ~b/t stiffer).
      double f = 0;
      for (int j = 0; j < Kt.rows() && f == 0; ++j) {
        const Eigen::Vector3d u = Psi * es.eigenvectors().col(j);
        if (std::abs(u.z()) > 10 * u.head<2>().norm()) f = std::sqrt(es.eigenvalues()(j));
      }
      const double ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, Om, false, 80, 1)(0);
      std::printf("[   info   ] strip h = %.2f m at %.0f omega_0: flap %.5f rad/s, rotating beam %.5f (%+.2e)\n", h,
                  ratio, f, ref, f / ref - 1);
      if (ratio == 1.0) err[k] = f / ref - 1;
      // The issue's 1 %; expected: DST with lumped masses O(h^2) (the strip at
      // rest: 2.8e-4 low at h = 0.05, 9.4e-4 at 0.1), the CST's piecewise-constant tension and
      // 8 modes' truncation: 2e-3 (measured 5e-4 and 1.7e-4 at omega_0).
      EXPECT_NEAR(f / ref, 1.0, 2e-3) << "h " << h << " ratio " << ratio;
    }
    ++k;
  }
  // Converging under refinement (the tension and the slopes both improve).
  EXPECT_LT(std::abs(err[1]), 0.6 * std::abs(err[0]));
}

TEST(GeometricStiffness, TipForceStiffensThePlateStrip) {
  // The shells' interface cases: the strip of spinning_strip.yaml (h = 0.05 m,
  // 12 modes) with an axial force P = +10 EI/L^2 at its tip interface (one node
  // on the centre line): Lambda + P K_force_x against the tensioned-beam
  // eigen-analysis with T = P, as the rod's TipForceStiffensLikeATensionedBeam.
  const BuildResult r = runYaml(spinningStrip(0.05, 12));
  const FlexBody& B = r.body;
  const FlexInterface& tip = B.interface("tip");
  ASSERT_EQ(tip.geometric_stiffness.size(), 6u);
  const double L = 2.0, b = 0.1, t = 0.01, EI = 70e9 * b * t * t * t / 12, rhoA = 2700 * b * t;
  const double P = 10.0 * EI / (L * L);
  Eigen::MatrixXd Kt = B.eigenvalues.asDiagonal();
  Kt += P * tip.geometric_stiffness[0];
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Kt);
  const Eigen::MatrixXd Psi = tip.shapes.leftCols(3).transpose();
  double f = 0;
  for (int j = 0; j < Kt.rows() && f == 0; ++j) {
    const Eigen::Vector3d u = Psi * es.eigenvectors().col(j);
    if (std::abs(u.z()) > 10 * u.head<2>().norm()) f = std::sqrt(es.eigenvalues()(j));
  }
  const double ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 1, 0.0, P)(0);
  const double bare = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 1)(0);
  std::printf("[   info   ] strip with tip force %+.1f N: flap %.5f rad/s, tensioned beam %.5f (%+.2e; unloaded %.5f)\n", P,
              f, ref, f / ref - 1, bare);
  // The strip's own O(h^2) error (2.8e-4 at rest) plus the membrane's spread of
  // the point load near the tip (Saint-Venant: the tension is P across the
  // strip beyond ~b from the tip, b/L = 5 % of the span): measured -1.8e-4;
  // 2e-3 as the spinning strip's, while the force moves the frequency by +104 %.
  EXPECT_NEAR(f / ref, 1.0, 2e-3);
}

TEST(GeometricStiffness, KeyErrors) {
  try {
    runYaml(R"(
materials:
  steel: {type: isotropic, E: 210.0e9, nu: 0.3, rho: 7850}
body:
  name: rod
  beam: {length: 2.0, elements: 4, section: {shape: solid_circle, diameter: 0.02, material: steel}}
  modes: 2
  geometric_stiffness: true
)");
    ADD_FAILURE() << "a free body with geometric_stiffness was accepted";
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("<test>:8"), std::string::npos) << msg;
    EXPECT_NE(msg.find("geometric_stiffness"), std::string::npos) << msg;
    EXPECT_NE(msg.find("reference"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace fc::feprep::test
