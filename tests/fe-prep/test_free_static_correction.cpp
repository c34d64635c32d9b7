// The static correction of a free body (inertia relief) in a run:
// a 2 m steel rod floating free (no joints, no gravity) pushed by a 1 N step
// force across its tip. Its elastic tip deflection (in the body frame) settles,
// with critical modal damping, at the inertia-relief static deflection F c,
// c = L^3/(105 EI) + 2L/(15 kappa GA) (+ rotary inertia; the closed form of
// test_residual_flexibility.cpp), which 2 free modes miss by 16 % and 2 modes
// plus the correction hold; undamped, its peak converges with modes to the
// linear superposition of all 240 elastic modes of the model,
// sum_j s_j^2 F / lambda_j (1 - cos omega_j t).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "common/flexbody.h"
#include "common/input.h"
#include "feprep_test_support.h"
#include "mbs-run/scene/scene.h"
#include "mbs-run/run/simulation.h"

namespace fc::feprep::test {
namespace {

std::string freeRod(const std::string& modes) {
  std::string y = steelCantileverYaml(modes);
  y.replace(y.find("reference: {clamp: [root]}"), 26, "reference: free");
  return y;
}

struct Response {
  std::vector<double> time, tip;  // elastic tip deflection along body y [m]
  double angle = 0.0;             // rotation about z at the end [rad]
  std::string status;
};

Response push(const FlexBody& body, const std::string& tag, double damping, double t_end, double step) {
  const std::string path = scratchDir("free-correction-" + tag) + "/rod.h5";
  Provenance p;
  p.inputs_sha256 = std::string(64, '0');
  writeFlexBody(path, body, computeInertiaInvariants(body), p);
  char scene[1024];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: rod, flexible: {file: %s, modes: all, damping_ratio: %g}}
forces:
  - {type: force, body: rod, point: tip, force: [0, 1.0, 0]}
simulation: {t_end: %g, output_step: %g, rtol: 1.0e-9, integrator: imex}
)",
                path.c_str(), damping, t_end, step);
  const mbs::Model model = mbs::parseScene(InputNode::loadString(scene, tag + "-scene.yaml"));
  const mbs::Results r = mbs::simulate(model, {true});
  Response out;
  out.status = r.status;
  out.time = r.time;
  const Eigen::VectorXd sy = body.interface("tip").shapes.col(1);
  for (const Eigen::VectorXd& q : r.modal[0]) out.tip.push_back(sy.dot(q));
  const Eigen::Vector4d e = r.orientation[0].back();
  out.angle = 2 * std::atan2(e(3), e(0));
  return out;
}

TEST(FreeStaticCorrection, FreeRodUnderAStepForceSettlesAtTheInertiaReliefDeflection) {
  const BuildResult all = runYaml(freeRod("240"));
  const FlexBody& full = all.body;
  const Eigen::VectorXd sy = full.interface("tip").shapes.col(1);
  const double c = (sy.array().square() / full.eigenvalues.array()).sum();  // the model's inertia-relief compliance
  std::printf("[   info   ] free rod: inertia-relief tip compliance of the model %.9e m/N\n", c);
  struct Basis {
    const char* label;
    std::string modes;
  };
  const std::vector<Basis> bases = {{"2 modes", "2"},
                                    {"2 modes + correction", "{count: 2, static_correction: [tip]}"},
                                    {"4 modes", "4"},
                                    {"4 modes + correction", "{count: 4, static_correction: [tip]}"},
                                    {"12 modes", "12"},
                                    {"48 modes", "48"}};
  // The linear superposition of all 240 modes on the output times (undamped).
  const double t_peak = 0.1, dt = 1e-4;
  double ref_peak = 0;
  for (double t = 0; t <= t_peak + 1e-12; t += dt) {
    const double w = (sy.array().square() / full.eigenvalues.array() *
                      (1 - (full.eigenvalues.array().sqrt() * t).cos())).sum();
    ref_peak = std::max(ref_peak, w);
  }
  std::printf("[   info   ] undamped peak over %.2f s, superposition of all 240 modes: %.6e m (%.4f x static)\n", t_peak,
              ref_peak, ref_peak / c);
  std::vector<double> settled_error, peak_error;  // relative to c and to the superposition's peak
  for (std::size_t i = 0; i < bases.size(); ++i) {
    const Basis& b = bases[i];
    const BuildResult br = runYaml(freeRod(b.modes));
    const Response settled = push(br.body, "settle-" + std::to_string(i), 1.0, 0.3, 0.05);
    const Response peak = push(br.body, "peak-" + std::to_string(i), 0.0, t_peak, dt);
    ASSERT_EQ(settled.status, "completed");
    ASSERT_EQ(peak.status, "completed");
    // The force is global: the body turned by `angle`, its y component is cos(angle).
    const double s = settled.tip.back() / (c * std::cos(settled.angle));
    double p = 0;
    for (double w : peak.tip) p = std::max(p, w);
    std::printf("[   info   ] %-22s %2d shapes: settled %.6e m (%+.2e, turned %.2e rad), undamped peak %.6e m (%+.2e)\n",
                b.label, br.body.modeCount(), settled.tip.back(), s - 1, settled.angle, p, p / ref_peak - 1);
    settled_error.push_back(s - 1);
    peak_error.push_back(p / ref_peak - 1);
  }
  // Settled: the corrected bases hold the inertia-relief deflection. Left: the
  // critically damped response lags the turning load by ~2/omega_1 (14 ms),
  // when cos(angle) was larger by sin(angle) alpha t 2/omega_1 = 7e-5
  // (measured +5.7e-5; 48 modes, which miss 4e-5 of the deflection, +1.5e-5):
  // 2e-4. Without the correction 2 modes miss 16 %, 4 modes 5 %.
  EXPECT_LT(std::abs(settled_error[1]), 2e-4);
  EXPECT_LT(std::abs(settled_error[3]), 2e-4);
  EXPECT_LT(settled_error[0], -0.1);
  EXPECT_LT(settled_error[2], -0.03);
  // Undamped peak: mbs-run with 48 modes is the linear superposition (the
  // floating frame's nonlinear terms, omega^2 ~ 1e-3 against lambda_1 = 2e4,
  // and rtol 1e-9: measured 1.7e-5): 2e-4. The correction brings the low
  // counts closer to it (2 modes -13.6 % -> +2.8 %, 4 modes -3.1 % -> +0.46 %;
  // the correction shapes' frequencies are upper bounds, so it overshoots).
  EXPECT_LT(std::abs(peak_error[5]), 2e-4);
  EXPECT_LT(std::abs(peak_error[1]), std::abs(peak_error[0]) / 3);
  EXPECT_LT(std::abs(peak_error[3]), std::abs(peak_error[2]) / 3);
}


}  // namespace
}  // namespace fc::feprep::test
