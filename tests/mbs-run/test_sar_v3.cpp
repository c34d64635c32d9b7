// The rigid SAR antenna, reconstruction v3.1 (tests/data/sar/sar-rigid-scene-v3.yaml,
// copied from the project's shared reference folder; the figures checked here are
// those of tests/data/sar/sar-antenna-model-v3.md, "Changes from v2" and "The knee,
// the stop, the latch and the end of phase 1"), whole 30 s, with the margins
// monitor (outputs.margins, mbs-run/run/margins.h) on the V-coupler legs:
// - phase 1: the knee minimum (0.030 rad, 6.126 s), the coplanar stop's Newton
//   impact (6.2245 s, -0.925 -> +0.277 rad/s), the hinge-2/3 latch 0.01 rad
//   behind it (6.2604 s), the knee then held at 0.0867 rad;
// - phase 2: actuator B (the gentle drive) brings the cluster to the R1 latch
//   at 25.025 s at 0.105 rad/s; R1 stays at 0 after it;
// - margins: the legs' axial force from the reactions of their two end joints
//   projected on the leg axis, 59.5 N of tension (the start) and 5.0 N of
//   compression (19.4 s), 0.08 of their pinned Euler load pi^2 EI / L^2 = 64.9 N
//   (d 6 mm, E 159 GPa, L 1.24 m).
// The model file's figures were measured with an independent event-driven
// simulation of the same scene, which agrees with mbs-run to about 1e-6 s in
// every event time; the tolerances below are the model file's printed digits
// (half a unit of the last digit, rounded up to the next decade).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/input.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/scene/scene.h"

namespace fc::mbs {
namespace {

// The reference scene with the margins monitor added (the reference has no outputs key).
Model sceneWithMargins() {
  const std::string path = std::string(FLEXCOMP_DATA_DIR) + "/sar/sar-rigid-scene-v3.yaml";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  // EI of a solid 6-mm rod of E = 159 GPa: 159e9 * pi * 0.006^4 / 64 = 10.115 N m^2.
  text << "outputs: {margins: {beams: [{body: B11, EI: 10.1151, ends: pinned}, {body: B12, EI: 10.1151, ends: pinned}],"
          " joints: [R1, H23]}}\n";
  return parseScene(InputNode::loadString(text.str(), path));
}

TEST(SarAntennaV3, RigidModelAgainstTheReconstructionsFigures) {
  const Model m = sceneWithMargins();
  const Results r = simulate(m, {true});
  ASSERT_EQ(r.status, "completed");
  const int R3 = m.jointIndex("R3"), H23 = m.jointIndex("H23"), R1 = m.jointIndex("R1");
  const auto& t = r.time;
  const auto& knee = r.joint_angle[R3];
  const auto& hinge = r.joint_angle[H23];
  // Phase 1: one impact on the coplanar stop, then the latch.
  const auto& imp = r.limit_impacts[H23];
  ASSERT_EQ(imp.size(), 1u);
  std::size_t k_min = 0;
  for (std::size_t k = 0; k < t.size() && t[k] < imp[0][0]; ++k)
    if (knee[k] < knee[k_min]) k_min = k;
  ASSERT_EQ(r.margins.latches.size(), 2u);
  const auto& l23 = r.margins.latches[0];
  const auto& l1 = r.margins.latches[1];
  ASSERT_EQ(l23.joint, H23);
  ASSERT_EQ(l1.joint, R1);
  const std::size_t k10 = std::size_t(std::lround(9.99 / 0.01));
  std::printf("[   info   ] SAR v3 rigid: knee minimum %.4f rad at %.2f s; H23 stop at %.5f s, %.4f -> %.4f rad/s; "
              "latch H23 at %.5f s (%.4f rad/s), knee %.4f rad at 9.99 s; latch R1 at %.4f s at %.4f rad/s\n",
              knee[k_min], t[k_min], imp[0][0], imp[0][1], imp[0][2], l23.time, l23.rate, knee[k10], l1.time, l1.rate);
  EXPECT_NEAR(knee[k_min], 0.030, 0.0005);  // output rows 10 ms apart on a flat minimum
  EXPECT_NEAR(t[k_min], 6.126, 0.01);
  EXPECT_NEAR(imp[0][0], 6.2245, 1e-4);
  EXPECT_NEAR(imp[0][1], -0.925, 1e-3);
  EXPECT_NEAR(imp[0][2], 0.277, 1e-3);
  EXPECT_NEAR(l23.time, 6.2604, 1e-4);
  EXPECT_NEAR(l23.angle, 0.01, 1e-12);
  EXPECT_GT(l23.rate, 0.0);  // rising through the latch angle
  EXPECT_NEAR(knee[k10], 0.0867, 1e-3);
  // Phase 2: the R1 latch.
  EXPECT_NEAR(l1.time, 25.025, 1e-3);
  EXPECT_NEAR(l1.rate, 0.105, 1e-3);
  EXPECT_NEAR(r.joint_angle[R1].back(), 0.0, 1e-9);
  EXPECT_NEAR(hinge.back(), 0.01, 1e-6);
  // Margins of the legs: the Euler load in closed form, the extreme axial
  // forces at the output rows (10 ms) as the model file gives them.
  ASSERT_EQ(r.margins.beams.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const BeamMarginSpec& b = m.margin_beams[k];
    EXPECT_NEAR(b.length, 1.24, 1e-6);
    EXPECT_NEAR(b.euler_load, M_PI * M_PI * 10.1151 / (1.24 * 1.24), 1e-9);
    EXPECT_NEAR(b.euler_load, 64.9, 0.05);
    const auto& g = r.margins.beams[k];
    ASSERT_EQ(g.axial_compression.size(), t.size());
    // The model file's leg criterion is phase 2's (after the switch at 10 s):
    // tension 59.5 N at the start, compression 5.0 N at 19.4 s.
    double c2 = -1e300, t2 = 0.0, tension2 = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] <= 10.0) continue;
      if (g.axial_compression[i] > c2) c2 = g.axial_compression[i], t2 = t[i];
      tension2 = std::max(tension2, -g.axial_compression[i]);
    }
    std::printf("[   info   ] leg %s: phase 2 tension %.2f N, compression %.2f N at %.2f s (%.3f of %.2f N); whole run: "
                "compression %.2f N at %.2f s\n",
                m.bodies[b.body].name.c_str(), tension2, c2, t2, c2 / b.euler_load, b.euler_load, g.compression,
                g.compression_time);
    EXPECT_NEAR(tension2, 59.5, 0.05);
    EXPECT_NEAR(g.tension, tension2, 1e-12);  // the largest tension of the run is phase 2's start
    EXPECT_NEAR(c2, 5.0, 0.05);
    EXPECT_NEAR(t2, 19.4, 0.05);
    EXPECT_GE(g.compression, c2);
  }
  EXPECT_LT(r.max_violation, 1e-7);
  EXPECT_LT(r.energy_balance_error, 1e-4 * r.energy_scale);
}

}  // namespace
}  // namespace fc::mbs
