// Simulation presets (`simulation: {preset: fast | accurate}`, docs/accuracy.md):
// - a preset fills in the settings it names, keys written beside it win;
// - an unknown name is a located input error with a did-you-mean;
// - the presets really trade accuracy for work: on a rod pendulum released
//   from the horizontal (large swing, no small-angle closed form) both are
//   compared with the 1-DOF equation phi'' = m g (L/2) cos(phi) / I_pivot
//   integrated by RK4 at a step far below either tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "helpers.h"
#include "mbs-run/run/run_policy.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

std::string pendulum(const std::string& simulation) {
  return R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: rod, rod: {length: 1.0, diameter: 0.02, mass: 1.0}, position: [0.5, 0, 0]}
joints:
  - {name: R, type: revolute, bodies: [ground, rod], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
simulation: )" + simulation + "\n";
}

TEST(Presets, FillDefaultsAndExplicitKeysWin) {
  // fast: auto, which picks dopri5 for this soft scene and may switch to
  // TR-BDF2 where the run proves stiff; accurate: dopri5 throughout. The
  // scene records what was asked for, the run policy what it means.
  Model m = sceneFromText(pendulum("{t_end: 1, preset: fast}"));
  EXPECT_EQ(m.settings.rtol, 1e-4);
  EXPECT_EQ(m.settings.integrator, IntegratorKind::Auto);
  RunPolicy p = runPolicy(m);
  EXPECT_EQ(p.integrator, IntegratorKind::DormandPrince);
  EXPECT_TRUE(p.switch_when_stiff);
  EXPECT_EQ(p.atol, 1e-3 * 1e-4);  // the default atol
  m = sceneFromText(pendulum("{t_end: 1, preset: accurate}"));
  p = runPolicy(m);
  EXPECT_EQ(p.rtol, 1e-7);
  EXPECT_EQ(p.integrator, IntegratorKind::DormandPrince);
  EXPECT_FALSE(p.switch_when_stiff);
  // Order in the map does not matter: explicit keys override the preset.
  p = runPolicy(sceneFromText(pendulum("{rtol: 1.0e-5, t_end: 1, preset: fast}")));
  EXPECT_EQ(p.rtol, 1e-5);
  EXPECT_EQ(p.integrator, IntegratorKind::DormandPrince);
  p = runPolicy(sceneFromText(pendulum("{t_end: 1, preset: accurate, integrator: trbdf2}")));
  EXPECT_EQ(p.rtol, 1e-7);
  EXPECT_EQ(p.integrator, IntegratorKind::TrBdf2);
  EXPECT_FALSE(p.switch_when_stiff);
  // No preset: the documented defaults (rtol 1e-6, auto -> dopri5 for a soft
  // scene, max_step ten output intervals).
  p = runPolicy(sceneFromText(pendulum("{t_end: 1}")));
  EXPECT_EQ(p.rtol, 1e-6);
  EXPECT_EQ(p.integrator, IntegratorKind::DormandPrince);
  EXPECT_EQ(p.max_step, 10.0 * 0.01);
}

TEST(Presets, UnknownNameIsALocatedErrorWithSuggestion) {
  try {
    sceneFromText(pendulum("{t_end: 1, preset: acurate}"));
    FAIL() << "expected an InputError";
  } catch (const fc::InputError& e) {
    EXPECT_EQ(e.file(), "test.yaml");
    EXPECT_EQ(e.line(), 9);  // the `simulation:` line (the text starts with a newline)
    EXPECT_EQ(e.keyPath(), "simulation.preset");
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown preset 'acurate'"), std::string::npos) << what;
    EXPECT_NE(what.find("did you mean 'accurate'"), std::string::npos) << what;
    EXPECT_NE(what.find("expected fast or accurate"), std::string::npos) << what;
  }
  EXPECT_THROW(sceneFromText(pendulum("{t_end: 1, preset: [fast]}")), fc::InputError);
}

// Largest distance of the rod's centre from the RK4 solution of the 1-DOF
// pendulum over the run; also returns the number of steps taken.
double pendulumError(const std::string& preset, long* steps) {
  const Results r = simulate(sceneFromText(pendulum("{t_end: 3, output_step: 0.05, preset: " + preset + "}")),
                             {true});
  EXPECT_EQ(r.status, "completed");
  const double m = 1.0, L = 1.0, d = 0.02, g = 9.81;
  // Solid cylinder about a transverse axis through its end.
  const double I_pivot = m * L * L / 3.0 + m * d * d / 16.0;
  auto f = [&](double, const Eigen::VectorXd& y) {
    Eigen::VectorXd dy(2);
    dy << y(1), m * g * 0.5 * L * std::cos(y(0)) / I_pivot;  // phi: angle below horizontal
    return dy;
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2);
  double t = 0.0, worst = 0.0;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    // RK4 at h = 1e-4 s: global error ~ (h w)^4 ~ 1e-14 rad, w ~ 5 rad/s.
    const int n = static_cast<int>(std::lround((r.time[k] - t) / 1e-4));
    if (n > 0) y = rk4(f, y, t, r.time[k], n);
    t = r.time[k];
    const Eigen::Vector3d c(0.5 * L * std::cos(y(0)), 0.0, -0.5 * L * std::sin(y(0)));
    worst = std::max(worst, (r.position[1][k] - c).norm());
  }
  *steps = r.steps;
  return worst;
}

TEST(Presets, AccurateCostsMoreStepsAndIsMoreAccurateThanFast) {
  long steps_fast = 0, steps_accurate = 0;
  const double e_fast = pendulumError("fast", &steps_fast);
  const double e_accurate = pendulumError("accurate", &steps_accurate);
  std::printf("[   info   ] pendulum 3 s: fast %.2e m in %ld steps, accurate %.2e m in %ld steps\n", e_fast,
              steps_fast, e_accurate, steps_accurate);
  // A 5th-order method's step scales as rtol^(1/5): 1000x tighter tolerance,
  // ~4x the steps (at least 2x leaves room for the step controller's start).
  EXPECT_GT(steps_accurate, 2 * steps_fast);
  // Global error of a tolerance-controlled solver is a modest multiple of
  // rtol times the scale (0.5 m, ~3 swings): bounds at 10x rtol.
  EXPECT_LT(e_fast, 10 * 1e-4);
  EXPECT_LT(e_accurate, 10 * 1e-7);
  EXPECT_LT(e_accurate, e_fast);
}

}  // namespace
}  // namespace fc::mbs::test
