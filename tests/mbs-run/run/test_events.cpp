// Events act at the right time:
// - lock at t = 0.3 and release at 0.6: the pendulum stops where the free
//   pendulum (RK4 of theta'' = -(3g/2L) sin theta, from the minimal
//   coordinate) is at 0.3, stays there, then falls again from rest;
// - a joint-angle crossing of a rotor spinning at constant rate (angle = w t
//   exactly, no forces) is located at t = angle / w to machine precision;
// - enabling a force element at a time starts its effect there.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

const std::string kPendulum = testScene("ground_and_rod.yaml") + R"(joints:
  - {name: R, type: revolute, bodies: [ground, arm], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {name: g, type: gravity, g: [0, 0, -9.81]}
)";

// Minimal coordinate: angle beta about +y from the horizontal start, the rod
// (m = 1, L = 1, d = 0.01) pivoting at one end: I_o beta'' = m g (L/2) cos(beta)
// (a +y rotation lowers the tip, so gravity makes beta grow), with
// I_o = m (3 r^2 + L^2) / 12 + m (L/2)^2 including the rod's thickness.
Eigen::VectorXd pendulum(double, const Eigen::VectorXd& y) {
  const double r = 0.005, Io = (3 * r * r + 1.0) / 12 + 0.25;
  Eigen::VectorXd d(2);
  d << y[1], 9.81 * 0.5 * std::cos(y[0]) / Io;
  return d;
}

TEST(Events, LockAndReleaseAtTheirTimes) {
  const Results r = simulate(sceneFromText(std::string(kPendulum) + R"(
events:
  - {time: 0.3, lock: [R]}
  - {time: 0.6, release: [R]}
simulation: {t_end: 0.8, output_step: 0.01, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  auto f = pendulum;
  Eigen::VectorXd y0(2);
  y0 << 0.0, 0.0;
  const Eigen::VectorXd at_lock = rk4(f, y0, 0.0, 0.3, 3000);
  const double locked = r.joint_angle[0][rowAt(r.time, 0.3)];
  std::printf("[   info   ] angle at lock %.12f, free pendulum at 0.3 s %.12f\n", locked, at_lock[0]);
  // rtol 1e-10 and RK4 at h = 1e-4 (error ~1e-14): 1e-8 rad.
  EXPECT_NEAR(locked, at_lock[0], 1e-8);
  for (double t : {0.35, 0.45, 0.6}) EXPECT_NEAR(r.joint_angle[0][rowAt(r.time, t)], locked, 1e-9) << t;
  // Released at rest from `locked`: compare with the free pendulum from there.
  Eigen::VectorXd y1(2);
  y1 << locked, 0.0;
  const Eigen::VectorXd after = rk4(f, y1, 0.6, 0.8, 2000);
  EXPECT_NEAR(r.joint_angle[0].back(), after[0], 1e-8);
  ASSERT_EQ(r.event_log.size(), 2u);
}

TEST(Events, AngleCrossingIsLocatedAccurately) {
  const Results r = simulate(sceneFromText(testScene("ground_and_rotor.yaml") + R"(    angular_velocity: [0, 2.0, 0]
joints:
  - {name: R, type: revolute, bodies: [ground, rotor], points: [[0,0,0],[0,0,0]], axes: [[0,1,0],[0,1,0]]}
events:
  - {joint: R, angle: 1.234, direction: rising, lock: [R]}
simulation: {t_end: 1.0, output_step: 0.05, rtol: 1.0e-9}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  ASSERT_EQ(r.event_log.size(), 1u);
  const double t_event = std::stod(r.event_log[0].substr(2));
  std::printf("[   info   ] crossing event: %s (exact t = %.9f)\n", r.event_log[0].c_str(), 1.234 / 2.0);
  // Bisection on the dense output to machine precision in time; the dense
  // output itself is exact here (angle linear in t), so 1e-9 is generous.
  EXPECT_NEAR(t_event, 0.617, 1e-9);
  // Locked at the crossing: the angle holds 1.234 to the dense output accuracy.
  EXPECT_NEAR(r.joint_angle[0].back(), 1.234, 1e-8);
  EXPECT_NEAR(r.joint_angle[0][rowAt(r.time, 0.6)], 1.2, 1e-8);  // before: free rotation at 2 rad/s
}

TEST(Events, ForceEnabledAtItsTime) {
  // Gravity starts disabled and is enabled at 0.5 s: the arm rests until then.
  std::string scene = kPendulum;
  scene.replace(scene.find("gravity, g"), 10, "gravity, enabled: false, g");
  const Results r = simulate(sceneFromText(scene + R"(
events:
  - {time: 0.5, enable: [g]}
simulation: {t_end: 0.7, output_step: 0.01, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  EXPECT_NEAR(r.joint_angle[0][rowAt(r.time, 0.5)], 0.0, 1e-12);
  // 0.2 s of fall from rest: the free pendulum angle.
  auto f = pendulum;
  Eigen::VectorXd y0(2);
  y0 << 0.0, 0.0;
  EXPECT_NEAR(r.joint_angle[0].back(), rk4(f, y0, 0, 0.2, 2000)[0], 1e-8);
}

}  // namespace
}  // namespace fc::mbs::test
