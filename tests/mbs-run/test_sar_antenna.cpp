// The rigid SAR antenna (reference scene v1, tests/data/sar, 12 bodies, 3 redundant
// constraint equations, a toggle position of the B7/B8 knee) through phase 1:
// it must run without special-casing, reach the aligned knee at a time
// comparable to the paper's 5.5 s (Neto et al. 2006, sec. 4.4), hold the
// constraints and the energy balance. The full 20 s run is in bench/ and the
// example (docs/mbs-run.md).
#include <gtest/gtest.h>

#include <cmath>

#include "mbs-run/scene/scene.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs {
namespace {

TEST(SarAntenna, PhaseOneReachesAlignmentThroughTheToggle) {
  Model m = loadScene(std::string(FLEXCOMP_DATA_DIR) + "/sar/sar-rigid-scene-v1.yaml");
  m.settings.t_end = 7.0;
  const Results r = simulate(m, {true});
  ASSERT_EQ(r.status, "completed");
  const int R3 = m.jointIndex("R3");
  std::size_t k_min = 0;
  for (std::size_t k = 0; k < r.time.size(); ++k)
    if (std::abs(r.joint_angle[R3][k]) < std::abs(r.joint_angle[R3][k_min])) k_min = k;
  std::printf("[   info   ] SAR phase 1: R3 closest to alignment %.4f rad at t = %.2f s (paper 5.5 s); violation %.2e; "
              "energy balance error %.2e J; %ld steps\n",
              r.joint_angle[R3][k_min], r.time[k_min], r.max_violation, r.energy_balance_error, r.steps);
  // Starts folded at 3.050 rad (reconstructed geometry) and reaches alignment.
  EXPECT_NEAR(r.joint_angle[R3][0], 3.050287, 1e-6);
  EXPECT_LT(std::abs(r.joint_angle[R3][k_min]), 0.01);
  // "Comparable to 5.5 s": the reconstruction's differences (folded angle
  // 3.050 vs 3.12 rad, assumed inertias) justify +-25 %.
  EXPECT_GT(r.time[k_min], 5.5 * 0.75);
  EXPECT_LT(r.time[k_min], 5.5 * 1.25);
  // Constraints held through the singular position and energy balanced (the
  // actuator's potential, damping) to well below the 6 J in motion.
  EXPECT_LT(r.max_violation, 1e-7);
  EXPECT_LT(r.energy_balance_error, 0.01);
  // R1 is locked in phase 1.
  EXPECT_NEAR(r.joint_angle[m.jointIndex("R1")].back(), -3.130169, 1e-6);
}

}  // namespace
}  // namespace fc::mbs
