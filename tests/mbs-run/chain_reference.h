#pragma once
// Issue 17's independent reference for rigid chains: the planar N-link
// pendulum of uniform links in absolute link angles phi_i (from the +x axis
// towards +z, in the x-z plane), from d'Alembert's principle on the links'
// centres p_k = sum_{j<k} l u(phi_j) + l/2 u(phi_k), u = (cos, sin):
//   sum_j m A_ij [cos(phi_i - phi_j) phi_j'' - sin(phi_j - phi_i) phi_j'^2]
//     + I_c phi_i'' + m g cos(phi_i) sum_k a_ki = 0,
// a_ki = dp_k/du(phi_i) = l (i < k), l/2 (i = k), 0 (i > k), A_ij = sum_k a_ki a_kj.
// No constraints, no multipliers, no Euler parameters: nothing in common
// with mbs-run's augmented Lagrangian path but the physics. The mass matrix
// is dense (O(N^3) per evaluation): for N up to a few hundred.
// Used by tests/mbs-run/test_chain_reference.cpp and bench/mbs-run/bench_chains.cpp.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace fc::mbs::test {

struct MinimalChain {
  int n;
  double l, m, ic, g;    // link length, mass, centroidal inertia about the joint axis, gravity
  Eigen::MatrixXd A;     // A_ij
  Eigen::VectorXd sa;    // sum_k a_ki
  MinimalChain(int n_links, double length, double mass, double inertia, double gravity)
      : n(n_links), l(length), m(mass), ic(inertia), g(gravity), A(n_links, n_links), sa(n_links) {
    for (int i = 0; i < n; ++i) {
      sa[i] = l / 2 + (n - 1 - i) * l;
      for (int j = 0; j < n; ++j) {
        const int hi = std::max(i, j);
        A(i, j) = (i == j ? l * l / 4 : l * l / 2) + (n - 1 - hi) * l * l;
      }
    }
  }
  // y = [phi, phi'].
  Eigen::VectorXd f(const Eigen::VectorXd& y) const {
    const Eigen::VectorXd phi = y.head(n), om = y.tail(n);
    Eigen::MatrixXd M(n, n);
    Eigen::VectorXd rhs(n);
    for (int i = 0; i < n; ++i) {
      rhs[i] = -m * g * std::cos(phi[i]) * sa[i];
      for (int j = 0; j < n; ++j) {
        M(i, j) = m * A(i, j) * std::cos(phi[i] - phi[j]);
        rhs[i] += m * A(i, j) * std::sin(phi[j] - phi[i]) * om[j] * om[j];
      }
      M(i, i) += ic;
    }
    Eigen::VectorXd d(2 * n);
    d.head(n) = om;
    d.tail(n) = M.llt().solve(rhs);
    return d;
  }
  // Centre of link k in (x, z).
  Eigen::Vector2d centre(const Eigen::VectorXd& y, int k) const {
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    for (int j = 0; j <= k; ++j) p += (j < k ? l : l / 2) * Eigen::Vector2d(std::cos(y[j]), std::sin(y[j]));
    return p;
  }
};

}  // namespace fc::mbs::test
