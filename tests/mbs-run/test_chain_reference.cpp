// a planar chain of N uniform rods on revolute joints, released at
// rest from the horizontal, against the independent minimal-coordinate model
// of chain_reference.h (the N-link pendulum in absolute link angles),
// integrated by RK4 at a fixed step. N = 10 runs the block Schur solve with a
// dense joint-space matrix S, N = 50 (250 constraint rows) the one with a
// sparse S (AlSolver::kMaxDenseSchurRows); the last test checks the three
// linear solvers against each other to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "chain_reference.h"
#include "helpers.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs::test {
namespace {

constexpr double kL = 0.1, kM = 0.1, kG = 9.81;

// Thin rods: centroidal inertia m l^2 / 12 about the joint axis.
struct Chain : MinimalChain {
  explicit Chain(int n_links) : MinimalChain(n_links, kL, kM, kM * kL * kL / 12, kG) {}
};

std::string chainScene(int n, double t_end, double rtol, double atol) {
  char sim[200];
  std::snprintf(sim, sizeof sim,
                "{t_end: %g, output_step: %g, rtol: %g, atol: %g, integrator: dopri5, formulation: constrained}", t_end,
                t_end / 10, rtol, atol);
  return thinLinkChainScene(n, kL, kM, sim);
}

// Largest distance between a rod centre of the run and of the reference at
// the output times; the reference by RK4 with `substeps` per output interval.
double worstCentreError(int n, const Results& r, int substeps) {
  const Chain c(n);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  double t = 0, worst = 0;
  for (std::size_t k = 1; k < r.time.size(); ++k) {
    y = rk4([&](double, const Eigen::VectorXd& z) { return c.f(z); }, y, t, r.time[k], substeps);
    t = r.time[k];
    for (int b = 0; b < n; ++b) {
      const Eigen::Vector2d ref = c.centre(y, b);
      const Eigen::Vector3d& p = r.position[b + 1][k];
      worst = std::max(worst, std::hypot(p.x() - ref.x(), p.z() - ref.y()) + std::abs(p.y()));
    }
  }
  return worst;
}

// The reference's own error, from RK4 at two step sizes (the error of the
// finer is about 1/16 of their difference).
struct Case {
  int n;
  double t_end;
  int substeps;
};

class ChainReference : public ::testing::TestWithParam<Case> {};

TEST_P(ChainReference, MatchesMinimalCoordinateChain) {
  const Case cs = GetParam();
  const Results r = simulate(sceneFromText(chainScene(cs.n, cs.t_end, 1e-10, 1e-13)), {true});
  ASSERT_EQ(r.status, "completed");
  const double err = worstCentreError(cs.n, r, cs.substeps);
  const double ref_self = std::abs(err - worstCentreError(cs.n, r, cs.substeps / 2));
  const double drop = -r.position[cs.n].back().z();  // the free end's rod fell this far
  std::printf("[   info   ] N = %d, %g s: last rod fell %.3f m; worst rod-centre error %.3e m (reference step "
              "change %.1e), %ld steps, violation %.1e\n",
              cs.n, cs.t_end, drop, err, ref_self, r.steps, r.max_violation);
  ASSERT_GT(drop, 0.1);  // a large motion, not a chain at rest
  // Dormand-Prince at rtol 1e-10 (atol 1e-13) on positions of order 1 m
  // keeps each step's error near 1e-10 m x (step's share of the run); the
  // motion is not yet chaotic over these spans (measured 9e-13 m at N = 10,
  // 4e-14 m at N = 50), so 1e-9 m (10 rtol x 1 m) is the bound a correct
  // engine meets with margin; a wrong inertia term or a drifting constraint
  // gives errors of order 1e-3 m and more.
  EXPECT_LT(err, 1e-9);
  EXPECT_LT(ref_self, 1e-10);  // the reference is converged below the bound (measured 6e-12 m)
  EXPECT_LT(r.max_violation, 1e-8);
}

INSTANTIATE_TEST_SUITE_P(Lengths, ChainReference,
                         ::testing::Values(Case{10, 0.4, 400}, Case{50, 0.2, 400}),
                         [](const ::testing::TestParamInfo<Case>& i) { return "N" + std::to_string(i.param.n); });

// The sparse joint-space factorisation (SparseSchur, O(N)) against the
// dense one (BlockSchur) and the sparse LDL^T of M + a Phi^T Phi, on a
// 30-rod chain (150 rows) in motion: one right-hand side at the same state
// must agree to rounding, and so must a whole run. The three solve the same
// equations by different eliminations, so their results differ by rounding
// amplified by the conditioning of the factorised matrices (penalty 1e5 over
// rod inertias ~1e-4, but the multiplier iteration refines the answer to
// the rounding of x = M^-1 (Q - Phi^T lambda)): measured 1e-14 relative on
// the accelerations and 4e-15 m over the run; 1e-11 leaves three decades
// for other compilers' operation order and flags any wrong entry of S.
TEST(ChainSolvers, SparseJointSpaceMatrixEqualsDenseToRounding) {
  const int n = 30;
  Model base = sceneFromText(chainScene(n, 0.1, 1e-8, 1e-11));
  const Results moving = simulate(base, {true});
  ASSERT_EQ(moving.status, "completed");
  const AlMethod methods[3] = {AlMethod::BlockSchur, AlMethod::SparseSchur, AlMethod::SparseLdlt};
  Eigen::VectorXd yd[3];
  Results runs[3];
  for (int k = 0; k < 3; ++k) {
    Model m = base;
    m.settings.linear_solver = methods[k];
    System sys(m);
    Eigen::VectorXd y = sys.initialState();
    sys.initializeJoints(y);
    // A state in motion: the run's last poses and velocities.
    for (int b = 0; b < n; ++b) {
      const Body& body = m.bodies[b + 1];
      y.segment<3>(body.pos_index) = moving.position[b + 1].back();
      y.segment<4>(body.pos_index + 3) = moving.orientation[b + 1].back();
    }
    sys.project(0.0, y);  // consistent positions; velocities from a swing below
    for (int b = 0; b < n; ++b) y[m.nq + m.bodies[b + 1].dof_index + 4] = 0.5 + 0.1 * b;  // omega_y'
    sys.project(0.0, y);
    sys.derivative(0.0, y, yd[k]);
    runs[k] = simulate(m, {true});
    ASSERT_EQ(runs[k].status, "completed");
  }
  for (int k : {1, 2}) {
    const double acc = (yd[k] - yd[0]).lpNorm<Eigen::Infinity>() / yd[0].lpNorm<Eigen::Infinity>();
    double worst = 0.0;
    for (std::size_t i = 0; i < runs[0].time.size(); ++i)
      for (int b = 1; b <= n; ++b) worst = std::max(worst, (runs[k].position[b][i] - runs[0].position[b][i]).norm());
    std::printf("[   info   ] %s vs dense Schur: right-hand side %.2e relative, run %.2e m\n",
                k == 1 ? "sparse Schur" : "sparse LDL^T", acc, worst);
    EXPECT_LT(acc, 1e-11);
    // A run at rtol 1e-8: the step sequences see the same error estimates to
    // rounding, so positions agree to rounding too, far below the tolerance.
    EXPECT_LT(worst, 1e-11);
  }
}

}  // namespace
}  // namespace fc::mbs::test
