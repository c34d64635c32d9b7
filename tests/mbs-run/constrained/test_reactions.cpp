// /joints/NAME/reaction_torque (contracts.md) against statics: a rigid beam
// held at one end by a joint that must carry the moment of its weight, and a
// locked revolute holding a spring torque. In each the bodies stay at rest,
// so the reactions are the equilibrium values, known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/flexbody.h"
#include "flexible/random_body.h"
#include "helpers.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

constexpr double kMass = 2.0, kLength = 1.5, kG = 9.81;

// Ground, then a beam of length L along +x from the joint at the origin,
// under gravity -z; `joint` is the joint's YAML after its name.
std::string cantilever(const std::string& joint, bool beam_first = false) {
  char s[1024];
  const char* bodies = beam_first ? "[beam, ground]" : "[ground, beam]";
  const char* points = beam_first ? "[[-0.75,0,0],[0,0,0]]" : "[[0,0,0],[-0.75,0,0]]";
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: beam, rod: {length: %g, diameter: 0.02, mass: %g}, position: [%g, 0, 0]}
joints:
  - {name: J, bodies: %s, points: %s, %s}
forces:
  - {type: gravity, g: [0, 0, %g]}
simulation: {t_end: 0.5, output_step: 0.1, rtol: 1.0e-8}
)",
                kLength, kMass, kLength / 2, bodies, points, joint.c_str(), -kG);
  return s;
}

// Every output row: force and torque on the first body equal `force`, `torque`.
// Tolerance: the multipliers solve the acceleration equations to a 1e-10
// residual (system.cpp) and the beam drifts by less than the 1e-11 m atol,
// so 1e-7 relative covers both with margin.
void expectReactions(const Results& r, const Eigen::Vector3d& force, const Eigen::Vector3d& torque) {
  ASSERT_EQ(r.status, "completed");
  ASSERT_EQ(r.time.size(), 6u);
  const double tol = 1e-7 * kMass * kG * kLength;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    EXPECT_LT((r.reaction[0][i] - force).norm(), tol) << "row " << i << ": " << r.reaction[0][i].transpose();
    EXPECT_LT((r.reaction_torque[0][i] - torque).norm(), tol)
        << "row " << i << ": " << r.reaction_torque[0][i].transpose();
  }
}

// The joint holds the beam's weight m g and its moment about the joint,
// (L/2 x) x (-m g z) = m g L/2 y on the beam's side; on the ground (first
// body) the opposite: force -m g z, torque +m g L/2 y.
class CantileverJoint : public ::testing::TestWithParam<const char*> {};

TEST_P(CantileverJoint, CarriesTheWeightMoment) {
  const Results r = simulate(sceneFromText(cantilever(GetParam())), {true});
  expectReactions(r, Eigen::Vector3d(0, 0, -kMass * kG), Eigen::Vector3d(0, kMass * kG * kLength / 2, 0));
}

// A fixed joint in place, a revolute about the vertical (the weight's moment is
// about the perpendicular y axis), and joints free along or about the beam's
// own axis x, where the weight has no component or moment.
INSTANTIATE_TEST_SUITE_P(Statics, CantileverJoint,
                         ::testing::Values("type: fixed",
                                           "type: revolute, axes: [[0,0,1],[0,0,1]]",
                                           "type: prismatic, axes: [[1,0,0],[1,0,0]]",
                                           "type: cylindrical, axes: [[1,0,0],[1,0,0]]"));

// With the beam as the first body the file holds the reaction on the beam,
// about the joint's point on the beam (its root, L/2 from the beam's frame
// origin): +m g z and -m g L/2 y.
TEST(ReactionTorque, OnTheFirstBodyAboutTheJointPoint) {
  const Results r = simulate(sceneFromText(cantilever("type: fixed", true)), {true});
  expectReactions(r, Eigen::Vector3d(0, 0, kMass * kG), Eigen::Vector3d(0, -kMass * kG * kLength / 2, 0));
}

// A locked revolute about y holding a constant spring torque M (no gravity):
// the spring applies +M y on the ground and -M y on the beam, so the joint
// applies +M y on the beam and -M y on the ground; no force.
TEST(ReactionTorque, LockedRevoluteHoldsASpringTorque) {
  const double M = 2.5;
  char s[1024];
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: beam, rod: {length: %g, diameter: 0.02, mass: %g}, position: [%g, 0, 0]}
joints:
  - {name: J, type: revolute, bodies: [ground, beam], points: [[0,0,0],[-0.75,0,0]], axes: [[0,1,0],[0,1,0]],
     locked: true}
forces:
  - {name: spring, type: rotational_spring_damper, joint: J, torque: {angle: [-1, 1], value: [%g, %g]}}
simulation: {t_end: 0.5, output_step: 0.1, rtol: 1.0e-8}
)",
                kLength, kMass, kLength / 2, M, M);
  const Results r = simulate(sceneFromText(s), {true});
  expectReactions(r, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, -M, 0));
}

// A spherical joint transmits no moment: its torque about the joint point is
// zero (and no reaction_torque dataset is written for it, results.cpp).
TEST(ReactionTorque, SphericalJointTransmitsNone) {
  std::string scene = cantilever("type: spherical");
  // Held also at the tip by a second spherical joint, the beam is a simply
  // supported span: each end carries m g / 2 and no moment.
  scene.replace(scene.find("forces:"), 0,
                "  - {name: tip, type: spherical, bodies: [ground, beam], points: [[1.5,0,0],[0.75,0,0]]}\n");
  const Results r = simulate(sceneFromText(scene), {true});
  ASSERT_EQ(r.status, "completed");
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    EXPECT_LT(r.reaction_torque[0][i].norm(), 1e-7 * kMass * kG * kLength);
    EXPECT_NEAR(r.reaction[0][i].z() + r.reaction[1][i].z(), -kMass * kG, 1e-7 * kMass * kG);
  }
}

// The run's peaks (summary and root attributes) are those of its rows.
TEST(RunPeaks, AreTheLargestRowValues) {
  const Results r = simulate(sceneFromText(cantilever("type: fixed")), {true});
  ASSERT_EQ(r.status, "completed");
  EXPECT_EQ(r.peak_reaction_torque.where, "J");
  EXPECT_NEAR(r.peak_reaction_torque.value, kMass * kG * kLength / 2, 1e-7 * kMass * kG * kLength);
  EXPECT_NEAR(r.peak_reaction_force.value, kMass * kG, 1e-7 * kMass * kG);
  double worst = 0.0;
  for (double v : r.violation) worst = std::max(worst, v);
  EXPECT_EQ(r.peak_violation.value, worst);
  EXPECT_EQ(r.max_violation, worst);
}

// Nyquist: rows every output_step resolve frequencies up to 1/(2 output_step);
// a kept mode above that is aliased, and the run says so.
TEST(SamplingWarnings, OutputStepAgainstTheHighestKeptMode) {
  const std::string file =
      writeTempBody(fc::testing::randomBody(8, 3, 21, 0.4, 1.0, 3.0), "mbs_nyquist_21");
  auto scene = [&](double output_step) {
    char s[512];
    std::snprintf(s, sizeof s, R"(
bodies:
  - name: b
    flexible: {file: %s, modes: 3}
simulation: {t_end: 0.1, output_step: %.17g}
)",
                  file.c_str(), output_step);
    return sceneFromText(s);
  };
  const Model m = scene(1.0);
  const Eigen::VectorXd& w2 = m.bodies[0].flex->modal.stiffness;
  const double f_max = std::sqrt(w2.head(3).maxCoeff()) / (2 * M_PI);
  EXPECT_TRUE(samplingWarnings(scene(0.99 * 0.5 / f_max)).empty());
  const std::vector<std::string> w = samplingWarnings(scene(1.01 * 0.5 / f_max));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("body b"), std::string::npos) << w[0];
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace fc::mbs::test
