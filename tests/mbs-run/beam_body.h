#pragma once
// A uniform Euler-Bernoulli cantilever as a reduced flexible body, written
// here (not by fe-prep) so the validation tests control every number: Hermite
// cubic bending elements in the body x-y plane (transverse displacement v
// along body y, rotation theta_z = dv/dx), clamped at the root node 0 (the
// body-frame origin), lumped masses rho A h (half at the ends) and rotary
// inertias m_k h^2 / 12 (the slice's own inertia; it vanishes as h -> 0 and
// keeps the lumped mass matrix positive definite). The modes are the
// mass-orthonormal eigenvectors of K phi = omega^2 M phi, so they are the
// clamped-root (fixed-interface) modes a floating frame at the root needs.
// Interfaces: "root" (node 0, shapes zero) and "tip" (last node).
//
// Also a brute-force planar reference: the same lumped masses swung about the
// root in the x-y plane, in minimal coordinates (theta, w), with each node's
// acceleration written out (no inertia invariants, no constraints), for the
// flexible pendulum and spin-up tests.
#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "common/flexbody.h"
#include "helpers.h"

namespace fc::mbs::test {

struct BeamSpec {
  double length = 1.0, rho_a = 1.0, ei = 80.0;  // [m], [kg/m], [N m^2]
  int elements = 20;
  int modes = 6;                 // kept in the file
  double stiffness_scale = 1.0;  // multiplies K (eigenvalues), shapes unchanged
  // Pinned root: node 0 keeps its rotation; the rigid rotation about the pin
  // (eigenvalue 0) is dropped and the next `modes` kept (the reference
  // condition of a hinge, as fe-prep's "pin").
  bool pinned_root = false;
  // false: no rotary inertia at the nodes (a section whose bending rotary
  // inertia is neglected): the rotations carry no mass and are
  // condensed statically (exact for such a lumped mass), leaving one mode per
  // free translational dof.
  bool rotary_inertia = true;
};

struct BeamModel {
  FlexBody body;
  Eigen::MatrixXd K, M;  // reduced (clamped) FE matrices, 2 dofs per free node
  Eigen::VectorXd node_mass, node_rotary;  // per node incl. root
};

inline BeamModel cantileverBeam(const BeamSpec& s) {
  const int ne = s.elements, nn = ne + 1, p = s.pinned_root ? 1 : 0;
  const int nd = 2 * ne + p;  // free dofs: [theta_0 if pinned], (v, theta) of nodes 1..ne
  const double h = s.length / ne;
  BeamModel b;
  b.K = Eigen::MatrixXd::Zero(nd, nd);
  Eigen::Matrix4d ke;
  ke << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h, 2 * h * h,
      -6 * h, 4 * h * h;
  ke *= s.ei * s.stiffness_scale / (h * h * h);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c) {
        // Element e's local dof a is global 2e + a - 2 (+ p); the root's
        // translation is always fixed, its rotation only when clamped.
        const int ga = 2 * e + a - 2 + p, gc = 2 * e + c - 2 + p;
        if (ga >= 0 && gc >= 0) b.K(ga, gc) += ke(a, c);
      }
  b.node_mass = Eigen::VectorXd::Constant(nn, s.rho_a * h);
  b.node_mass(0) *= 0.5;
  b.node_mass(ne) *= 0.5;
  b.node_rotary = b.node_mass * (h * h / 12.0);
  b.M = Eigen::MatrixXd::Zero(nd, nd);
  if (p) b.M(0, 0) = b.node_rotary(0);
  for (int k = 1; k < nn; ++k) {
    b.M(2 * k - 2 + p, 2 * k - 2 + p) = b.node_mass(k);
    b.M(2 * k - 1 + p, 2 * k - 1 + p) = b.node_rotary(k);
  }
  if (!s.rotary_inertia) b.node_rotary.setZero();
  // Without rotary inertia: condense the rotations, K* = Ktt - Ktr Krr^-1 Krt
  // on the translations t, rotations from r = -Krr^-1 Krt t.
  std::vector<int> tr, rot;
  for (int d = 0; d < nd; ++d) ((d - p) % 2 == 0 && d >= p ? tr : rot).push_back(d);
  Eigen::MatrixXd phi_all(nd, nd);
  Eigen::VectorXd lambda_all(nd);
  if (s.rotary_inertia) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(b.K, b.M);
    phi_all = es.eigenvectors();
    lambda_all = es.eigenvalues();
  } else {
    const int nt = int(tr.size()), nr = int(rot.size());
    Eigen::MatrixXd Ktt(nt, nt), Ktr(nt, nr), Krr(nr, nr), Mtt = Eigen::MatrixXd::Zero(nt, nt);
    for (int a = 0; a < nt; ++a) {
      for (int c = 0; c < nt; ++c) Ktt(a, c) = b.K(tr[a], tr[c]);
      for (int c = 0; c < nr; ++c) Ktr(a, c) = b.K(tr[a], rot[c]);
      Mtt(a, a) = b.M(tr[a], tr[a]);
    }
    for (int a = 0; a < nr; ++a)
      for (int c = 0; c < nr; ++c) Krr(a, c) = b.K(rot[a], rot[c]);
    const Eigen::MatrixXd R = -Krr.ldlt().solve(Ktr.transpose());  // rotations per translation
    const Eigen::MatrixXd Ks = Ktt + Ktr * R;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ks, Mtt);
    phi_all.setZero(nd, nt);
    for (int a = 0; a < nt; ++a) phi_all.row(tr[a]) = es.eigenvectors().row(a);
    const Eigen::MatrixXd rv = R * es.eigenvectors();
    for (int a = 0; a < nr; ++a) phi_all.row(rot[a]) = rv.row(a);
    lambda_all = es.eigenvalues();
    b.M.setZero();
    for (int a = 0; a < nt; ++a) b.M(tr[a], tr[a]) = Mtt(a, a);
  }
  FlexBody& f = b.body;
  f.name = "beam";
  f.nodes = Eigen::MatrixXd::Zero(nn, 3);
  f.nodal_mass.resize(nn, 4);
  for (int k = 0; k < nn; ++k) {
    f.nodes(k, 0) = k * h;
    // Torsional and out-of-plane rotary inertias: any positive values (they
    // are not excited in plane), here those of the slice as well.
    // Without bending rotary inertia the polar one (about the axis) stays:
    // a body whose mass lies on a line is rejected by the body file writer.
    const double polar = s.rotary_inertia ? b.node_rotary(k) : b.node_mass(k) * h * h / 12.0;
    f.nodal_mass.row(k) << b.node_mass(k), polar, b.node_rotary(k), b.node_rotary(k);
  }
  const int nm = s.modes;
  f.shapes = Eigen::MatrixXd::Zero(6 * nn, nm);
  // Pinned: the first eigenvalue is the rigid rotation about the pin (zero),
  // dropped. Condensed pinned beams have it too (the rotation carries the
  // translations along).
  f.eigenvalues = lambda_all.segment(p, nm);
  f.frequencies_hz = f.eigenvalues.array().sqrt() / (2 * M_PI);
  for (int j = 0; j < nm; ++j) {
    Eigen::VectorXd phi = phi_all.col(j + p);  // M-orthonormal
    if (phi(nd - 2) < 0) phi = -phi;                     // tip moves along +y
    if (p) f.shapes(5, j) = phi(0);
    for (int k = 1; k < nn; ++k) {
      f.shapes(6 * k + 1, j) = phi(2 * k - 2 + p);
      f.shapes(6 * k + 5, j) = phi(2 * k - 1 + p);
    }
  }
  for (int k : {0, ne}) {
    FlexInterface it;
    it.name = k == 0 ? "root" : "tip";
    it.node = k;
    it.position = f.nodes.row(k).transpose();
    it.shapes = f.shapes.middleRows(6 * k, 6).transpose();
    f.interfaces.push_back(it);
  }
  f.elements["beams"] = IndexMatrix(ne, 2);
  for (int e = 0; e < ne; ++e) f.elements["beams"].row(e) << e, e + 1;
  setRigidPropertiesFromLumpedMasses(f);
  return b;
}

inline std::string writeBeam(const BeamModel& b, const std::string& tag) {
  return writeTempBody(b.body, "flexval_" + tag);
}

// Planar motion of the lumped beam about its root (a revolute about z at the
// origin), minimal coordinates q = [theta, w_1..w_nm]. Node k: body position
// s_k = (x_k, Phi_k w), global x_k = R(theta) s_k, rotary inertia J_k spinning
// at theta_dot + Theta_k w_dot. Lagrange's equations per node:
//   sum m_k J_k^T (J_k qdd + a_k) + sum J_k^rot (theta_dd + Theta_k wdd) [1; Theta_k^T]
//     + [0; Lambda w + D w_dot] = sum m_k J_k^T g,
// J_k = [R' s_k, R Phi_k], a_k = R'' s_k theta_dot^2 + 2 R' Phi_k w_dot theta_dot.
struct PlanarBeam {
  const FlexBody& body;
  int nm;
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  Eigen::VectorXd damping;  // 2 zeta omega per mode (empty: none)

  // Returns qdd; if `prescribed`, theta_dd is given and only the modal rows are solved.
  Eigen::VectorXd accel(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, bool prescribed = false,
                        double theta_dd = 0.0) const {
    const int n = 1 + nm;
    const double th = q(0), c = std::cos(th), sn = std::sin(th);
    Eigen::Matrix2d R, Rp;
    R << c, -sn, sn, c;
    Rp << -sn, -c, c, -sn;
    const Eigen::VectorXd w = q.tail(nm), wd = qd.tail(nm);
    Eigen::MatrixXd Mq = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    for (long k = 0; k < body.nodeCount(); ++k) {
      const double m = body.nodal_mass(k, 0), J = body.nodal_mass(k, 3);
      const Eigen::RowVectorXd phi = body.shapes.row(6 * k + 1).head(nm);
      const Eigen::RowVectorXd thz = body.shapes.row(6 * k + 5).head(nm);
      const Eigen::Vector2d sk(body.nodes(k, 0), phi.dot(w));
      Eigen::MatrixXd Jk(2, n);
      Jk.col(0) = Rp * sk;
      Jk.rightCols(nm) = R.col(1) * phi;
      const Eigen::Vector2d a = -R * sk * qd(0) * qd(0) + 2 * Rp.col(1) * phi.dot(wd) * qd(0);
      Mq += m * Jk.transpose() * Jk;
      f += m * Jk.transpose() * (g - a);
      Eigen::RowVectorXd jr(n);
      jr << 1.0, thz;
      Mq += J * jr.transpose() * jr;
    }
    for (int j = 0; j < nm; ++j) {
      f(1 + j) -= body.eigenvalues(j) * w(j);
      if (damping.size()) f(1 + j) -= damping(j) * wd(j);
    }
    Eigen::VectorXd qdd(n);
    if (!prescribed) return Mq.ldlt().solve(f);
    qdd(0) = theta_dd;
    qdd.tail(nm) = Mq.bottomRightCorner(nm, nm).ldlt().solve(f.tail(nm) - Mq.bottomLeftCorner(nm, 1) * theta_dd);
    return qdd;
  }
};

// Two such beams in a planar chain: beam 1 hinged at the origin, beam 2's root
// hinged at beam 1's tip (both about z). Minimal coordinates
// q = [theta1, w1 (nm1), theta2, w2 (nm2)], absolute angles. Beam 2's node k:
// x = R1 (p1 + Phi1_tip w1) + R2 s2_k(w2), so its Jacobian carries beam 1's
// tip motion; the same node-by-node Lagrange equations as PlanarBeam.
struct PlanarDoubleBeam {
  const FlexBody& b1;
  const FlexBody& b2;
  int nm1, nm2;
  Eigen::Vector2d g = Eigen::Vector2d::Zero();

  Eigen::VectorXd accel(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    const int n = 2 + nm1 + nm2, i2 = 1 + nm1;  // index of theta2
    auto rot = [](double th, Eigen::Matrix2d& R, Eigen::Matrix2d& Rp) {
      const double c = std::cos(th), sn = std::sin(th);
      R << c, -sn, sn, c;
      Rp << -sn, -c, c, -sn;
    };
    Eigen::Matrix2d R1, R1p, R2, R2p;
    rot(q(0), R1, R1p);
    rot(q(i2), R2, R2p);
    const Eigen::VectorXd w1 = q.segment(1, nm1), wd1 = qd.segment(1, nm1);
    const Eigen::VectorXd w2 = q.tail(nm2), wd2 = qd.tail(nm2);
    Eigen::MatrixXd Mq = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    const long tip = b1.nodeCount() - 1;
    const Eigen::RowVectorXd phi_tip = b1.shapes.row(6 * tip + 1).head(nm1);
    const Eigen::Vector2d p1(b1.nodes(tip, 0), phi_tip.dot(w1));  // beam 1's deformed tip, body 1 frame
    for (int body = 0; body < 2; ++body) {
      const FlexBody& b = body == 0 ? b1 : b2;
      const int nm = body == 0 ? nm1 : nm2, it = body == 0 ? 0 : i2;
      const Eigen::Matrix2d& R = body == 0 ? R1 : R2;
      const Eigen::Matrix2d& Rp = body == 0 ? R1p : R2p;
      const Eigen::VectorXd& w = body == 0 ? w1 : w2;
      const Eigen::VectorXd& wd = body == 0 ? wd1 : wd2;
      for (long k = 0; k < b.nodeCount(); ++k) {
        const double m = b.nodal_mass(k, 0), J = b.nodal_mass(k, 3);
        const Eigen::RowVectorXd phi = b.shapes.row(6 * k + 1).head(nm);
        const Eigen::RowVectorXd thz = b.shapes.row(6 * k + 5).head(nm);
        const Eigen::Vector2d sk(b.nodes(k, 0), phi.dot(w));
        Eigen::MatrixXd Jk = Eigen::MatrixXd::Zero(2, n);
        const Eigen::Vector2d jt = Rp * sk;
        Jk(0, it) = jt(0);  // element-wise: GCC 12 reports a false -Wstringop-overread
        Jk(1, it) = jt(1);  // on a vectorised copy into a dynamic column
        Jk.middleCols(it + 1, nm) = R.col(1) * phi;
        Eigen::Vector2d a = -R * sk * qd(it) * qd(it) + 2 * Rp.col(1) * phi.dot(wd) * qd(it);
        if (body == 1) {  // carried by beam 1's tip
          Jk.col(0) = R1p * p1;
          Jk.middleCols(1, nm1) = R1.col(1) * phi_tip;
          a += -R1 * p1 * qd(0) * qd(0) + 2 * R1p.col(1) * phi_tip.dot(wd1) * qd(0);
        }
        Mq += m * Jk.transpose() * Jk;
        f += m * Jk.transpose() * (g - a);
        Eigen::RowVectorXd jr = Eigen::RowVectorXd::Zero(n);
        jr(it) = 1.0;
        jr.segment(it + 1, nm) = thz;
        Mq += J * jr.transpose() * jr;
      }
      for (int j = 0; j < nm; ++j) f(it + 1 + j) -= b.eigenvalues(j) * w(j);
    }
    return Mq.ldlt().solve(f);
  }
};

}  // namespace fc::mbs::test
