// Force elements and the remaining joint types against closed forms:
// - a slider on a prismatic joint held by a translational spring-damper:
//   x(t) = X e^{-zeta w t} cos(w_d t) + ... (damped oscillator, exact);
// - a rotor on a revolute joint under a constant torque: angle = tau t^2 / (2 I),
//   and the applied-work quadrature equals the kinetic energy;
// - a cylindrical joint: free spin and slide along the axis are independent
//   (constant rates, a constant force gives x = F t^2 / 2m);
// - a universal joint transmits rotation between perpendicular-crossing
//   shafts: a driven input shaft at constant speed gives the closed-form
//   Cardan output angle tan(out) = tan(in) cos(beta) for shafts at angle beta,
//   angles counted from the input yoke perpendicular to the shafts' plane.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

TEST(ForceElements, SpringDamperOnPrismaticJoint) {
  const double m = 2.0, k = 50.0, c = 1.0, x0 = 0.1;
  char s[2048];
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: slider
    rigid: {mass: %g, inertia: [[0.1,0,0],[0,0.1,0],[0,0,0.1]]}
    position: [%g, 0, 0]
joints:
  - {name: P, type: prismatic, bodies: [ground, slider], points: [[0,0,0],[0,0,0]], axes: [[1,0,0],[1,0,0]]}
forces:
  - {type: translational_spring_damper, bodies: [ground, slider], points: [[-1,0,0],[0,0,0]],
     stiffness: %g, damping: %g, free_length: 1.0}
simulation: {t_end: 3.0, output_step: 0.01, rtol: 1.0e-10}
)",
                m, x0, k, c);
  const Results r = simulate(sceneFromText(s), {true});
  ASSERT_EQ(r.status, "completed");
  const double w = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m)), wd = w * std::sqrt(1 - zeta * zeta);
  double worst = 0, dE = 0;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    const double t = r.time[i];
    const double x = x0 * std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
    worst = std::max(worst, std::abs(r.position[1][i].x() - x));
    dE = std::max(dE, std::abs(r.kinetic[i] + r.potential[i] + r.dissipated[i] - r.potential[0]));
    // The prismatic joint keeps the slider on the axis and unrotated.
    EXPECT_LT(r.position[1][i].tail<2>().norm(), 1e-9);
  }
  std::printf("[   info   ] damped slider: |x - closed form| %.2e m, energy balance %.2e J\n", worst, dE);
  EXPECT_LT(worst, 1e-8);  // rtol 1e-10 on x ~ 0.1 over ~3 periods
  EXPECT_LT(dE, 1e-8);
}

TEST(ForceElements, ConstantTorqueSpinsUpRotor) {
  const Results r = simulate(sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: rotor
    rigid: {mass: 3.0, inertia: [[0.3,0,0],[0,0.5,0],[0,0,0.3]]}
joints:
  - {name: R, type: revolute, bodies: [ground, rotor], points: [[0,0,0],[0,0,0]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {type: torque, body: rotor, torque: [0.3, 2.0, -0.1]}
simulation: {t_end: 2.0, output_step: 0.1, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  // Only the component along the axis acts: angle = 2.0 t^2 / (2 * 0.5).
  const double t = r.time.back();
  EXPECT_NEAR(r.joint_angle[0].back(), 2.0 * t * t, 1e-8);
  EXPECT_NEAR(r.applied_work.back(), r.kinetic.back(), 1e-8 * r.kinetic.back());
}

TEST(ForceElements, CylindricalJointSlidesAndSpinsIndependently) {
  const Results r = simulate(sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: sleeve
    rigid: {mass: 2.0, inertia: [[0.3,0,0],[0,0.2,0],[0,0,0.2]]}
    angular_velocity: [4.0, 0, 0]
joints:
  - {name: C, type: cylindrical, bodies: [ground, sleeve], points: [[0,0,0],[0,0,0]], axes: [[1,0,0],[1,0,0]]}
forces:
  - {type: force, body: sleeve, force: [1.0, 5.0, -3.0]}
simulation: {t_end: 1.5, output_step: 0.05, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  const double t = r.time.back();
  EXPECT_NEAR(r.position[1].back().x(), 0.5 * (1.0 / 2.0) * t * t, 1e-9);
  EXPECT_LT(r.position[1].back().tail<2>().norm(), 1e-9);
  EXPECT_NEAR(r.angular_velocity[1].back().x(), 4.0, 1e-9);
  EXPECT_LT(r.angular_velocity[1].back().tail<2>().norm(), 1e-9);
}

TEST(ForceElements, UniversalJointCardanLaw) {
  // Input shaft along x driven at 2 rad/s (revolute to ground about x); the
  // output shaft's axis is at beta = 30 deg in the x-y plane, held by a
  // revolute to ground; a cross (universal joint) connects them at the origin.
  const double beta = M_PI / 6;
  char s[2048];
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: input, rigid: {mass: 1, inertia: [[0.01,0,0],[0,0.02,0],[0,0,0.02]]}}
  - name: output
    rigid: {mass: 1, inertia: [[0.01,0,0],[0,0.02,0],[0,0,0.02]]}
    orientation: [%.17g, 0, 0, %.17g]
joints:
  - {name: Rin, type: revolute, bodies: [ground, input], points: [[0,0,0],[0,0,0]], axes: [[1,0,0],[1,0,0]],
     drive: {angle0: 0.0, speed: 2.0}}
  - {name: Rout, type: revolute, bodies: [ground, output], points: [[0,0,0],[0,0,0]],
     axes: [[%.17g, %.17g, 0],[1,0,0]]}
  - {name: U, type: universal, bodies: [input, output], points: [[0,0,0],[0,0,0]], axes: [[0,0,1],[0,1,0]]}
simulation: {t_end: 2.0, output_step: 0.02, rtol: 1.0e-10}
)",
                std::cos(beta / 2), std::sin(beta / 2), std::cos(beta), std::sin(beta));
  const Results r = simulate(sceneFromText(s), {true});
  ASSERT_EQ(r.status, "completed");
  double worst = 0;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    const double in = 2.0 * r.time[i];
    // Cardan: tan(out) = tan(in) cos(beta) (input yoke starts perpendicular to
    // the plane of the shafts), on the continuous branch.
    const double out = std::atan2(std::sin(in) * std::cos(beta), std::cos(in));
    worst = std::max(worst, std::abs(std::remainder(r.joint_angle[1][i] - out, 2 * M_PI)));
  }
  std::printf("[   info   ] Cardan joint: output angle error %.2e rad over 4 rad of input\n", worst);
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace fc::mbs::test
