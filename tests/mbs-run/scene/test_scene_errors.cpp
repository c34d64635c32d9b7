// Bad scenes end with one InputError naming the file, the line, the key and
// what was expected (contracts.md, "Errors").
#include <gtest/gtest.h>

#include <string>

#include "helpers.h"
#include "mbs-run/run/run_policy.h"

namespace fc::mbs::test {
namespace {

const std::string kHead = R"(bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: arm
    rod: {length: 1.0, diameter: 0.01, mass: 1.0}
)";  // lines 1-4

struct Expect {
  int line;
  std::string key, words;
};

void expectError(const std::string& yaml, const Expect& e) {
  try {
    sceneFromText(yaml);
    FAIL() << "no error for:\n" << yaml;
  } catch (const fc::InputError& err) {
    EXPECT_EQ(err.file(), "test.yaml");
    EXPECT_EQ(err.line(), e.line) << err.what();
    EXPECT_NE(err.keyPath().find(e.key), std::string::npos) << err.what();
    EXPECT_NE(std::string(err.what()).find(e.words), std::string::npos) << err.what();
  }
}

const std::string kSim = "simulation: {t_end: 1.0}\n";

TEST(SceneErrors, UnknownJointTypeWithSuggestion) {
  expectError(kHead + "joints:\n  - {name: J, type: revolut, bodies: [ground, arm], points: [[0,0,0],[0,0,0]]}\n" + kSim,
              {6, "joints[0].type", "did you mean 'revolute'"});
}
TEST(SceneErrors, UnknownBodyInJoint) {
  expectError(kHead + "joints:\n  - {name: J, type: spherical, bodies: [ground, amr], points: [[0,0,0],[0,0,0]]}\n" + kSim,
              {6, "joints[0].bodies[1]", "unknown body 'amr'"});
}
TEST(SceneErrors, NamesThatAreNotResultsGroups) {
  // A joint named "." once failed only when the results file made /joints/. (fuzz
  // campaign, other seeds): names are HDF5 group names and are checked at their key.
  for (const char* bad : {"\".\"", "\"..\"", "\"a/b\"", "\"\""})
    expectError(kHead + "joints:\n  - {name: " + bad + ", type: spherical, bodies: [ground, arm], points: [[0,0,0],[0,0,0]]}\n" + kSim,
                {6, "joints[0].name", "usable as a results group"});
  expectError("bodies:\n  - {name: x/y, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}}\n" + kSim,
              {2, "bodies[0].name", "usable as a results group"});
}
TEST(SceneErrors, GravityBeyondPhysicalRange) {
  // Fuzz campaign, seeds +200: g = 1e300 ran, then failed writing an infinite peak reaction.
  expectError(kHead + "forces:\n  - {type: gravity, g: [0, 0, -1e300]}\n" + kSim,
              {6, "forces[0].g", "within 1e6 m/s^2"});
}
TEST(SceneErrors, SpringDampersBeyondPhysicalRange) {
  // Fuzz campaign (session 6): a damping of 1.7e308 ran and stopped with a
  // non-finite state; it is an input error at its key.
  const std::string joint =
      "joints:\n  - {name: R, type: revolute, bodies: [ground, arm], points: [[0,0,0],[-0.5,0,0]], axes: [[0,0,1],[0,0,1]]}\n";
  expectError(kHead + joint + "forces:\n  - {type: rotational_spring_damper, joint: R, damping: 1.7e308}\n" + kSim,
              {8, "forces[0].damping", "N m s/rad"});
  expectError(kHead + "forces:\n  - {type: translational_spring_damper, bodies: [ground, arm], points: [[0,0,0],[0.5,0,0]], "
                      "stiffness: 1e20, free_length: 0}\n" + kSim,
              {6, "forces[0].stiffness", "N/m"});
  expectError(kHead + "forces:\n  - {type: translational_spring_damper, bodies: [ground, arm], points: [[0,0,0],[0.5,0,0]], "
                      "stiffness: 10, damping: 1e13, free_length: 0}\n" + kSim,
              {6, "forces[0].damping", "N s/m"});
}
TEST(SceneErrors, VectorsBeyondPhysicalRange) {
  // Fuzz campaign on the new keys (session 6): a 1e300 N force ran and then failed
  // writing an infinite peak reaction (an error naming no key); a body 1e9 m from
  // its joint integrated for ever. Every scene vector is bounded in SI units.
  expectError(kHead + "forces:\n  - {type: force, body: arm, force: [0, 1e300, 0]}\n" + kSim,
              {6, "forces[0].force", "within 1e12 N"});
  expectError(kHead + "forces:\n  - {type: torque, body: arm, torque: [-1e13, 0, 0]}\n" + kSim,
              {6, "forces[0].torque", "within 1e12 N m"});
  expectError(kHead + "    position: [0, 1e9, 0]\n" + kSim, {5, "bodies[1].position", "within 1e6 m"});
  expectError(kHead + "    angular_velocity: [0, 0, 1e7]\n" + kSim, {5, "bodies[1].angular_velocity", "within 1e6 rad/s"});
  expectError(kHead + "joints:\n  - {name: J, type: spherical, bodies: [ground, arm], points: [[0,0,0],[0,0,-1.7e308]]}\n" +
                  kSim,
              {6, "joints[0].points[1]", "within 1e6 m"});
}
TEST(SceneErrors, DistancePairListedTwice) {
  // Each pair is one results group: a repeat failed only when the file was written.
  const std::string two = R"(  - {name: other, rod: {length: 1.0, diameter: 0.01, mass: 1.0}, position: [0, 1, 0]}
)";
  expectError(kHead + two + "outputs: {distances: [[arm, other], [other, arm]]}\n" + kSim,
              {6, "outputs.distances[1]", "listed twice"});
}
TEST(SceneErrors, KeyWithoutAValue) {
  // `max_step:` with nothing after it used to read as absent: the default was
  // taken silently (fuzz: fe-prep's `static_correction: null`). An empty list
  // (`events:`) stays an empty list.
  expectError(kHead + "simulation: {t_end: 1.0, max_step: }\n", {5, "simulation.max_step", "without a value"});
  expectError(kHead + "simulation:\n  t_end: 1.0\n  rtol: ~\n", {7, "simulation.rtol", "without a value"});
  EXPECT_NO_THROW(sceneFromText(kHead + "events:\nforces:\n" + kSim));
}
TEST(SceneErrors, MissingMass) {
  expectError("bodies:\n  - name: b\n    rigid: {inertia: [[1,0,0],[0,1,0],[0,0,1]]}\n" + kSim,
              {3, "bodies[0].rigid", "mass"});
}
TEST(SceneErrors, NegativeMass) {
  expectError("bodies:\n  - name: b\n    rigid: {mass: -2, inertia: [[1,0,0],[0,1,0],[0,0,1]]}\n" + kSim,
              {3, "bodies[0].rigid.mass", "positive"});
}
TEST(SceneErrors, NonUnitEulerParameters) {
  expectError(kHead + "    orientation: [1, 1, 0, 0]\n" + kSim, {5, "bodies[1].orientation", "unit Euler parameters"});
}
TEST(SceneErrors, FlexibleBodyFileMissing) {
  expectError("bodies:\n  - name: p\n    flexible: {file: no-such-panel.h5, modes: 4}\n" + kSim,
              {3, "bodies[0].flexible.file", "flexible body file"});
}
TEST(SceneErrors, InterfaceNameOnRigidBody) {
  expectError(kHead + "joints:\n  - {name: J, type: spherical, bodies: [ground, arm], points: [[0,0,0], S1]}\n" + kSim,
              {6, "joints[0].points[1]", "is rigid"});
}
TEST(SceneErrors, TorqueTableNotIncreasing) {
  expectError(kHead +
                  "joints:\n  - {name: R, type: revolute, bodies: [ground, arm], points: [[0,0,0],[0,0,0]], axes: [[0,1,0],[0,1,0]]}\n"
                  "forces:\n  - {type: rotational_spring_damper, joint: R, torque: {angle: [0.2, -0.2], value: [1, 2]}}\n" +
                  kSim,
              {8, "forces[0].torque.angle", "increasing"});
}
TEST(SceneErrors, EventNamesUnknownElement) {
  expectError(kHead + "events:\n  - {time: 1.0, enable: [nothing]}\n" + kSim, {6, "events[0].enable[0]", "'nothing'"});
}
TEST(SceneErrors, UnknownKeyWithSuggestion) {
  expectError(kHead + "simulation: {t_end: 1.0, rtoll: 1e-6}\n", {5, "simulation", "rtol"});
}
TEST(SceneErrors, MissingSimulationBlock) {
  expectError(kHead, {1, "simulation", "simulation"});
}
TEST(SceneErrors, BadIntegratorName) {
  expectError(kHead + "simulation: {t_end: 1.0, integrator: rk4}\n", {5, "simulation.integrator", "dopri5"});
}

TEST(SceneErrors, SharedSarSceneParses) {
  // The v1 reference scene (tests/data/sar) is valid input as distributed.
  const Model m = loadScene(std::string(FLEXCOMP_DATA_DIR) + "/sar/sar-rigid-scene-v1.yaml");
  EXPECT_EQ(m.bodies.size(), 12u);
  EXPECT_EQ(m.joints.size(), 20u);
  EXPECT_EQ(m.nv, 66);
  EXPECT_EQ(runPolicy(m).integrator, IntegratorKind::DormandPrince);
}

}  // namespace
}  // namespace fc::mbs::test
