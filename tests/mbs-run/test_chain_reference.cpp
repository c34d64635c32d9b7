// Issue 17: a planar chain of N uniform rods on revolute joints, released at
// rest from the horizontal, against an independent minimal-coordinate model
// written here: the N-link pendulum in absolute link angles phi_i (from the
// +x axis towards +z, in the x-z plane), from d'Alembert's principle on the
// rods' centres p_k = sum_{j<k} l u(phi_j) + l/2 u(phi_k), u = (cos, sin):
//   sum_j m A_ij [cos(phi_i - phi_j) phi_j'' - sin(phi_j - phi_i) phi_j'^2]
//     + I_c phi_i'' + m g cos(phi_i) sum_k a_ki = 0,
// a_ki = dp_k/du(phi_i) = l (i < k), l/2 (i = k), 0 (i > k), A_ij = sum_k a_ki a_kj,
// integrated by RK4 at a fixed step. No constraints, no multipliers, no
// Euler parameters: nothing in common with mbs-run's augmented Lagrangian
// path but the physics. N = 10 runs the block Schur solve, N = 50 (250
// constraint rows) the sparse LDL^T.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "helpers.h"
#include "mbs-run/simulation.h"

namespace fc::mbs::test {
namespace {

constexpr double kL = 0.1, kM = 0.1, kG = 9.81;

struct Chain {
  int n;
  Eigen::MatrixXd A;    // A_ij
  Eigen::VectorXd sa;   // sum_k a_ki
  explicit Chain(int n_links) : n(n_links), A(n_links, n_links), sa(n_links) {
    for (int i = 0; i < n; ++i) {
      sa[i] = kL / 2 + (n - 1 - i) * kL;
      for (int j = 0; j < n; ++j) {
        const int hi = std::max(i, j);
        A(i, j) = (i == j ? kL * kL / 4 : kL * kL / 2) + (n - 1 - hi) * kL * kL;
      }
    }
  }
  // y = [phi, phi'].
  Eigen::VectorXd f(const Eigen::VectorXd& y) const {
    const Eigen::VectorXd phi = y.head(n), om = y.tail(n);
    Eigen::MatrixXd M(n, n);
    Eigen::VectorXd rhs(n);
    for (int i = 0; i < n; ++i) {
      rhs[i] = -kM * kG * std::cos(phi[i]) * sa[i];
      for (int j = 0; j < n; ++j) {
        M(i, j) = kM * A(i, j) * std::cos(phi[i] - phi[j]);
        rhs[i] += kM * A(i, j) * std::sin(phi[j] - phi[i]) * om[j] * om[j];
      }
      M(i, i) += kM * kL * kL / 12;
    }
    Eigen::VectorXd d(2 * n);
    d.head(n) = om;
    d.tail(n) = M.llt().solve(rhs);
    return d;
  }
  // Centre of rod k in (x, z).
  Eigen::Vector2d centre(const Eigen::VectorXd& y, int k) const {
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    for (int j = 0; j <= k; ++j) p += (j < k ? kL : kL / 2) * Eigen::Vector2d(std::cos(y[j]), std::sin(y[j]));
    return p;
  }
};

std::string chainScene(int n, double t_end, double rtol, double atol) {
  std::string b = "bodies:\n  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n";
  std::string j = "joints:\n";
  char s[400];
  for (int k = 0; k < n; ++k) {
    // Thin rods along body x: the axial inertia only enters an idle spin.
    std::snprintf(s, sizeof s,
                  "  - {name: L%d, rigid: {mass: %g, inertia: [[1e-7,0,0],[0,%.17g,0],[0,0,%.17g]]}, position: "
                  "[%.17g, 0, 0]}\n",
                  k, kM, kM * kL * kL / 12, kM * kL * kL / 12, (k + 0.5) * kL);
    b += s;
    std::snprintf(s, sizeof s,
                  "  - {name: J%d, type: revolute, bodies: [%s, L%d], points: [[%g, 0, 0], [%g, 0, 0]], axes: "
                  "[[0, 1, 0], [0, 1, 0]]}\n",
                  k, k ? ("L" + std::to_string(k - 1)).c_str() : "ground", k, k ? kL / 2 : 0.0, -kL / 2);
    j += s;
  }
  std::snprintf(s, sizeof s, "simulation: {t_end: %g, output_step: %g, rtol: %g, atol: %g, integrator: dopri5}\n",
                t_end, t_end / 10, rtol, atol);
  return b + j + "forces:\n  - {type: gravity, g: [0, 0, -9.81]}\n" + s;
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

}  // namespace
}  // namespace fc::mbs::test
