// Flexible bodies inside the engine (issue 6), on body files written here from
// random lumped-mass bodies with mass-orthonormal modes (the flexible-body
// tests' generator, tests/mbs-run/flexible/random_body.h):
// - `modes: 0` gives exactly the rigid body of the same inertia (same
//   trajectory as the scene with rigid: {mass, center_of_mass, inertia});
// - a flexible pendulum hanging from an interface (the joint point moves with
//   the modes) conserves T + V_gravity + U_strain without damping, and
//   T + V + U + dissipated with modal damping;
// - a free-floating flexible body keeps its linear and angular momentum.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "flexible/random_body.h"
#include "common/flexbody.h"
#include "common/rotations.h"
#include "helpers.h"
#include "mbs-run/flexible/flexible_inertia.h"
#include "mbs-run/simulation.h"

namespace fc::mbs::test {
namespace {

std::string writeBody(int nm, unsigned seed) {
  return writeTempBody(fc::testing::randomBody(8, nm, seed, 0.4, 1.0, 3.0), "mbs_flex_" + std::to_string(seed));
}

// A pendulum: the body hangs from the ground at interface P0 (or, rigid, at
// the same body-frame point), tilted so that it swings in 3D.
std::string pendulum(const std::string& body_block, const std::string& point, double t_end, const char* extra = "") {
  return R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: b
    )" + body_block + R"(
    orientation: [0.9, 0.3, -0.2, 0.24494897427831783]
    angular_velocity: [0.3, -0.5, 1.0]
joints:
  - {name: S, type: spherical, bodies: [ground, b], points: [[0, 0, 0], )" +
         point + R"(]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
simulation: {t_end: )" + std::to_string(t_end) + R"(, output_step: 0.01, rtol: 1.0e-9}
)" + extra;
}

TEST(FlexibleEngine, ZeroModesIsTheRigidBody) {
  const std::string file = writeBody(3, 11);
  const FlexBodyFile f = readFlexBody(file, 0);
  const InertiaInvariants& inv = f.invariants;
  const Eigen::Vector3d c = inv.centerOfMass();
  const Eigen::Matrix3d cs = fc::skew(c);
  const Eigen::Matrix3d Ic = inv.inertiaAboutOrigin() + inv.mass * cs * cs;
  char rigid[512];
  std::snprintf(rigid, sizeof rigid,
                "rigid: {mass: %.17g, center_of_mass: %s, inertia: [[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g], "
                "[%.17g, %.17g, %.17g]]}",
                inv.mass, yamlVector(c).c_str(), Ic(0, 0), Ic(0, 1), Ic(0, 2), Ic(1, 0), Ic(1, 1), Ic(1, 2), Ic(2, 0),
                Ic(2, 1), Ic(2, 2));
  const Eigen::Vector3d p0 = f.body.interfaces[0].position;
  // The pendulum's first point puts the body's P0 at the origin.
  const std::string pos = "position: [0, 0, 0]\n    ";
  const Results rr = simulate(sceneFromText(pendulum(pos + rigid, yamlVector(p0), 2.0)), {true});
  const Results rf = simulate(
      sceneFromText(pendulum(pos + "flexible: {file: " + file + ", modes: 0}", f.body.interfaces[0].name, 2.0)),
      {true});
  ASSERT_EQ(rr.status, "completed");
  ASSERT_EQ(rf.status, "completed");
  ASSERT_EQ(rr.time.size(), rf.time.size());
  double worst = 0;
  for (std::size_t k = 0; k < rr.time.size(); ++k)
    worst = std::max({worst, (rr.position[1][k] - rf.position[1][k]).norm(),
                      (rr.orientation[1][k] - rf.orientation[1][k]).norm()});
  std::printf("[   info   ] modes: 0 vs rigid: largest difference %.2e over 2 s\n", worst);
  // Same equations (the flexible kernel reduces to the rigid M and Q_v), so
  // the only differences are rounding in differently ordered sums, amplified
  // by the step control: far below the 1e-9 tolerance.
  EXPECT_LT(worst, 1e-10);
  std::filesystem::remove(file);
}

TEST(FlexibleEngine, FlexiblePendulumConservesEnergy) {
  const std::string file = writeBody(3, 12);
  // Start assembled and undeformed: the frame origin placed so that P0 is at
  // the pivot (otherwise the initial projection, mass-orthogonal, would
  // satisfy the joint partly by deforming the light modes).
  const Eigen::Vector3d p0 = readFlexBody(file, 3).body.interfaces[0].position;
  const Eigen::Matrix3d A = fc::rotationMatrix(Eigen::Vector4d(0.9, 0.3, -0.2, 0.24494897427831783));
  const std::string pos = "position: " + yamlVector(-A * p0) + "\n    ";
  for (double zeta : {0.0, 0.05}) {
    char block[256];
    std::snprintf(block, sizeof block, "flexible: {file: %s, modes: 3, damping_ratio: %g}", file.c_str(), zeta);
    const Results r = simulate(sceneFromText(pendulum(pos + block, "P0", 3.0)), {true});
    ASSERT_EQ(r.status, "completed");
    double dE = 0, scale = 0, umax = 0;
    const double E0 = r.kinetic[0] + r.potential[0] + r.strain[0];
    for (std::size_t k = 0; k < r.time.size(); ++k) {
      const double E = r.kinetic[k] + r.potential[k] + r.strain[k] + r.dissipated[k];
      dE = std::max(dE, std::abs(E - E0));
      scale = std::max(scale, r.kinetic[k]);
      umax = std::max(umax, r.strain[k]);
    }
    std::printf("[   info   ] flexible pendulum (zeta %.2f): energy balance %.2e J of %.3g J, max strain energy %.3g J, "
                "dissipated %.3g J, violation %.2e, %ld steps\n",
                zeta, dE, scale, umax, r.dissipated.back(), r.max_violation, r.steps);
    EXPECT_GT(umax, 1e-3 * scale);  // the modes are really excited
    if (zeta > 0) { EXPECT_GT(r.dissipated.back(), 1e-3 * scale); }
    // Local errors of at most rtol per step add up linearly (as for the rigid
    // energy test); the projection adds nothing measurable.
    EXPECT_LT(dE, r.steps * 1e-9 * scale);
    EXPECT_LT(r.max_violation, 1e-8);
  }
  std::filesystem::remove(file);
}

TEST(FlexibleEngine, FreeFloatingBodyKeepsMomentum) {
  const std::string file = writeBody(4, 13);
  const Results r = simulate(sceneFromText(R"(
bodies:
  - name: b
    flexible: {file: )" + file + R"(, modes: 4}
    velocity: [0.2, -0.1, 0.3]
    angular_velocity: [1.0, 0.5, -2.0]
simulation: {t_end: 3.0, output_step: 0.01, rtol: 1.0e-9}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  const FlexBodyFile f = readFlexBody(file, 4);
  double dP = 0, dL = 0, dE = 0;
  Eigen::Vector3d P0 = Eigen::Vector3d::Zero(), L0 = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const Eigen::Matrix3d A = fc::rotationMatrix(r.orientation[0][k]);
    Eigen::VectorXd v(10);
    v.head<3>() = r.velocity[0][k];
    v.segment<3>(3) = A.transpose() * r.angular_velocity[0][k];
    v.tail(4) = r.modal_rate[0][k];
    const Eigen::Vector3d P = linearMomentum(f.invariants, A, r.modal[0][k], v);
    const Eigen::Vector3d L = angularMomentum(f.invariants, r.position[0][k], A, r.modal[0][k], v);
    if (k == 0) {
      P0 = P;
      L0 = L;
    }
    dP = std::max(dP, (P - P0).norm());
    dL = std::max(dL, (L - L0).norm());
    dE = std::max(dE, std::abs(r.kinetic[k] + r.strain[k] - r.kinetic[0] - r.strain[0]));
  }
  std::printf("[   info   ] free flexible body: |dP| %.2e of %.3g, |dL| %.2e of %.3g, |dE| %.2e\n", dP, P0.norm(), dL,
              L0.norm(), dE);
  // Exact invariants (the flexible kernel's momenta, computed from the
  // recorded state); rtol 1e-9 over 3 s of 1-3 Hz vibration.
  EXPECT_LT(dP, 1e-7 * P0.norm());
  EXPECT_LT(dL, 1e-7 * L0.norm());
  EXPECT_LT(dE, 1e-7 * r.kinetic[0]);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace fc::mbs::test
