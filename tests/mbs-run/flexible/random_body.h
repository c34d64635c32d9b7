#pragma once
// Test bodies whose invariants nobody precomputed: random lumped masses, rotary
// inertias and modes made mass-orthonormal, plus brute-force sums over the nodes
// (kinetic energy, momenta) that serve as the reference for the invariant-based
// kernels. Header-only, shared by the flexible-body tests.
#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <string>

#include "common/flexbody.h"

namespace fc::testing {

// n nodes in a box of half-size `size`, nm modes orthonormal with respect to the
// lumped mass diag(m, m, m, J1, J2, J3) per node, eigenvalues (2 pi f)^2 with f in
// [f_min, f_max] Hz ascending, and one interface per listed node (its own shapes).
inline FlexBody randomBody(int n, int nm, unsigned seed, double size = 1.0, double f_min = 1.0,
                           double f_max = 4.0) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  FlexBody b;
  b.name = "random" + std::to_string(seed);
  b.nodes.resize(n, 3);
  b.nodal_mass.resize(n, 4);
  for (int k = 0; k < n; ++k) {
    for (int d = 0; d < 3; ++d) b.nodes(k, d) = size * u(gen);
    b.nodal_mass(k, 0) = 1.25 + 0.75 * u(gen);
    for (int d = 1; d < 4; ++d) b.nodal_mass(k, d) = 0.055 + 0.045 * u(gen);
  }
  Eigen::VectorXd mdiag(6 * n);
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 6; ++d) mdiag(6 * k + d) = b.nodal_mass(k, d < 3 ? 0 : d - 2);
  Eigen::MatrixXd X0(6 * n, nm);
  for (int i = 0; i < X0.size(); ++i) X0.data()[i] = u(gen);
  const Eigen::MatrixXd gram = X0.transpose() * mdiag.asDiagonal() * X0;
  const Eigen::LLT<Eigen::MatrixXd> llt(gram);
  // X = X0 L^-T so that X^T M X = L^-1 (L L^T) L^-T = I.
  b.shapes = llt.matrixL().solve(X0.transpose()).transpose();
  b.eigenvalues.resize(nm);
  b.frequencies_hz.resize(nm);
  for (int j = 0; j < nm; ++j) {
    const double f = nm > 1 ? f_min + (f_max - f_min) * j / (nm - 1) : f_min;
    b.frequencies_hz(j) = f;
    b.eigenvalues(j) = std::pow(2.0 * M_PI * f, 2);
  }
  for (int k : {0, n / 2}) {
    FlexInterface it;
    it.name = "P" + std::to_string(k);
    it.node = k;
    it.position = b.nodes.row(k).transpose();
    it.shapes = b.shapes.middleRows(6 * k, 6).transpose();
    b.interfaces.push_back(it);
  }
  b.elements["triangles"] = IndexMatrix(1, 3);
  b.elements["triangles"] << 0, 1, 2;
  setRigidPropertiesFromLumpedMasses(b);
  return b;
}

// Brute-force state of every lumped node, the reference for the kernels.
struct BruteForce {
  const FlexBody& body;
  int nm;

  Eigen::MatrixXd Phi(long k) const { return body.shapes.block(6 * k, 0, 3, nm); }
  Eigen::MatrixXd Theta(long k) const { return body.shapes.block(6 * k + 3, 0, 3, nm); }
  Eigen::Vector3d s(long k, const Eigen::VectorXd& w) const {
    return body.nodes.row(k).transpose() + Phi(k) * w;
  }
  // Global velocity of node k for v = [rdot, omega', wdot].
  Eigen::Vector3d velocity(long k, const Eigen::Matrix3d& A, const Eigen::VectorXd& w,
                           const Eigen::VectorXd& v) const {
    const Eigen::Vector3d om = v.segment<3>(3);
    return v.head<3>() + A * (om.cross(s(k, w)) + Phi(k) * v.tail(nm));
  }
  // Angular velocity of node k's rotary inertia, body axes (the model of flexbody.h).
  Eigen::Vector3d spin(long k, const Eigen::VectorXd& v) const {
    return v.segment<3>(3) + Theta(k) * v.tail(nm);
  }
  Eigen::Matrix3d J(long k) const { return body.nodal_mass.row(k).tail<3>().asDiagonal(); }

  double kinetic(const Eigen::Matrix3d& A, const Eigen::VectorXd& w, const Eigen::VectorXd& v) const {
    double T = 0.0;
    for (long k = 0; k < body.nodeCount(); ++k) {
      T += 0.5 * body.nodal_mass(k, 0) * velocity(k, A, w, v).squaredNorm();
      const Eigen::Vector3d o = spin(k, v);
      T += 0.5 * o.dot(J(k) * o);
    }
    return T;
  }
  Eigen::Vector3d linearMomentum(const Eigen::Matrix3d& A, const Eigen::VectorXd& w,
                                 const Eigen::VectorXd& v) const {
    Eigen::Vector3d L = Eigen::Vector3d::Zero();
    for (long k = 0; k < body.nodeCount(); ++k) L += body.nodal_mass(k, 0) * velocity(k, A, w, v);
    return L;
  }
  // About the global origin: sum m x_k x xdot_k + sum A J_k spin_k.
  Eigen::Vector3d angularMomentum(const Eigen::Vector3d& r, const Eigen::Matrix3d& A,
                                  const Eigen::VectorXd& w, const Eigen::VectorXd& v) const {
    Eigen::Vector3d H = Eigen::Vector3d::Zero();
    for (long k = 0; k < body.nodeCount(); ++k) {
      const Eigen::Vector3d x = r + A * s(k, w);
      H += body.nodal_mass(k, 0) * x.cross(velocity(k, A, w, v)) + A * (J(k) * spin(k, v));
    }
    return H;
  }
};

}  // namespace fc::testing
