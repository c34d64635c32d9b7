// Compound double pendulum (two uniform rods, revolute joints) against an
// independent solution of its 2-DOF Lagrange equations in absolute angles
// theta1, theta2 from the downward vertical:
//   [m1 L1^2/3 + m2 L1^2,        m2 L1 L2/2 cos(t1-t2)] [t1'']   [-m2 L1 L2/2 sin(t1-t2) t2'^2 - (m1/2+m2) g L1 sin t1]
//   [m2 L1 L2/2 cos(t1-t2),      m2 L2^2/3           ] [t2''] = [ m2 L1 L2/2 sin(t1-t2) t1'^2 - m2 g L2/2 sin t2       ]
// integrated here with RK4 at a step whose error is far below the tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

constexpr double kG = 9.81, kM1 = 1.0, kM2 = 0.6, kL1 = 1.0, kL2 = 0.7;

Eigen::VectorXd lagrange(double, const Eigen::VectorXd& y) {
  const double t1 = y[0], t2 = y[1], w1 = y[2], w2 = y[3];
  const double c = kM2 * kL1 * kL2 / 2.0;
  Eigen::Matrix2d M;
  M << kM1 * kL1 * kL1 / 3.0 + kM2 * kL1 * kL1, c * std::cos(t1 - t2), c * std::cos(t1 - t2), kM2 * kL2 * kL2 / 3.0;
  Eigen::Vector2d rhs(-c * std::sin(t1 - t2) * w2 * w2 - (kM1 / 2.0 + kM2) * kG * kL1 * std::sin(t1),
                      c * std::sin(t1 - t2) * w1 * w1 - kM2 * kG * kL2 / 2.0 * std::sin(t2));
  const Eigen::Vector2d acc = M.partialPivLu().solve(rhs);
  Eigen::VectorXd d(4);
  d << w1, w2, acc;
  return d;
}

// Body x along the rod pointing away from the pivot: a rotation about +y by
// beta = pi/2 - theta maps x to (sin theta, 0, -cos theta).
std::string pose(double theta, const Eigen::Vector3d& centre) {
  const double beta = M_PI / 2 - theta;
  char buf[256];
  std::snprintf(buf, sizeof buf, "position: [%.17g, %.17g, %.17g]\n    orientation: [%.17g, 0, %.17g, 0]\n",
                centre.x(), centre.y(), centre.z(), std::cos(beta / 2), std::sin(beta / 2));
  return buf;
}

constexpr double th1 = M_PI / 2, th2 = M_PI / 2;  // both horizontal, at rest: a large, chaotic swing

std::string pendulumScene(double rtol, double atol) {
  const Eigen::Vector3d e1(std::sin(th1), 0, -std::cos(th1)), e2(std::sin(th2), 0, -std::cos(th2));
  // Thin rods: the axial inertia only enters the idle spin, give it a tiny value.
  char scene[2048];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: rod1
    rigid: {mass: %g, inertia: [[1e-6,0,0],[0,%.17g,0],[0,0,%.17g]]}
    %s
  - name: rod2
    rigid: {mass: %g, inertia: [[1e-6,0,0],[0,%.17g,0],[0,0,%.17g]]}
    %s
joints:
  - {name: J1, type: revolute, bodies: [ground, rod1], points: [[0,0,0],[%g,0,0]], axes: [[0,1,0],[0,1,0]]}
  - {name: J2, type: revolute, bodies: [rod1, rod2], points: [[%g,0,0],[%g,0,0]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
simulation: {t_end: 3.0, output_step: 0.05, rtol: %.17g, atol: %.17g}
)",
                kM1, kM1 * kL1 * kL1 / 12, kM1 * kL1 * kL1 / 12, pose(th1, 0.5 * kL1 * e1).c_str(), kM2,
                kM2 * kL2 * kL2 / 12, kM2 * kL2 * kL2 / 12, pose(th2, kL1 * e1 + 0.5 * kL2 * e2).c_str(),
                -kL1 / 2, kL1 / 2, -kL2 / 2, rtol, atol);
  return scene;
}


// Largest distance between rod 2's tip in the results and in the Lagrange
// solution, integrated alongside with RK4 at h = 1e-4 between samples (local
// error ~ h^5 |y^(5)| ~ 1e-17 per step, far below any engine tolerance here).
double tipErrorAgainstLagrange(const Results& r) {
  Eigen::VectorXd y(4);
  y << th1, th2, 0, 0;
  double t = 0.0, worst = 0.0;
  for (std::size_t k = 1; k < r.time.size(); ++k) {
    y = rk4(lagrange, y, t, r.time[k], 500);
    t = r.time[k];
    const Eigen::Vector3d tip_ref = kL1 * Eigen::Vector3d(std::sin(y[0]), 0, -std::cos(y[0])) +
                                    kL2 * Eigen::Vector3d(std::sin(y[1]), 0, -std::cos(y[1]));
    // Tip of rod 2 = centre + A (L2/2, 0, 0): first column of A from p.
    const Eigen::Vector4d p = r.orientation[2][k];
    const Eigen::Vector3d col0(2 * (p[0] * p[0] + p[1] * p[1]) - 1, 2 * (p[1] * p[2] + p[0] * p[3]),
                               2 * (p[1] * p[3] - p[0] * p[2]));
    worst = std::max(worst, (r.position[2][k] + 0.5 * kL2 * col0 - tip_ref).norm());
  }
  return worst;
}

// Both formulations (docs/mbs-run.md, Formulation): auto runs this open
// chain in joint coordinates, constrained in Cartesian ones.
TEST(DoublePendulum, MatchesMinimalCoordinateLagrangeSolution) {
  for (Formulation f : {Formulation::Constrained, Formulation::Tree}) {
    Model model = sceneFromText(pendulumScene(1e-10, 1e-13));
    model.settings.formulation = f;
    const Results r = simulate(model, {true});
    ASSERT_EQ(r.status, "completed");
    EXPECT_EQ(r.formulation.substr(0, 4), f == Formulation::Tree ? "tree" : "cons");

    const double worst = tipErrorAgainstLagrange(r);
    // The motion is chaotic (largest Lyapunov exponent a few 1/s), so errors of
    // order rtol = 1e-10 grow by ~e^(3 * 3) ~ 1e4 over 3 s: 1e-5 m is the bound a
    // correct engine meets; a wrong term in M or Q_v gives errors of order 0.1 m.
    std::printf("[   info   ] %s: tip error vs Lagrange/RK4: %.3e m, violation %.3e, %ld steps\n",
                r.formulation.c_str(), worst, r.max_violation, r.steps);
    EXPECT_LT(worst, 1e-5);
    EXPECT_LT(r.max_violation, 1e-8);
  }
}

// The two ways of applying (M + a Phi^T Phi)^-1 give the same motion: their
// rounding differs, and the chaotic swing amplifies it by ~1e4 over 3 s
// (first test), so 1e-9 m leaves room above 1e-16 x 1e4 and is far below
// any modelling or integration error.
TEST(DoublePendulum, SchurAndSparseSolversAgree) {
  Model a = sceneFromText(pendulumScene(1e-8, 1e-11));
  a.settings.formulation = Formulation::Constrained;  // the solvers of the constrained path
  Model b = a;
  a.settings.linear_solver = AlMethod::BlockSchur;
  b.settings.linear_solver = AlMethod::SparseLdlt;
  const Results ra = simulate(a, {true}), rb = simulate(b, {true});
  ASSERT_EQ(ra.status, "completed");
  ASSERT_EQ(rb.status, "completed");
  ASSERT_EQ(ra.time.size(), rb.time.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < ra.time.size(); ++k)
    worst = std::max(worst, (ra.position[2][k] - rb.position[2][k]).norm());
  std::printf("[   info   ] schur vs sparse: rod 2 centre differs by %.2e m at most\n", worst);
  EXPECT_LT(worst, 1e-9);
}

// At a loose tolerance the run projects only the drift the error control
// could see (above atol/10): the sampled violation stays below atol, most
// steps are not projected, and those steps reuse their last stage (FSAL), so
// an accepted or rejected step costs 6 evaluations, not 7 plus a projection.
TEST(DoublePendulum, LooseToleranceProjectsOnlyVisibleDrift) {
  // atol above rtol |q|: the drift a step leaves (~rtol |q|) is then mostly
  // below the projection threshold.
  const double rtol = 1e-6, atol = 1e-4;
  Model model = sceneFromText(pendulumScene(rtol, atol));
  model.settings.formulation = Formulation::Constrained;  // projections are the constrained path's
  const Results r = simulate(model, {true});
  ASSERT_EQ(r.status, "completed");
  const long attempts = r.steps + r.rejected_steps;
  std::printf("[   info   ] rtol %g: %ld steps, %ld rejected, %ld projections, %ld evaluations, violation %.3e\n",
              rtol, r.steps, r.rejected_steps, r.projections, r.evaluations, r.max_violation);
  // Step ends are held below atol/10; samples in between are interpolated
  // (4th-order dense output), whose own error is of the order of atol.
  EXPECT_LT(r.max_violation, atol);
  EXPECT_LT(r.projections, r.steps * 3 / 4);  // measured: about half
  // 6 per attempt, 1 per projection (renewed first stage), 1 per output
  // sample (its reactions), 2 to start (first derivative and the starting-step probe).
  EXPECT_LE(r.evaluations, 6 * attempts + r.projections + long(r.time.size()) + 2);
  // Still the Lagrange solution: measured 1.1e-4 m, i.e. atol grown by the
  // chaotic swing; the bound keeps two decades of margin and is still far
  // below the metres a drift left to run away would give.
  const double worst = tipErrorAgainstLagrange(r);
  std::printf("[   info   ] tip error vs Lagrange/RK4: %.3e m\n", worst);
  EXPECT_LT(worst, 1e-2);
}

}  // namespace
}  // namespace fc::mbs::test
