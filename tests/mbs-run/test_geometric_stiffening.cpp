// Geometric stiffening in mbs-run, end to end: fe-prep writes the
// body (geometric_stiffness: true), mbs-run spins it (geometric_stiffening:
// true), and the results are compared with references that share no code with
// either tool:
// - a uniform cantilever spinning about its root at Omega = omega_0 and 2 omega_0:
//   the flapwise and lead-lag frequencies of the run (zero crossings of the tip
//   deflection) against a converged rotating Euler-Bernoulli eigen-analysis
//   (rotating_beam_reference.h, itself checked against the published tables in
//   tests/fe-prep/test_geometric_stiffness.cpp);
// - Kane, Ryan & Banerjee's spin-up beam at Omega_s = 6 and 10 rad/s: the tip
//   deflection against a geometrically exact planar model written here (a
//   Hencky bar chain: rigid links and rotational springs, exact kinematics);
// - off: the same scene without the key gives bit-identical results whether or
//   not the file holds the data.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "../fe-prep/feprep_test_support.h"
#include "helpers.h"
#include "mbs-run/run/simulation.h"
#include "rotating_beam_reference.h"

namespace fc::mbs::test {
namespace {

// Times where s changes sign upward, linearly interpolated.
std::vector<double> upCrossings(const std::vector<double>& t, const std::vector<double>& s) {
  std::vector<double> out;
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k - 1] < 0 && s[k] >= 0) out.push_back(t[k - 1] + (t[k] - t[k - 1]) * (-s[k - 1]) / (s[k] - s[k - 1]));
  return out;
}

double crossingFrequency(const std::vector<double>& t, const std::vector<double>& s) {
  const std::vector<double> c = upCrossings(t, s);
  if (c.size() < 3) return 0.0;
  return 2 * M_PI * static_cast<double>(c.size() - 1) / (c.back() - c.front());
}

// The steel rod of tests/data/fe-prep/spinning_rod.yaml (also read by
// tests/fe-prep/test_geometric_stiffness.cpp): L = 2 m, d = 0.02 m, clamped at its root.
std::string rod(int elements, int modes) {
  return feprep::test::dataBodyYaml("spinning_rod.yaml",
                                    {{"elements", std::to_string(elements)}, {"modes", std::to_string(modes)}});
}

// q as a YAML flow list, "[q0, q1, ...]" (std::to_string: 6 decimals).
std::string flowList(const Eigen::VectorXd& q) {
  std::string out = "[";
  for (long j = 0; j < q.size(); ++j) out += (j ? ", " : "") + std::to_string(q(j));
  return out + "]";
}

// The scenes' first lines: the fixed ground and the rod (its file, modes and
// geometric stiffening as given) placed with its root at the origin; callers
// append the rod's further keys (4-space indent) and the rest of the scene.
std::string groundAndRod(const std::string& file, int modes, bool stiffening) {
  return "bodies:\n"
         "  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n"
         "  - name: rod\n"
         "    flexible: {file: " + file + ", modes: " + std::to_string(modes) +
         (stiffening ? ", geometric_stiffening: true" : "") + "}\n"
         "    position: [1.0, 0, 0]\n";
}

// A driven hub (revolute about z at the rod's root, constant rate Omega) and the rod.
std::string spinningScene(const std::string& file, int modes, double Omega, const Eigen::VectorXd& q0,
                          bool stiffening, double t_end, const std::string& integrator = "dopri5") {
  char text[2000];
  std::snprintf(text, sizeof text, R"(    velocity: [0, %.17g, 0]
    angular_velocity: [0, 0, %.17g]
    modal_coordinates: %s
joints:
  - {name: hub, type: revolute, bodies: [ground, rod], points: [[0, 0, 0], root], axes: [[0, 0, 1], [0, 0, 1]],
     drive: {angle0: 0.0, speed: %.17g}}
simulation: {t_end: %g, output_step: 0.0005, rtol: 1.0e-9, integrator: %s}
)",
                Omega, Omega, flowList(q0).c_str(), Omega, t_end, integrator.c_str());
  return groundAndRod(file, modes, stiffening) + text;
}

struct SpinFrequencies {
  double flap = 0, lag = 0, cpu = 0;
  Eigen::Vector2d linear = Eigen::Vector2d::Zero();  // the linearised modal equations' two lowest
  long steps = 0;
  std::string status;
};

// Spins the rod at Omega started in its stiffened first flap and lag modes
// (eigenvectors of the linearised modal equations, so that the tip traces one
// frequency each) and measures the frequencies of the tip's z and y motion.
SpinFrequencies spinRod(const fc::FlexBody& body, const std::string& file, int modes, double Omega,
                        const std::string& integrator = "dopri5") {
  const double L = 2.0;
  // The linearised modal stiffness about steady spin (mbs-run's equations with
  // the frame held by the drive): Lambda + K_G - Omega^2 S_yy (centrifugal
  // softening in the plane of rotation), unit modal mass.
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body, modes);
  Eigen::MatrixXd K = body.eigenvalues.head(modes).asDiagonal();
  K += Omega * Omega * (body.geometric_stiffness[5] - 0.5 * L * body.geometric_stiffness[0]).topLeftCorner(modes, modes);
  K -= Omega * Omega * inv.modal_products[4];
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
  // The first two eigenvectors: one moves the tip in y (lag), the other in z (flap).
  const FlexInterface& tip = body.interface("tip");
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(modes);
  for (int j = 0; j < 2; ++j) {
    Eigen::VectorXd v = es.eigenvectors().col(j);
    const Eigen::Vector3d u = tip.shapes.topRows(modes).leftCols(3).transpose() * v;
    q0 += 1e-3 * v / u.norm();  // 1 mm at the tip each
  }
  const double period = 2 * M_PI / std::sqrt(es.eigenvalues()(0));
  const Results r = simulate(sceneFromText(spinningScene(file, modes, Omega, q0, true, 6 * period, integrator)), {true});
  SpinFrequencies out;
  out.linear = es.eigenvalues().head(2).cwiseSqrt();
  out.status = r.status;
  out.steps = r.steps;
  out.cpu = r.cpu_seconds;
  std::vector<double> y, z;
  for (const auto& w : r.modal[1]) {
    const Eigen::Vector3d u = tip.shapes.topRows(modes).leftCols(3).transpose() * w;
    y.push_back(u.y());
    z.push_back(u.z());
  }
  out.lag = crossingFrequency(r.time, y);
  out.flap = crossingFrequency(r.time, z);
  return out;
}

TEST(GeometricStiffening, TipMassPullsTheSpinningRodThroughItsJoint) {
  // The rod spinning at Omega = omega_0 with a point mass M joined to its tip
  // interface (spherical joint): the joint's reaction M Omega^2 L tensions the
  // whole rod, through the tip interface's load cases and the multipliers. The
  // flapwise frequency of the run against the rotating-beam eigen-analysis with
  // the tip mass (rotating_beam_reference.h: mass M at the tip, T += M Omega^2 L).
  const int kModes = 8;
  const feprep::BuildResult b = feprep::test::runYaml(rod(40, kModes));
  const std::string file = writeTempBody(b.body, "geostiff_rod_tipmass");
  const double L = 2.0, d = 0.02, A = M_PI * d * d / 4, rhoA = 7850 * A, EI = 210e9 * M_PI * std::pow(d, 4) / 64;
  const double w0 = 1.8751040687 * 1.8751040687 * std::sqrt(EI / (rhoA * std::pow(L, 4)));
  const double Om = w0, M = 2.0;  // the rod weighs 4.93 kg
  // Linearised flapwise modal equations about steady spin: mass I + M Psi_z^T Psi_z
  // (the tip), stiffness Lambda + Omega^2 (K_wzwz - L/2 K_ax) + M Omega^2 L K_tip,fx.
  const FlexInterface& tip = b.body.interface("tip");
  const Eigen::MatrixXd Psi = tip.shapes.topRows(kModes).leftCols(3).transpose();
  Eigen::MatrixXd K = b.body.eigenvalues.head(kModes).asDiagonal();
  K += Om * Om * (b.body.geometric_stiffness[5] - 0.5 * L * b.body.geometric_stiffness[0]);
  K += M * Om * Om * L * tip.geometric_stiffness[0];
  const Eigen::MatrixXd Mm = Eigen::MatrixXd::Identity(kModes, kModes) + M * Psi.row(2).transpose() * Psi.row(2);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, Mm);
  // Start in the lowest mode that moves the tip in z.
  Eigen::VectorXd q0;
  for (int j = 0; j < kModes && q0.size() == 0; ++j) {
    const Eigen::Vector3d u = Psi * es.eigenvectors().col(j);
    if (std::abs(u.z()) > 10 * std::abs(u.y())) q0 = 1e-3 * es.eigenvectors().col(j) / u.z();
  }
  ASSERT_EQ(q0.size(), kModes);
  const double period = 2 * M_PI / w0;
  const Eigen::Vector3d u0 = Psi * q0;  // the mass starts on the displaced tip
  char text[2000];
  std::snprintf(text, sizeof text, R"(    velocity: [0, %.17g, 0]
    angular_velocity: [0, 0, %.17g]
    modal_coordinates: %s
  - name: tip_mass
    rigid: {mass: %g, inertia: [[1.0e-4,0,0],[0,1.0e-4,0],[0,0,1.0e-4]]}
    position: [%.17g, %.17g, %.17g]
    velocity: [0, %.17g, 0]
joints:
  - {name: hub, type: revolute, bodies: [ground, rod], points: [[0, 0, 0], root], axes: [[0, 0, 1], [0, 0, 1]],
     drive: {angle0: 0.0, speed: %.17g}}
  - {name: pin, type: spherical, bodies: [rod, tip_mass], points: [tip, [0, 0, 0]]}
simulation: {t_end: %g, output_step: 0.0005, rtol: 1.0e-9, integrator: dopri5}
)",
                Om, Om, flowList(q0).c_str(), M, 2.0 + u0.x(), u0.y(), u0.z(), (2.0 + u0.x()) * Om, Om, 8 * period);
  const Results r = simulate(sceneFromText(groundAndRod(file, kModes, true) + text), {true});
  ASSERT_EQ(r.status, "completed");
  std::vector<double> z;
  for (const auto& w : r.modal[1]) z.push_back((Psi * w).z());
  const double flap = crossingFrequency(r.time, z);
  const double ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, Om, false, 80, 1, 0.0, 0.0, M)(0);
  const double no_pull = fc::test::rotatingBeamFrequencies(L, EI, rhoA, Om, false, 80, 1)(0);
  // The same linearised model without the joint's pull (mass at the tip, no tension from it).
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> loose(K - M * Om * Om * L * tip.geometric_stiffness[0], Mm);
  const double unpulled = std::sqrt(loose.eigenvalues()(0));
  std::printf("[   info   ] tip mass %.1f kg at Omega = omega_0: flap %.5f rad/s (linearised %.5f, reference %.5f; "
              "without the joint's pull %.5f; the bare rod %.5f)\n", M, flap, std::sqrt(es.eigenvalues()(0)), ref,
              unpulled, no_pull);
  // Budget as the spinning rod's (40 lumped-mass elements, 8 modes, the
  // crossing count over ~8 periods at 0.5 ms): 2e-3; the issue asks for 1 %.
  EXPECT_NEAR(flap / ref, 1.0, 2e-3);
  // The pull matters far beyond that budget, so the check sees the interface cases.
  EXPECT_GT(std::abs(unpulled / ref - 1.0), 10 * 2e-3);
}

TEST(GeometricStiffening, ForceElementsAtTheTipStiffenTheRod) {
  // The rod clamped at its root (no spin) and loaded at its tip interface by a
  // force element: a soft translational spring anchored 100 km away along +x
  // with a preload of +10 EI/L^2 (tension), and a constant force of
  // -1.5 EI/L^2 along x (compression, below Euler's 2.47 EI/L^2). Their force
  // at the interface weights fe-prep's tip cases; the run's first bending
  // frequency against the tensioned-beam eigen-analysis (rotating_beam_reference.h,
  // constant tension T = P: a dead axial tip load). The spring's lateral pull
  // P/D (0.04 N/m against the rod's 3 EI/L^3 = 620 N/m at the tip) is ~3e-5 of
  // the frequency.
  const int kModes = 12;  // the tensioned shape needs more modes (tests/fe-prep/test_geometric_stiffness.cpp)
  const feprep::BuildResult b = feprep::test::runYaml(rod(40, kModes));
  const std::string file = writeTempBody(b.body, "geostiff_tipforce");
  const double L = 2.0, d = 0.02, A = M_PI * d * d / 4, rhoA = 7850 * A, EI = 210e9 * M_PI * std::pow(d, 4) / 64;
  const FlexInterface& tip = b.body.interface("tip");
  const Eigen::MatrixXd Psi = tip.shapes.topRows(kModes).leftCols(3).transpose();
  for (int spring = 1; spring >= 0; --spring) {
    const double P = spring ? 10.0 * EI / (L * L) : -1.5 * EI / (L * L);
    Eigen::MatrixXd K = b.body.eigenvalues.head(kModes).asDiagonal();
    K += P * tip.geometric_stiffness[0];
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
    const Eigen::VectorXd v = es.eigenvectors().col(0);
    const Eigen::Vector3d u = Psi * v;
    const Eigen::VectorXd q0 = 1e-3 * v / u.norm();
    const double D = 1.0e5, k = 1.0;
    char force[400];
    if (spring)
      std::snprintf(force, sizeof force,
                    "  - {type: translational_spring_damper, bodies: [rod, ground], points: [tip, [%.17g, 0, 0]], "
                    "stiffness: %g, free_length: %.17g}\n", D, k, D - 2.0 - P / k);
    else
      std::snprintf(force, sizeof force, "  - {type: force, body: rod, point: tip, force: [%.17g, 0, 0]}\n", P);
    const double period = 2 * M_PI / std::sqrt(es.eigenvalues()(0));
    char text[2000];
    std::snprintf(text, sizeof text, R"(    modal_coordinates: %s
joints:
  - {name: clamp, type: fixed, bodies: [ground, rod], points: [[0, 0, 0], root]}
forces:
%ssimulation: {t_end: %g, output_step: 0.0002, rtol: 1.0e-9}
)",
                  flowList(q0).c_str(), force, 6 * period);
    const Results r = simulate(sceneFromText(groundAndRod(file, kModes, true) + text), {true});
    ASSERT_EQ(r.status, "completed");
    const Eigen::Vector3d dir = u.normalized();
    std::vector<double> s;
    for (const auto& w : r.modal[1]) s.push_back(dir.dot(Psi * w));
    const double f = crossingFrequency(r.time, s);
    const double ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 1, 0.0, P)(0);
    const double bare = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 1)(0);
    std::printf("[   info   ] %s %+.0f N at the tip: bending %.5f rad/s (linearised %.5f, tensioned beam %.5f, %+.2e; "
                "unloaded %.5f)\n", spring ? "spring" : "force", P, f, std::sqrt(es.eigenvalues()(0)), ref, f / ref - 1, bare);
    // The fe-prep model's own error with the tip cases (40 lumped-mass
    // elements, 12 modes: 9e-5 at +10 EI/L^2, 3e-4 at -1.5 EI/L^2, linearised)
    // plus the crossing count (~1e-5): 2e-3, as the spinning rod's.
    EXPECT_NEAR(f / ref, 1.0, 2e-3);
    // The load moves the frequency by +104 % / -36 %: far beyond the tolerance.
    EXPECT_GT(std::abs(bare / ref - 1), 0.3);
  }
  std::filesystem::remove(file);
}

TEST(GeometricStiffening, SpinningCantileverFlapAndLagFrequencies) {
  // 8 modes (4 bending pairs): with 4 the lag frequency at 2 omega_0 is 1 % high
  // (the stiffened shape needs the higher modes; measured).
  const int kModes = 8;
  const feprep::BuildResult b = feprep::test::runYaml(rod(40, kModes));
  const std::string file = writeTempBody(b.body, "geostiff_rod");
  const double L = 2.0, d = 0.02, A = M_PI * d * d / 4, rhoA = 7850 * A, EI = 210e9 * M_PI * std::pow(d, 4) / 64;
  const double w0 = 1.8751040687 * 1.8751040687 * std::sqrt(EI / (rhoA * std::pow(L, 4)));
  for (double ratio : {1.0, 2.0}) {
    const double Om = ratio * w0;
    const SpinFrequencies f = spinRod(b.body, file, kModes, Om);
    ASSERT_EQ(f.status, "completed");
    const double flap = fc::test::rotatingBeamFrequencies(L, EI, rhoA, Om, false, 80, 1)(0);
    const double lag = fc::test::rotatingBeamFrequencies(L, EI, rhoA, Om, true, 80, 1)(0);
    std::printf("[   info   ] rod spun at %.0f omega_0 = %.3f rad/s: flap %.5f rad/s (reference %.5f, %+.2e), lag %.5f "
                "rad/s (reference %.5f, %+.2e); linearised modal equations %.5f %.5f; %ld steps, %.2f s CPU\n",
                ratio, Om, f.flap, flap, f.flap / flap - 1, f.lag, lag, f.lag / lag - 1, f.linear(0), f.linear(1), f.steps, f.cpu);
    // The run is the linearised modal equations it was started from: the
    // crossings of 6 periods sampled at 0.5 ms (linear interpolation) and the
    // rtol 1e-9 integration agree with their eigenvalues to ~1e-6; 1e-4.
    EXPECT_NEAR(f.lag / f.linear(0), 1.0, 1e-4);
    EXPECT_NEAR(f.flap / f.linear(1), 1.0, 1e-4);
    // The issue asks for 1 %. Expected: fe-prep's model (40 lumped-mass
    // Timoshenko elements: O(h^2) ~4e-4, shear/rotary ~1e-4) with 8 modes
    // (truncation of the stiffened shape ~1e-4): 1e-3 flap; lag 2e-3 (the
    // difference omega_flap^2 - Omega^2 amplifies relative errors by
    // omega_flap^2/omega_lag^2, 3.5 at 2 omega_0).
    EXPECT_NEAR(f.flap / flap, 1.0, 1e-3);
    EXPECT_NEAR(f.lag / lag, 1.0, 2e-3);
  }
  std::filesystem::remove(file);
}

TEST(GeometricStiffening, SpinningPlateStripFlapsAsTheRotatingBeam) {
  // The shells' membrane-stress geometric stiffness end to end: the narrow
  // strip of tests/data/fe-prep/spinning_strip.yaml (DST, 2 m x 0.1 m x 0.01 m,
  // nu = 0: a beam of EI = E b t^3 / 12, rho A = rho b t) spun about its normal
  // (z) through the root at Omega = omega_0, started in its stiffened first
  // flapwise mode; the tip's z frequency against the rotating-beam eigen-analysis.
  const int kModes = 8;
  const feprep::BuildResult b =
      feprep::test::runYaml(feprep::test::dataBodyYaml("spinning_strip.yaml", {{"modes", std::to_string(kModes)}}));
  const std::string file = writeTempBody(b.body, "geostiff_strip");
  const double L = 2.0, w = 0.1, t = 0.01, EI = 70e9 * w * t * t * t / 12, rhoA = 2700 * w * t;
  const double w0 = 1.8751040687 * 1.8751040687 * std::sqrt(EI / (rhoA * std::pow(L, 4)));
  const double Om = w0;
  // Linearised modal equations about steady spin, as spinRod's.
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(b.body, kModes);
  Eigen::MatrixXd K = b.body.eigenvalues.head(kModes).asDiagonal();
  K += Om * Om * (b.body.geometric_stiffness[5] - 0.5 * L * b.body.geometric_stiffness[0]).topLeftCorner(kModes, kModes);
  K -= Om * Om * inv.modal_products[4];
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
  const Eigen::MatrixXd Psi = b.body.interface("tip").shapes.topRows(kModes).leftCols(3).transpose();
  Eigen::VectorXd q0;
  double linear = 0;
  for (int j = 0; j < kModes && q0.size() == 0; ++j) {
    const Eigen::Vector3d u = Psi * es.eigenvectors().col(j);
    if (std::abs(u.z()) > 10 * u.head<2>().norm()) {
      q0 = 1e-3 * es.eigenvectors().col(j) / u.z();
      linear = std::sqrt(es.eigenvalues()(j));
    }
  }
  ASSERT_EQ(q0.size(), kModes);
  const Results r = simulate(sceneFromText(spinningScene(file, kModes, Om, q0, true, 6 * 2 * M_PI / linear)), {true});
  ASSERT_EQ(r.status, "completed");
  std::vector<double> z;
  for (const auto& m : r.modal[1]) z.push_back((Psi * m).z());
  const double flap = crossingFrequency(r.time, z);
  const double ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, Om, false, 80, 1)(0);
  std::printf("[   info   ] strip spun at omega_0 = %.4f rad/s: flap %.5f rad/s (linearised %.5f, rotating beam %.5f, "
              "%+.2e; at rest %.5f)\n", Om, flap, linear, ref, flap / ref - 1, w0);
  // The run against its own linearised equations: as the rod's, 1e-4.
  EXPECT_NEAR(flap / linear, 1.0, 1e-4);
  // The issue asks for 1-2 %. Expected: fe-prep's strip at h = 0.05 m is 1.7e-4
  // low at omega_0 and 2.8e-4 at rest (DST with lumped masses, O(h^2);
  // tests/fe-prep/test_geometric_stiffness.cpp), plus the crossing count
  // (~1e-5): 2e-3, a thirtieth of the stiffening itself (+48 %).
  EXPECT_NEAR(flap / ref, 1.0, 2e-3);
  std::filesystem::remove(file);
}

TEST(GeometricStiffening, HangingRodStiffenedByGravity) {
  // Gravity enters as a frame acceleration -g: a rod clamped at its root and
  // hanging along +x under g = 9.81 m/s^2 along +x carries the tension
  // rho A g (L - x), which raises its bending frequency (here by 0.7 %); a rod
  // standing on its root (g along -x) is compressed and softened.
  const feprep::BuildResult b = feprep::test::runYaml(rod(40, 8));
  const std::string file = writeTempBody(b.body, "geostiff_hanging");
  const double L = 2.0, d = 0.02, A = M_PI * d * d / 4, rhoA = 7850 * A, EI = 210e9 * M_PI * std::pow(d, 4) / 64;
  const FlexInterface& tip = b.body.interface("tip");
  for (double sign : {1.0, -1.0}) {
    // Start in the first mode of the stiffened modal equations (Lambda - g_x K_a_x).
    Eigen::MatrixXd K = b.body.eigenvalues.head(8).asDiagonal();
    K += -(-sign * 9.81) * b.body.geometric_stiffness[0];
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
    const Eigen::VectorXd v = es.eigenvectors().col(0);
    const Eigen::Vector3d u = tip.shapes.leftCols(3).transpose() * v;
    const Eigen::VectorXd q0 = 1e-3 * v / u.norm();
    char text[1200];
    std::snprintf(text, sizeof text, R"(    modal_coordinates: %s
joints:
  - {name: clamp, type: fixed, bodies: [ground, rod], points: [[0, 0, 0], root]}
forces:
  - {type: gravity, g: [%g, 0, 0]}
simulation: {t_end: 1.7, output_step: 0.0005, rtol: 1.0e-9}
)",
                  flowList(q0).c_str(), sign * 9.81);
    const Results r = simulate(sceneFromText(groundAndRod(file, 8, true) + text), {true});
    ASSERT_EQ(r.status, "completed");
    // The mode's tip direction (the round rod's pair is degenerate: any direction).
    const Eigen::Vector3d dir = u.normalized();
    std::vector<double> s;
    for (const auto& w : r.modal[1]) s.push_back(dir.dot(tip.shapes.leftCols(3).transpose() * w));
    const double f = crossingFrequency(r.time, s);
    const double ref = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 1, sign * 9.81)(0);
    const double bare = fc::test::rotatingBeamFrequencies(L, EI, rhoA, 0.0, false, 80, 1)(0);
    std::printf("[   info   ] rod %s under gravity: %.5f rad/s (reference %.5f, %+.2e; without gravity %.5f)\n",
                sign > 0 ? "hanging" : "standing", f, ref, f / ref - 1, bare);
    // The model's own error (40 lumped-mass elements, 8 modes) is ~4e-4, as for
    // the spinning rod: 1e-3, and within a fifth of the gravity effect itself
    // (0.7 %, of the right sign), so a missing or reversed g would fail.
    EXPECT_NEAR(f / ref, 1.0, 1e-3);
    EXPECT_GT(std::abs(ref / bare - 1), 5e-3);
    EXPECT_LT(std::abs(f - ref), 0.2 * std::abs(ref - bare));
  }
  std::filesystem::remove(file);
}

TEST(GeometricStiffening, OffIsBitIdentical) {
  // The same scene without the key, from a file with and without the data:
  // every output bit-identical (the data is not even read).
  const feprep::BuildResult b = feprep::test::runYaml(rod(20, 4));
  const std::string with = writeTempBody(b.body, "geostiff_with");
  fc::FlexBody plain = b.body;
  plain.geometric_stiffness.clear();
  const std::string without = writeTempBody(plain, "geostiff_without");
  Eigen::VectorXd q0 = Eigen::VectorXd::Constant(4, 1e-4);
  const Results a = simulate(sceneFromText(spinningScene(with, 4, 10.0, q0, false, 0.5)), {true});
  const Results c = simulate(sceneFromText(spinningScene(without, 4, 10.0, q0, false, 0.5)), {true});
  ASSERT_EQ(a.status, "completed");
  ASSERT_EQ(a.time.size(), c.time.size());
  for (std::size_t k = 0; k < a.time.size(); ++k) {
    ASSERT_EQ(a.time[k], c.time[k]);
    for (long j = 0; j < 4; ++j) ASSERT_EQ(a.modal[1][k](j), c.modal[1][k](j)) << "row " << k;
  }
  EXPECT_EQ(a.steps, c.steps);
  // (The cost, off and on: bench/mbs-run/bench_stiffening.cpp, docs/benchmarks.md.)
  // The key on a file without the data: an error at the key.
  try {
    sceneFromText(spinningScene(without, 4, 10.0, q0, true, 0.5));
    ADD_FAILURE() << "geometric_stiffening accepted a file without the data";
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("geometric_stiffening"), std::string::npos) << msg;
    EXPECT_NE(msg.find("geometric_stiffness: true"), std::string::npos) << msg;
  }
  std::filesystem::remove(with);
  std::filesystem::remove(without);
}

// Kane, Ryan & Banerjee, J. Guid. Control Dyn. 10 (1987) 139-151: a uniform
// cantilever L = 10 m, E = 7e10 Pa, A = 4e-4 m^2, I = 2e-7 m^4, rho = 3000 kg/m^3
// (EA = 2.8e7 N, EI = 14 000 N m^2, rho A = 1.2 kg/m), its hub spun up by
// theta(t) = Os/T (t^2/2 + (T/2 pi)^2 (cos(2 pi t/T) - 1)) for t < T = 15 s, then
// at the rate Os. Here a tube of that A and I (equal bending stiffness in both
// planes; the motion stays in the plane of rotation).
double hubAngle(double Os, double t) {
  const double T = 15.0;
  if (t >= T) return Os * T / 2 + Os * (t - T);
  return Os / T * (t * t / 2 + std::pow(T / (2 * M_PI), 2) * (std::cos(2 * M_PI * t / T) - 1));
}

// Geometrically exact planar reference: a Hencky bar chain (N rigid uniform links
// of length l = L/N, joined by rotational springs EI/l, the first held to the hub
// by 2 EI/l: the central-difference discretisation of the inextensible
// Euler-Bernoulli elastica, converging as 1/N^2), with exact large-rotation
// kinematics. Absolute link angles phi_i; the hub angle theta(t) is prescribed.
// Lagrange's equations: sum_k G_jk [cos(phi_j - phi_k) phi_k'' + sin(phi_j - phi_k) phi_k'^2]
// = -dV/dphi_j, G_jk = m l^2 (N - max(j, k) + 1/2) (j != k), G_jj = m l^2 (N - j + 1/4) + m l^2/12
// (1-based), V = sum_j k_j/2 (phi_j - phi_{j-1})^2, phi_0 = theta.
struct HenckyChain {
  int N;
  double l, m, EI;
  Eigen::MatrixXd G;
  HenckyChain(int n, double L, double rhoA, double ei) : N(n), l(L / n), m(rhoA * L / n), EI(ei), G(n, n) {
    for (int j = 1; j <= N; ++j)
      for (int k = 1; k <= N; ++k)
        G(j - 1, k - 1) = j == k ? m * l * l * (N - j + 0.25 + 1.0 / 12) : m * l * l * (N - std::max(j, k) + 0.5);
  }
  Eigen::VectorXd accel(const Eigen::VectorXd& phi, const Eigen::VectorXd& dphi, double theta) const {
    Eigen::MatrixXd M(N, N);
    Eigen::VectorXd rhs(N);
    for (int j = 0; j < N; ++j) {
      double c = 0.0;
      for (int k = 0; k < N; ++k) {
        const double d = phi(j) - phi(k);
        M(j, k) = G(j, k) * std::cos(d);
        c += G(j, k) * std::sin(d) * dphi(k) * dphi(k);
      }
      const double kj = (j == 0 ? 2.0 : 1.0) * EI / l;
      const double prev = j == 0 ? theta : phi(j - 1);
      double f = -kj * (phi(j) - prev);
      if (j + 1 < N) f += EI / l * (phi(j + 1) - phi(j));
      rhs(j) = f - c;
    }
    return M.ldlt().solve(rhs);
  }
  // Tip deflection normal to the hub's radial line (the rotating frame's y).
  double tipDeflection(const Eigen::VectorXd& phi, double theta) const {
    double x = 0, y = 0;
    for (int j = 0; j < N; ++j) x += l * std::cos(phi(j)), y += l * std::sin(phi(j));
    return -std::sin(theta) * x + std::cos(theta) * y;
  }
};

// The chain's tip deflection at the given times (RK4, step below its stability limit).
std::vector<double> henckySpinUp(int N, double Os, const std::vector<double>& times) {
  const HenckyChain c(N, 10.0, 1.2, 14000.0);
  // Highest frequency of the chain at rest (linearised: G phi'' = -K phi).
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  for (int j = 0; j < N; ++j) {
    K(j, j) += (j == 0 ? 2.0 : 1.0) * c.EI / c.l;
    if (j + 1 < N) {
      K(j, j) += c.EI / c.l;
      K(j, j + 1) -= c.EI / c.l;
      K(j + 1, j) -= c.EI / c.l;
    }
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, c.G);
  // RK4 is stable to h omega = 2.8; 1.0 keeps its error on the top modes damped
  // and the first mode's (h omega_1 ~ 1e-4) negligible.
  const double hmax = 1.0 / std::sqrt(es.eigenvalues().maxCoeff());
  auto f = [&](double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd d(2 * N);
    d.head(N) = y.tail(N);
    d.tail(N) = c.accel(y.head(N), y.tail(N), hubAngle(Os, t));
    return d;
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * N);
  std::vector<double> out;
  double t = 0;
  for (double tk : times) {
    if (tk > t) y = rk4(f, y, t, tk, static_cast<int>(std::ceil((tk - t) / hmax)));
    t = tk;
    out.push_back(c.tipDeflection(y.head(N), hubAngle(Os, t)));
  }
  return out;
}

struct KaneRun {
  std::vector<double> time, tip;
  double tip_max = 0, cpu = 0;
  long steps = 0;
  std::string status;
};

KaneRun kaneRun(const fc::FlexBody& body, const std::string& file, int modes, double Os, bool stiffening) {
  char text[1500];
  std::snprintf(text, sizeof text, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: %s, modes: %d%s}
    position: [5.0, 0, 0]
joints:
  - {name: hub, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], root], axes: [[0, 0, 1], [0, 0, 1]],
     drive: {angle0: 0.0, spin_up: {rate: %g, time: 15.0}}}
simulation: {t_end: 20.0, output_step: 0.05, rtol: 1.0e-8}
)",
                file.c_str(), modes, stiffening ? ", geometric_stiffening: true" : "", Os);
  const Results r = simulate(sceneFromText(text), {true});
  KaneRun out;
  out.status = r.status;
  out.steps = r.steps;
  out.cpu = r.cpu_seconds;
  out.time = r.time;
  const FlexInterface& tip = body.interface("tip");
  for (const auto& w : r.modal[1]) {
    out.tip.push_back(tip.shapes.col(1).head(modes).dot(w));
    out.tip_max = std::max(out.tip_max, std::abs(out.tip.back()));
  }
  return out;
}

TEST(GeometricStiffening, KaneSpinUpBeamStaysBoundedAsTheExactBeam) {
  // Tube of A = 4e-4 m^2 and I = 2e-7 m^4 (outer diameter and wall solved to 1e-16).
  const feprep::BuildResult b = feprep::test::runYaml(R"(
materials:
  al: {type: isotropic, E: 7.0e10, nu: 0.3, rho: 3000}
body:
  name: kane
  beam: {length: 10.0, elements: 40, section: {shape: tube, outer_diameter: 0.06522766214534317, wall: {thickness: 0.0020141901799545195}, material: al}}
  interfaces: {root: [-5.0, 0, 0], tip: [5.0, 0, 0]}
  reference: {clamp: [root]}
  mass: lumped
  geometric_stiffness: true
  modes: 8
)");
  const std::string file = writeTempBody(b.body, "geostiff_kane");
  for (double Os : {6.0, 10.0}) {
    const KaneRun run = kaneRun(b.body, file, 8, Os, true);
    ASSERT_EQ(run.status, "completed");
    // The chain converges as 1/N^2: Richardson's (4 y_24 - y_12)/3 is the
    // converged beam to O(1/N^4) (N = 40 at Os = 10 gave a peak 0.8586 m, N = 20
    // 0.8606 m: 2.3e-3 apart, three quarters of N = 20's error).
    const std::vector<double> fine = henckySpinUp(24, Os, run.time);
    const std::vector<double> coarse = henckySpinUp(12, Os, run.time);
    double ref_max = 0, fine_max = 0, coarse_max = 0, diff = 0;
    std::vector<double> ref(fine.size());
    for (std::size_t k = 0; k < ref.size(); ++k) {
      ref[k] = (4 * fine[k] - coarse[k]) / 3;
      ref_max = std::max(ref_max, std::abs(ref[k]));
      fine_max = std::max(fine_max, std::abs(fine[k]));
      coarse_max = std::max(coarse_max, std::abs(coarse[k]));
      diff = std::max(diff, std::abs(run.tip[k] - ref[k]));
    }
    std::printf("[   info   ] Kane spin-up Os = %.0f rad/s: largest tip deflection %.4f m (exact beam, extrapolated: "
                "%.4f m; N = 24: %.4f m, N = 12: %.4f m); largest difference over the run %.4f m = %.2f %% of the peak; "
                "tip at 20 s %.4f m (exact %.4f m); %ld steps, %.2f s CPU\n",
                Os, run.tip_max, ref_max, fine_max, coarse_max, diff, 100 * diff / ref_max, run.tip.back(), ref.back(),
                run.steps, run.cpu);
    // Converging: the two chains differ by 1 % at most, so the extrapolation is
    // far inside the tolerance below.
    EXPECT_LT(std::abs(fine_max - coarse_max), 0.01 * ref_max);
    // Bounded as the exact beam (the lag during the spin-up peaks below L/10 and
    // dies out at constant rate), not divergent as linear modes without
    // stiffening are (past 10 m at 7.1 s, docs/mbs-run.md).
    EXPECT_LT(run.tip_max, 0.1 * 10.0);
    // "Within a few percent" of the exact beam: the modal model is
    // linear in the deflection (the exact one is not: (tip/L)^2 ~ 7e-3 of
    // second-order terms, most of which the stiffening carries), has 4 in-plane
    // modes and fe-prep's lumped masses (~1e-3); measured 0.16 % and 0.25 % of the
    // peak over the whole history, 1 % asserted.
    EXPECT_NEAR(run.tip_max / ref_max, 1.0, 0.01);
    EXPECT_LT(diff, 0.01 * ref_max);
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace fc::mbs::test
