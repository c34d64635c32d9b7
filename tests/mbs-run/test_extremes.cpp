// Stability at the extremes, each against a reference that does not
// depend on the engine: first integrals, a minimal-coordinate solution
// integrated here by RK4, or a tight-tolerance closed-form-backed run:
// - a free-floating body with 200 modes conserves energy and momenta;
// - a double pendulum whose links differ in mass by 1e6 follows its 2-DOF
//   Lagrange equations, constraints held, no NaN;
// - a 1000-second pendulum keeps its energy within steps x rtol and its
//   joint closed;
// - rtol from 1e-2 to 1e-12, both integrators: every run either completes
//   with an error proportional to the tolerance, or stops with a status
//   saying why; never NaN, never a silent wrong answer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "common/flexbody.h"
#include "common/rotations.h"
#include "flexible/random_body.h"
#include "helpers.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/run/run_quality.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

double angleZ(const Eigen::Vector4d& p) { return 2.0 * std::atan2(p(3), p(0)); }

TEST(Extremes, TwoHundredModesFreeFloating) {
  const int nm = 200;
  // 40 nodes x 6 dofs = 240 >= 200 independent mass-orthonormal modes, 1-20 Hz.
  const FlexBody b = fc::testing::randomBody(40, nm, 21, 0.5, 1.0, 20.0);
  const std::string file = writeTempBody(b, "flexval_200modes");
  const Results r = simulate(sceneFromText(R"(
bodies:
  - name: b
    flexible: {file: )" + file + R"(, modes: 200}
    velocity: [0.2, -0.1, 0.3]
    angular_velocity: [1.0, 0.5, -2.0]
simulation: {t_end: 0.2, output_step: 0.01, rtol: 1.0e-6}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  const FlexBodyFile f = readFlexBody(file, nm);
  double dP = 0, dL = 0, dE = 0, wmax = 0;
  Eigen::Vector3d P0 = Eigen::Vector3d::Zero(), L0 = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const Eigen::Matrix3d A = fc::rotationMatrix(r.orientation[0][k]);
    Eigen::VectorXd v(6 + nm);
    v.head<3>() = r.velocity[0][k];
    v.segment<3>(3) = A.transpose() * r.angular_velocity[0][k];
    v.tail(nm) = r.modal_rate[0][k];
    ASSERT_TRUE(v.allFinite());
    const Eigen::Vector3d P = linearMomentum(f.invariants, A, r.modal[0][k], v);
    const Eigen::Vector3d L = angularMomentum(f.invariants, r.position[0][k], A, r.modal[0][k], v);
    if (k == 0) {
      P0 = P;
      L0 = L;
    }
    dP = std::max(dP, (P - P0).norm());
    dL = std::max(dL, (L - L0).norm());
    dE = std::max(dE, std::abs(r.kinetic[k] + r.strain[k] - r.kinetic[0] - r.strain[0]));
    wmax = std::max(wmax, r.modal[0][k].cwiseAbs().maxCoeff());
  }
  std::printf("[   info   ] 200 modes: |dP| %.2e of %.3g, |dL| %.2e of %.3g, |dE| %.2e of %.3g, max |w| %.2e, %ld "
              "steps, %.2f s CPU\n",
              dP, P0.norm(), dL, L0.norm(), dE, r.kinetic[0], wmax, r.steps, r.cpu_seconds);
  EXPECT_GT(wmax, 1e-4);  // the spin really excites the modes
  // Exact invariants of the motion; rtol 1e-6 over 0.2 s (4 periods of the
  // stiffest mode): local errors of rtol relative, 1e-6 relative overall.
  EXPECT_LT(dP, 1e-6 * P0.norm());
  EXPECT_LT(dL, 1e-6 * L0.norm());
  EXPECT_LT(dE, 1e-6 * r.kinetic[0]);
  std::filesystem::remove(file);
}

// Compound double pendulum of uniform rods hanging from the origin, angles
// from the downward vertical (Lagrange's equations, e.g. Greenwood,
// Principles of Dynamics, 2nd ed., sec. 6.2).
struct DoubleRod {
  double m1, l1, m2, l2, d = 0.001;  // masses, lengths, diameter of both rods
  double g = 9.81;
  Eigen::VectorXd operator()(double, const Eigen::VectorXd& y) const {
    const double a = y(0), b = y(1), da = y(2), db = y(3), c1 = 0.5 * l1, c2 = 0.5 * l2;
    // Transverse inertia of a solid cylinder about its centre, m (3 r^2 + l^2) / 12.
    const double I1 = m1 * (0.75 * d * d + l1 * l1) / 12, I2 = m2 * (0.75 * d * d + l2 * l2) / 12;
    const double M11 = I1 + m1 * c1 * c1 + m2 * l1 * l1, M12 = m2 * l1 * c2 * std::cos(a - b);
    const double M22 = I2 + m2 * c2 * c2;
    Eigen::Matrix2d M;
    M << M11, M12, M12, M22;
    const Eigen::Vector2d f(-m2 * l1 * c2 * std::sin(a - b) * db * db - (m1 * c1 + m2 * l1) * g * std::sin(a),
                            m2 * l1 * c2 * std::sin(a - b) * da * da - m2 * c2 * g * std::sin(b));
    Eigen::VectorXd dd(4);
    dd << da, db, M.ldlt().solve(f);
    return dd;
  }
};

// Two rods along body x, the first hinged at the origin, both starting
// horizontal (+x) at rest. Rod diameters 1 mm (axial inertia irrelevant in plane).
std::string doubleRodScene(double m1, double m2, const std::string& sim) {
  char s[1200];
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: a, rod: {length: 1.0, diameter: 0.001, mass: %.17g}, position: [0.5, 0, 0]}
  - {name: b, rod: {length: 0.8, diameter: 0.001, mass: %.17g}, position: [1.4, 0, 0]}
joints:
  - {name: R1, type: revolute, bodies: [ground, a], points: [[0, 0, 0], [-0.5, 0, 0]], axes: [[0,0,1],[0,0,1]]}
  - {name: R2, type: revolute, bodies: [a, b], points: [[0.5, 0, 0], [-0.4, 0, 0]], axes: [[0,0,1],[0,0,1]]}
forces:
  - {type: gravity, g: [0, -9.81, 0]}
simulation: %s
)",
                m1, m2, sim.c_str());
  return s;
}

TEST(Extremes, MassRatioOfAMillion) {
  // Heavy first link, light second one, and the reverse: the penalty scale
  // follows the largest mass, so the light body's rows are the hard case.
  for (const auto& [m1, m2] : {std::pair{1.0e3, 1.0e-3}, std::pair{1.0e-3, 1.0e3}}) {
    const Results r = simulate(sceneFromText(doubleRodScene(m1, m2, "{t_end: 2.0, output_step: 0.01, rtol: 1.0e-9}")),
                               {true});
    ASSERT_EQ(r.status, "completed");
    DoubleRod dr{m1, 1.0, m2, 0.8};
    // Horizontal start: 90 degrees from the downward vertical.
    Eigen::VectorXd y(4);
    y << M_PI / 2, M_PI / 2, 0, 0;
    double t = 0, err = 0;
    for (double tc : {0.5, 1.0, 1.5, 2.0}) {
      y = rk4(dr, y, t, tc, static_cast<int>(std::lround((tc - t) / 1e-5)));
      t = tc;
      const std::size_t k = rowAt(r.time, tc);
      // Body angle about z from +x; from the downward vertical: angle + pi/2.
      for (int i = 0; i < 2; ++i) {
        ASSERT_TRUE(r.orientation[1 + i][k].allFinite());
        const double th = angleZ(r.orientation[1 + i][k]) + M_PI / 2;
        err = std::max(err, std::abs(std::remainder(th - y(i), 2 * M_PI)));
      }
    }
    std::printf("[   info   ] mass ratio m1/m2 = %.0e: angle error vs Lagrange %.2e rad, violation %.2e, %ld steps, "
                "%ld rejected\n",
                m1 / m2, err, r.max_violation, r.steps, r.rejected_steps);
    // rtol 1e-9 over 2 s of a non-chaotic swing (the light link is a driven
    // pendulum, or the heavy one a pendulum on a weightless first link).
    EXPECT_LT(err, 1e-6);
    EXPECT_LT(r.max_violation, 1e-8);  // metres, 1 m links
  }
}

TEST(Extremes, ThousandSecondPendulum) {
  const Results r = simulate(sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: a, rod: {length: 1.0, diameter: 0.01, mass: 2.0}, position: [0.5, 0, 0]}
joints:
  - {name: R1, type: revolute, bodies: [ground, a], points: [[0, 0, 0], [-0.5, 0, 0]], axes: [[0,0,1],[0,0,1]]}
forces:
  - {type: gravity, g: [0, -9.81, 0]}
simulation: {t_end: 1000.0, output_step: 1.0, rtol: 1.0e-6}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  double dE = 0, scale = 0;
  const double E0 = r.kinetic[0] + r.potential[0];
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    ASSERT_TRUE(std::isfinite(r.kinetic[k] + r.potential[k]));
    dE = std::max(dE, std::abs(r.kinetic[k] + r.potential[k] - E0));
    scale = std::max(scale, r.kinetic[k]);
  }
  std::printf("[   info   ] 1000 s pendulum: energy drift %.2e J of %.3g J, violation %.2e, %ld steps, %.2f s CPU\n",
              dE, scale, r.max_violation, r.steps, r.cpu_seconds);
  EXPECT_GT(r.time.back(), 999.999);
  // Local errors of at most rtol per step add up at worst linearly.
  EXPECT_LT(dE, r.steps * 1e-6 * scale);
  // The outputs are dense-output interpolants between steps projected to
  // 1e-12: they carry the local error, rtol x 1 m; and it must not grow.
  double early = 0, late = 0;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    if (r.time[k] <= 100) early = std::max(early, r.violation[k]);
    if (r.time[k] >= 900) late = std::max(late, r.violation[k]);
  }
  std::printf("[   info   ] violation in the first 100 s %.2e, in the last 100 s %.2e\n", early, late);
  EXPECT_LT(r.max_violation, 1e-6);
  EXPECT_LT(late, 10 * early + 1e-12);
}

TEST(Extremes, TolerancesFromOneHundredthToOneTrillionth) {
  // Reference: the double pendulum of comparable masses over 1 s (not yet
  // chaotic), RK4 at h = 1e-5 s (error ~1e-14 rad).
  DoubleRod dr{1.0, 1.0, 0.7, 0.8};
  Eigen::VectorXd y(4);
  y << M_PI / 2, M_PI / 2, 0, 0;
  y = rk4(dr, y, 0.0, 1.0, 100000);
  for (const char* integ : {"dopri5", "trbdf2"}) {
    for (double rtol : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
      char sim[200];
      std::snprintf(sim, sizeof sim, "{t_end: 1.0, output_step: 0.05, rtol: %g, integrator: %s}", rtol, integ);
      const Results r = simulate(sceneFromText(doubleRodScene(1.0, 0.7, sim)), {true});
      const std::size_t k = r.time.size() - 1;
      bool finite = true;
      for (std::size_t i = 0; i < r.time.size(); ++i)
        finite = finite && r.orientation[1][i].allFinite() && r.orientation[2][i].allFinite();
      EXPECT_TRUE(finite) << integ << " rtol " << rtol;
      if (r.status != "completed") {
        // A stop must say why.
        std::printf("[   info   ] %s rtol %.0e: stopped at %.3f s: %s\n", integ, rtol, r.t_reached, r.status.c_str());
        EXPECT_NE(r.status.find("rtol"), std::string::npos) << r.status;  // names the setting to change
        EXPECT_NE(r.status.find("loosen"), std::string::npos) << r.status;
        continue;
      }
      double err = 0;
      for (int i = 0; i < 2; ++i)
        err = std::max(err,
                       std::abs(std::remainder(angleZ(r.orientation[1 + i][k]) + M_PI / 2 - y(i), 2 * M_PI)));
      std::printf("[   info   ] %s rtol %.0e: angle error %.2e rad at 1 s, %ld steps, %ld rejected, violation %.1e\n",
                  integ, rtol, err, r.steps, r.rejected_steps, r.max_violation);
      // Each step's local error is at most rtol x |y| (|y| < 2 rad): without
      // amplification (a regular 1 s swing) the global error is below
      // steps x rtol x 2, plus the rounding floor of the projections
      // (|Phi| < 1e-12 x scene size).
      EXPECT_LT(err, r.steps * rtol * 2 + 1e-10) << integ << " rtol " << rtol;
    }
  }
}

}  // namespace
TEST(Extremes, RunThatWouldNeverFinishStopsAndNamesItsTimeScale) {
  // Time scales of 1e-9 s in runs of 100 s (3e10 steps of dopri5 at its
  // stability limit h ~ 3.3 / omega): a milligram on a 1e12 N/m spring
  // (omega = 1e9 rad/s, constrained path) and a light rod on a hinge with a
  // 1e6 N m s damper (decay rate c / J = 3e9 1/s, joint-coordinate path).
  // Before, both ground on for days with the progress bar still; now they
  // stop after one window of steps with a status naming the time scale.
  const char* spring = R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: p, rigid: {mass: 1.0e-6, inertia: [[1.0e-9,0,0],[0,1.0e-9,0],[0,0,1.0e-9]]}, position: [0.001, 0, 0]}
forces:
  - {type: translational_spring_damper, bodies: [ground, p], points: [[0, 0, 0], [0, 0, 0]], stiffness: 1.0e12, free_length: 0.0}
simulation: {t_end: 100.0, output_step: 1.0, integrator: dopri5}
)";
  const char* damper = R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: a, rod: {length: 1.0, diameter: 0.001, mass: 1.0e-3}, position: [0.5, 0, 0]}
joints:
  - {name: R1, type: revolute, bodies: [ground, a], points: [[0, 0, 0], [-0.5, 0, 0]], axes: [[0,0,1],[0,0,1]]}
forces:
  - {type: gravity, g: [0, -9.81, 0]}
  - {type: rotational_spring_damper, joint: R1, damping: 1.0e6}
simulation: {t_end: 100.0, output_step: 1.0, integrator: dopri5}
)";
  for (const char* scene : {spring, damper}) {
    const Results r = simulate(sceneFromText(scene), {true});
    std::printf("[   info   ] %s\n", r.status.c_str());
    EXPECT_EQ(r.status.rfind("solver failure: no progress", 0), 0u) << r.status;
    EXPECT_NE(r.status.find("time scale near"), std::string::npos) << r.status;
    // One window of steps at ~3e-9 s each: stopped within the first 1e-3 s.
    EXPECT_EQ(r.steps, StallMonitor::kWindow);
    EXPECT_LT(r.t_reached, 1e-3);
    for (const auto& q : r.orientation.back()) EXPECT_TRUE(q.allFinite());
  }
}

}  // namespace fc::mbs::test
