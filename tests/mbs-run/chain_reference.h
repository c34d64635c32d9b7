#pragma once
// the independent reference for rigid chains: the planar N-link
// pendulum of uniform links in absolute link angles phi_i (from the +x axis
// towards +z, in the x-z plane), from d'Alembert's principle on the links'
// centres p_k = sum_{j<k} l u(phi_j) + l/2 u(phi_k), u = (cos, sin):
//   sum_j m A_ij [cos(phi_i - phi_j) phi_j'' - sin(phi_j - phi_i) phi_j'^2]
//     + I_c phi_i'' + m g cos(phi_i) sum_k a_ki = 0,
// a_ki = dp_k/du(phi_i) = l (i < k), l/2 (i = k), 0 (i > k), A_ij = sum_k a_ki a_kj.
// No constraints, no multipliers, no Euler parameters: nothing in common
// with mbs-run's augmented Lagrangian path but the physics. The mass matrix
// is dense (O(N^3) per evaluation): for N up to a few hundred.
// Used by tests/mbs-run/test_chain_reference.cpp, test_kinematic_tree.cpp,
// test_run_quality.cpp and bench/mbs-run (bench_chains.cpp, chain_scene.h).
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

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

// The same chain as an mbs-run scene: n thin links (length l, mass m,
// centroidal inertia m l^2 / 12 about the joint axis y, 1e-7 about their
// own axis, which only enters an idle spin) on revolute joints about y,
// laid out along +x from the ground's origin, gravity -z; `simulation` is the
// scene's simulation block.
inline std::string thinLinkChainScene(int n, double l, double m, const std::string& simulation) {
  std::string b = "bodies:\n  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n";
  std::string j = "joints:\n";
  char s[400];
  for (int k = 0; k < n; ++k) {
    std::snprintf(s, sizeof s,
                  "  - {name: L%d, rigid: {mass: %g, inertia: [[1e-7,0,0],[0,%.17g,0],[0,0,%.17g]]}, position: "
                  "[%.17g, 0, 0]}\n",
                  k, m, m * l * l / 12, m * l * l / 12, (k + 0.5) * l);
    b += s;
    std::snprintf(s, sizeof s,
                  "  - {name: J%d, type: revolute, bodies: [%s, L%d], points: [[%g, 0, 0], [%g, 0, 0]], axes: "
                  "[[0, 1, 0], [0, 1, 0]]}\n",
                  k, k ? ("L" + std::to_string(k - 1)).c_str() : "ground", k, k ? l / 2 : 0.0, -l / 2);
    j += s;
  }
  return b + j + "forces:\n  - {type: gravity, g: [0, 0, -9.81]}\nsimulation: " + simulation + "\n";
}

// n rods (0.1 m, 0.1 kg, 10 mm across) on revolute joints about y along +x
// from the ground's origin, gravity -z: the chain of the benchmarks
// (bench/mbs-run) and of the run-quality tests.
inline std::string rodChainScene(int n, const std::string& simulation) {
  std::string y = "bodies:\n  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n";
  std::string j = "joints:\n";
  for (int k = 0; k < n; ++k) {
    y += "  - {name: L" + std::to_string(k) + ", rod: {length: 0.1, diameter: 0.01, mass: 0.1}, position: [" +
         std::to_string(0.05 + 0.1 * k) + ", 0, 0]}\n";
    const std::string prev = k ? "L" + std::to_string(k - 1) : "ground";
    const std::string at = k ? "[0.05, 0, 0]" : "[0, 0, 0]";
    j += "  - {name: J" + std::to_string(k) + ", type: revolute, bodies: [" + prev + ", L" + std::to_string(k) +
         "], points: [" + at + ", [-0.05, 0, 0]], axes: [[0, 1, 0], [0, 1, 0]]}\n";
  }
  return y + j + "forces:\n  - {type: gravity, g: [0, 0, -9.81]}\nsimulation: " + simulation + "\n";
}

}  // namespace fc::mbs::test
