// Conservation laws nobody has to trust us for:
// - a torque-free asymmetric rigid body: kinetic energy and the global angular
//   momentum are constant (Euler's equations), over many tumbling periods,
//   including the unstable intermediate-axis flip (Dzhanibekov effect);
// - two free bodies linked by a spherical joint, with offset centres of mass:
//   total linear momentum, angular momentum about the fixed origin and energy
//   are constant (internal constraint forces cancel);
// - a conservative pendulum with a rotational spring over 100 s: energy
//   constant to the integrator tolerance, for both integrators.
#include <gtest/gtest.h>

#include <cmath>

#include "common/rotations.h"
#include "helpers.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

TEST(Conservation, TorqueFreeTumblingBody) {
  const Model m = sceneFromText(R"(
bodies:
  - name: brick
    rigid: {mass: 3.0, inertia: [[0.1, 0, 0], [0, 0.2, 0], [0, 0, 0.3]]}
    orientation: [0.9, 0.3, 0.2, 0.24494897427831783]
    velocity: [0.5, -0.2, 0.1]
    angular_velocity: [0.01, 5.0, 0.02]
simulation: {t_end: 20.0, output_step: 0.05, rtol: 1.0e-9}
)");
  const Results r = simulate(m, {true});
  ASSERT_EQ(r.status, "completed");
  const Eigen::Matrix3d J = Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal();
  Eigen::Vector3d H0 = Eigen::Vector3d::Zero();
  double dH = 0, dE = 0, flip = 1;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const Eigen::Matrix3d A = fc::rotationMatrix(r.orientation[0][k]);
    const Eigen::Vector3d wb = A.transpose() * r.angular_velocity[0][k];
    const Eigen::Vector3d H = A * J * wb;
    if (k == 0) H0 = H;
    dH = std::max(dH, (H - H0).norm());
    dE = std::max(dE, std::abs(r.kinetic[k] - r.kinetic[0]));
    flip = std::min(flip, wb.y() / 5.0);
    // Free flight of the centre of mass.
    EXPECT_NEAR((r.position[0][k] - r.time[k] * Eigen::Vector3d(0.5, -0.2, 0.1)).norm(), 0.0, 1e-9);
  }
  std::printf("[   info   ] tumbling body: |dH| %.3e of %.3g, |dT| %.3e of %.3g\n", dH, H0.norm(), dE, r.kinetic[0]);
  EXPECT_LT(flip, -0.5);  // it did flip about the intermediate axis: a demanding motion
  // rtol 1e-9 over 20 s (several flips, each amplifying errors): 1e-7 relative.
  EXPECT_LT(dH, 1e-7 * H0.norm());
  EXPECT_LT(dE, 1e-7 * r.kinetic[0]);
}

TEST(Conservation, JointedFreeBodiesKeepMomentum) {
  const Model m = sceneFromText(R"(
bodies:
  - name: a
    rigid: {mass: 2.0, center_of_mass: [0.1, 0.05, 0], inertia: [[0.05, 0.01, 0], [0.01, 0.08, 0], [0, 0, 0.1]]}
    velocity: [0.3, 0.1, 0]
    angular_velocity: [1.0, 2.0, 0.5]
  - name: b
    rod: {length: 0.8, diameter: 0.05, mass: 1.0}
    position: [0.8, 0.0, 0.0]
    orientation: [0.9238795325112867, 0, 0, 0.3826834323650898]
    velocity: [0.0, 0.0, 0.0]
    angular_velocity: [0, 0, 0]
joints:
  - {name: s, type: spherical, bodies: [a, b], points: [[0.4, 0, 0], [-0.4, 0, 0]]}
simulation: {t_end: 10.0, output_step: 0.02, rtol: 1.0e-9}
)");
  const Results r = simulate(m, {true});
  ASSERT_EQ(r.status, "completed");
  const double ma = 2.0, mb = 1.0;
  const Eigen::Vector3d ca(0.1, 0.05, 0);
  Eigen::Matrix3d Ja;
  Ja << 0.05, 0.01, 0, 0.01, 0.08, 0, 0, 0, 0.1;
  const double Ib = 1.0 * (3 * 0.025 * 0.025 + 0.64) / 12;
  const Eigen::Matrix3d Jb = Eigen::Vector3d(0.5 * 0.025 * 0.025, Ib, Ib).asDiagonal();
  Eigen::Vector3d P0 = Eigen::Vector3d::Zero(), L0 = Eigen::Vector3d::Zero();
  double dP = 0, dL = 0, dE = 0;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const Eigen::Matrix3d Aa = fc::rotationMatrix(r.orientation[0][k]), Ab = fc::rotationMatrix(r.orientation[1][k]);
    const Eigen::Vector3d wa = r.angular_velocity[0][k], wb = r.angular_velocity[1][k];
    const Eigen::Vector3d xa = r.position[0][k] + Aa * ca, va = r.velocity[0][k] + wa.cross(Aa * ca);
    const Eigen::Vector3d xb = r.position[1][k], vb = r.velocity[1][k];
    const Eigen::Vector3d P = ma * va + mb * vb;
    const Eigen::Vector3d L = ma * xa.cross(va) + Aa * Ja * Aa.transpose() * wa + mb * xb.cross(vb) +
                              Ab * Jb * Ab.transpose() * wb;
    if (k == 0) { P0 = P; L0 = L; }
    dP = std::max(dP, (P - P0).norm());
    dL = std::max(dL, (L - L0).norm());
    dE = std::max(dE, std::abs(r.kinetic[k] - r.kinetic[0]));
  }
  std::printf("[   info   ] jointed free bodies: |dP| %.3e of %.3g, |dL| %.3e of %.3g, |dT| %.3e of %.3g\n", dP,
              P0.norm(), dL, L0.norm(), dE, r.kinetic[0]);
  // Exact invariants; rtol 1e-9 over 10 s.
  EXPECT_LT(dP, 1e-7 * P0.norm());
  EXPECT_LT(dL, 1e-7 * L0.norm());
  EXPECT_LT(dE, 1e-7 * r.kinetic[0]);
}

class EnergyConservation : public ::testing::TestWithParam<std::string> {};

TEST_P(EnergyConservation, PendulumWithSpringOver100Seconds) {
  const Model m = sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: arm
    rod: {length: 1.0, diameter: 0.02, mass: 1.5}
    position: [0.5, 0, 0]
joints:
  - {name: R, type: revolute, bodies: [ground, arm], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
  - {type: rotational_spring_damper, joint: R, torque: {angle: [-1, 1], value: [-3, 3]}}
simulation: {t_end: 100.0, output_step: 0.1, rtol: )" + std::string(GetParam() == "dopri5" ? "1e-8" : "1e-6") +
                              ", integrator: " + GetParam() + "}\n");
  const Results r = simulate(m, {true});
  ASSERT_EQ(r.status, "completed");
  double dE = 0, scale = 0;
  const double E0 = r.kinetic[0] + r.potential[0];
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    dE = std::max(dE, std::abs(r.kinetic[k] + r.potential[k] - E0));
    scale = std::max(scale, r.kinetic[k]);
  }
  std::printf("[   info   ] %s: energy drift %.3e J of max kinetic %.3g J over 100 s (%ld steps)\n",
              GetParam().c_str(), dE, scale, r.steps);
  // Energy is not controlled directly: each step may commit a local error up
  // to rtol (relative), and these add at most linearly over the run, so the
  // bound is steps * rtol * energy scale.
  EXPECT_LT(dE, r.steps * m.settings.rtol * scale);
}

INSTANTIATE_TEST_SUITE_P(Integrators, EnergyConservation, ::testing::Values("dopri5", "trbdf2"));

}  // namespace
}  // namespace fc::mbs::test
