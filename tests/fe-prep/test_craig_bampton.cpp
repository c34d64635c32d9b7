// Craig-Bampton bodies (issue 16, contracts.md reduction: craig_bampton): two
// 1 m steel beam bodies welded end to end in mbs-run are one 2 m cantilever.
// References nobody here wrote: Timoshenko's cantilever deflection
// P L^3 / 3EI + P L / (kappa G A) (kappa: Cowper's solid-circle factor), and
// the lowest frequency of the 2 m cantilever modelled whole by fe-prep.
// With free-interface modes (two per body) both are far off: the test asserts
// that too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/flexbody.h"
#include "common/input.h"
#include "common/rotations.h"
#include "feprep_test_support.h"
#include "mbs-run/scene.h"
#include "mbs-run/simulation.h"

namespace fc::feprep::test {
namespace {

const double E = 210e9, nu = 0.3, rho = 7850, d = 0.02;

std::string halfYaml(bool craig_bampton) {
  return std::string(R"(
materials:
  steel: {type: isotropic, E: 210.0e9, nu: 0.3, rho: 7850}
body:
  name: half
  beam: {length: 1.0, elements: 10, section: {shape: solid_circle, diameter: 0.02, material: steel}}
  interfaces: {a: [-0.5, 0, 0], b: [0.5, 0, 0]}
)") + (craig_bampton ? "  reference: {clamp: [a, b]}\n  reduction: craig_bampton\n" : "  reference: free\n") +
         "  modes: 2\n";
}

std::string writeBody(const BuildResult& r, const std::string& tag) {
  const std::string path = scratchDir("cb-" + tag) + "/half.h5";
  Provenance p;
  p.inputs_sha256 = std::string(64, '0');
  writeFlexBody(path, r.body, computeInertiaInvariants(r.body), p);
  return path;
}

// Two halves: A clamped to the ground at its end a (global x = 0), B welded to
// A's end b; tip force -P y at B's end b (global x = 2). Returns the tip's y
// over time.
std::vector<double> weldedTip(const std::string& file, double zeta, double t_end, double step, std::vector<double>* time) {
  char scene[2048];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: A, flexible: {file: %s, modes: all, damping_ratio: %g}, position: [0.5, 0, 0]}
  - {name: B, flexible: {file: %s, modes: all, damping_ratio: %g}, position: [1.5, 0, 0]}
joints:
  - {name: root, type: fixed, bodies: [ground, A], points: [[0, 0, 0], a]}
  - {name: weld, type: fixed, bodies: [A, B], points: [b, a]}
forces:
  - {type: force, body: B, point: b, force: [0, -1.0, 0]}
simulation: {t_end: %g, output_step: %g, rtol: 1.0e-9}
)",
                file.c_str(), zeta, file.c_str(), zeta, t_end, step);
  const mbs::Model model = mbs::parseScene(InputNode::loadString(scene, "welded.yaml"));
  const mbs::Results r = mbs::simulate(model, {true});
  EXPECT_EQ(r.status, "completed");
  const FlexBody b = readFlexBody(file).body;
  const FlexInterface& tip = b.interface("b");
  std::vector<double> y;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const Eigen::Vector3d local = tip.position + tip.shapes.leftCols(3).transpose() * r.modal[2][k];
    y.push_back((r.position[2][k] + rotationMatrix(r.orientation[2][k]) * local).y());
  }
  if (time) *time = r.time;
  return y;
}

// The mean and the period of an oscillation from rest (y(0) = 0): first the
// mean over the whole run, then (twice) the upward crossings of the mean and
// the mean over the whole periods between the first and the last of them.
struct Swing {
  double mean = 0.0, period = 0.0;
};
Swing swingOf(const std::vector<double>& t, const std::vector<double>& y) {
  Swing s;
  for (double v : y) s.mean += v / static_cast<double>(y.size());
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::size_t> up;
    std::vector<double> at;
    for (std::size_t k = 1; k < y.size(); ++k)
      if (y[k - 1] < s.mean && y[k] >= s.mean) {
        up.push_back(k);
        at.push_back(t[k - 1] + (s.mean - y[k - 1]) / (y[k] - y[k - 1]) * (t[k] - t[k - 1]));
      }
    if (up.size() < 2) return {};
    s.period = (at.back() - at.front()) / static_cast<double>(at.size() - 1);
    double integral = 0.0;  // trapezoids between the first and last crossing
    for (std::size_t k = up.front(); k < up.back(); ++k) integral += 0.5 * (y[k] + y[k - 1]) * (t[k] - t[k - 1]);
    s.mean = integral / (t[up.back() - 1] - t[up.front() - 1]);
  }
  return s;
}

TEST(CraigBampton, TwoWeldedHalvesAreOneCantileverStaticallyAndInFrequency) {
  const BuildResult cb = runYaml(halfYaml(true), "cb.yaml");
  const BuildResult ff = runYaml(halfYaml(false), "free.yaml");
  // 12 constraint modes + 2 fixed-interface modes - 6 rigid motions.
  ASSERT_EQ(cb.body.modeCount(), 8);
  EXPECT_EQ(cb.rigid_removed, 6);
  EXPECT_EQ(cb.body.reduction, "craig_bampton: 12 constraint modes + 2 fixed-interface modes - 6 rigid = 8 shapes");
  // Diagonalised: unit modal mass with the file's nodal masses, ascending eigenvalues.
  Eigen::VectorXd m(6 * cb.body.nodeCount());
  for (long k = 0; k < cb.body.nodeCount(); ++k) {
    m.segment<3>(6 * k).setConstant(cb.body.nodal_mass(k, 0));
    m.segment<3>(6 * k + 3) = cb.body.nodal_mass.block<1, 3>(k, 1).transpose();
  }
  const Eigen::MatrixXd G = cb.body.shapes.transpose() * m.asDiagonal() * cb.body.shapes;
  EXPECT_LT((G - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-9);
  const std::string cb_file = writeBody(cb, "cb"), ff_file = writeBody(ff, "free");

  // Statics and frequency from one undamped step response (no damping model
  // in the way: modal damping of each body's own shapes damps the welded
  // pair's 3.6 Hz mode, which is mostly frame motion, hardly at all). From rest
  // under a step load the tip oscillates about the static deflection: its mean
  // over whole periods of the first mode is the static deflection (the faster
  // modes, ~3 % of it, average out to ~1e-4 over four periods), the period the
  // first mode's.
  const double L = 2.0, A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64, G_mod = E / (2 * (1 + nu));
  const double kappa = 6 * (1 + nu) / (7 + 6 * nu);
  const double exact = L * L * L / (3 * E * I) + L / (kappa * G_mod * A);
  std::vector<double> t, tf;
  const std::vector<double> y = weldedTip(cb_file, 0.0, 1.2, 2e-4, &t);
  const std::vector<double> yf = weldedTip(ff_file, 0.0, 1.2, 2e-4, &tf);
  const Swing s_cb = swingOf(t, y), s_ff = swingOf(tf, yf);
  std::printf("[   info   ] tip deflection under 1 N: Timoshenko %.6e m; Craig-Bampton halves %.6e (%+.2e); "
              "free-interface halves (2 modes each) %.6e (%+.2e)\n", exact, -s_cb.mean, -s_cb.mean / exact - 1,
              -s_ff.mean, -s_ff.mean / exact - 1);
  // The constraint modes hold the static response at the weld exactly; what is
  // left is the beam element (10 per metre), the averaging (~1e-4) and the
  // integrator (rtol 1e-9).
  EXPECT_NEAR(-s_cb.mean / exact, 1.0, 0.002);
  EXPECT_GT(std::abs(-s_ff.mean / exact - 1), 0.05);

  // Frequency: the whole 2 m cantilever in fe-prep, 20 elements, same mass option.
  const BuildResult whole = runYaml(R"(
materials:
  steel: {type: isotropic, E: 210.0e9, nu: 0.3, rho: 7850}
body:
  name: whole
  beam: {length: 2.0, elements: 20, section: {shape: solid_circle, diameter: 0.02, material: steel}}
  reference: {clamp: [end_min]}
  modes: 1
)");
  const double f_whole = whole.body.frequencies_hz(0);
  const double f_cb = 1.0 / s_cb.period, f_ff = 1.0 / s_ff.period;
  std::printf("[   info   ] first frequency: whole cantilever (fe-prep, 20 elements) %.5f Hz; Craig-Bampton halves "
              "%.5f Hz (%+.2e); free-interface halves %.5f Hz (%+.2e)\n", f_whole, f_cb, f_cb / f_whole - 1, f_ff,
              f_ff / f_whole - 1);
  EXPECT_NEAR(f_cb / f_whole, 1.0, 0.005);
  EXPECT_GT(std::abs(f_ff / f_whole - 1), 0.05);
}

}  // namespace
}  // namespace fc::feprep::test
