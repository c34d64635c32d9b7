#include "mbs-run/tree/kinematic_tree.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "common/rotations.h"

namespace fc::mbs {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

const char* typeName(JointType t) {
  switch (t) {
    case JointType::Spherical: return "spherical";
    case JointType::Revolute: return "revolute";
    case JointType::Fixed: return "fixed";
    case JointType::Universal: return "universal";
    case JointType::Cylindrical: return "cylindrical";
    case JointType::Prismatic: return "prismatic";
  }
  return "?";
}

struct Edge {
  int joint, child;
};

// Breadth-first from the fixed bodies: each joint met leads to a body not
// yet reached (its link), or closes a loop. Fills `order` (parents first) and
// returns "" for an open tree that reaches every moving body.
std::string treeOrder(const Model& m, std::vector<Edge>& order) {
  const std::size_t nb = m.bodies.size();
  std::vector<std::vector<int>> touching(nb);
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const Joint& jt = m.joints[j];
    if (m.bodies[jt.body_i].fixed && m.bodies[jt.body_j].fixed) return "joint " + jt.name + " joins two fixed bodies";
    touching[jt.body_i].push_back(int(j));
    touching[jt.body_j].push_back(int(j));
  }
  std::vector<char> reached(nb, 0), used(m.joints.size(), 0);
  std::deque<int> queue;
  for (std::size_t k = 0; k < nb; ++k)
    if (m.bodies[k].fixed) {
      reached[k] = 1;
      queue.push_back(int(k));
    }
  while (!queue.empty()) {
    const int b = queue.front();
    queue.pop_front();
    for (int j : touching[b]) {
      if (used[j]) continue;
      used[j] = 1;
      const Joint& jt = m.joints[j];
      const int other = jt.body_i == b ? jt.body_j : jt.body_i;
      if (reached[other]) return "joint " + jt.name + " closes a loop";
      reached[other] = 1;
      order.push_back({j, other});
      queue.push_back(other);
    }
  }
  for (std::size_t k = 0; k < nb; ++k)
    if (!reached[k]) return "body " + m.bodies[k].name + " is not joined to a fixed body (a floating base)";
  return "";
}

// Spatial cross products at O (Featherstone eqs. 2.31-2.33): motion x motion
// and motion x* force.
inline Vector6d crossMotion(const Vector6d& v, const Vector6d& m) {
  Vector6d r;
  const Vector3d w = v.head<3>(), vo = v.tail<3>();
  r.head<3>() = w.cross(m.head<3>());
  r.tail<3>() = w.cross(m.tail<3>()) + vo.cross(m.head<3>());
  return r;
}
inline Vector6d crossForce(const Vector6d& v, const Vector6d& f) {
  Vector6d r;
  const Vector3d w = v.head<3>(), vo = v.tail<3>();
  r.head<3>() = w.cross(f.head<3>()) + vo.cross(f.tail<3>());
  r.tail<3>() = w.cross(f.tail<3>());
  return r;
}

// Link k's motion subspace at poses P (kinematic_tree.h): revolute
// [n; x x n] with x the joint point on the child, prismatic [0; n].
Vector6d motionSubspace(const TreeLink& L, const std::vector<BodyPose>& P) {
  const BodyPose &pp = P[L.parent], &pc = P[L.body];
  const Vector3d nax = pp.A * L.axis;
  Vector6d S;
  if (L.prismatic) {
    S << Vector3d::Zero(), nax;
  } else {
    const Vector3d x = pc.r + pc.A * L.s_child;
    S << nax, x.cross(nax);
  }
  return S;
}

// A body's spatial velocity at O: (omega, v_O), v_O = rdot - omega x r.
Vector6d spatialVelocity(const BodyPose& pc) {
  const Vector3d w = pc.A * pc.w;
  Vector6d v;
  v << w, pc.rdot - w.cross(pc.r);
  return v;
}

// Spatial inertia at O of mass m at centre c with central inertia Ic:
// [[Ic + m C C^T, m C], [m C^T, m 1]], C = c~ (Featherstone eq. 2.63).
void spatialInertia(const Body& b, const BodyPose& pc, Matrix6d& I) {
  const Vector3d c = pc.r + pc.A * b.com;
  const Matrix3d C = fc::skew(c);
  I.topLeftCorner<3, 3>() = pc.A * b.inertia_com * pc.A.transpose() - b.mass * C * C;
  I.topRightCorner<3, 3>() = b.mass * C;
  I.bottomLeftCorner<3, 3>() = -b.mass * C;
  I.bottomRightCorner<3, 3>() = b.mass * Matrix3d::Identity();
}

// Q on the body's velocity coordinates [rdot, omega'] (a force at the frame
// origin and a torque in body axes) as a spatial force at O: (r x f + A n', f).
Vector6d spatialForce(const Body& b, const BodyPose& pc, const VectorXd& Q) {
  const Vector3d f = Q.segment<3>(b.dof_index), tq = pc.A * Q.segment<3>(b.dof_index + 3);
  Vector6d F;
  F << pc.r.cross(f) + tq, f;
  return F;
}

}  // namespace

std::vector<BodyPose> placedPoses(const Model& m) {
  std::vector<BodyPose> P(m.bodies.size());
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    BodyPose& p = P[k];
    p.r = b.position;
    p.p = b.orientation.normalized();
    p.A = fc::rotationMatrix(p.p);
    p.free = !b.fixed;
    p.rdot = b.fixed ? Vector3d::Zero() : b.velocity;
    p.w = b.fixed ? Vector3d::Zero() : Vector3d(p.A.transpose() * b.angular_velocity);
  }
  return P;
}

std::vector<JointRuntime> treeJointRuntimes(const Model& m, const std::vector<BodyPose>& P0) {
  std::vector<JointRuntime> rt(m.joints.size());
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const Joint& jt = m.joints[j];
    rt[j].enabled = jt.enabled;
    rt[j].locked = jt.locked;
    const BodyPose &bi = P0[jt.body_i], &bj = P0[jt.body_j];
    if (jt.type == JointType::Prismatic) captureLock(jt, rt[j], bi, bj);
    if (jt.type == JointType::Revolute) {
      rt[j].angle_offset = jt.initial_angle - rawRevoluteAngle(jt, bi, bj);
      rt[j].last_angle = jt.initial_angle;
    }
  }
  return rt;
}

std::string treeUnsupported(const Model& m) {
  for (const Body& b : m.bodies)
    if (b.flex || b.modes > 0) return "flexible body " + b.name;
  if (!m.events.empty()) return "events (the tree path has none)";
  if (m.settings.integrator == IntegratorKind::Imex) return "integrator imex (it splits modal stiffness; a rigid tree has none)";
  for (const Joint& jt : m.joints) {
    if (jt.type != JointType::Revolute && jt.type != JointType::Prismatic)
      return "joint " + jt.name + " is " + typeName(jt.type);
    if (!jt.enabled) return "joint " + jt.name + " starts disabled";
    if (jt.drive.active) return "joint " + jt.name + " is driven";
    if (jt.locked) return "joint " + jt.name + " is locked";
    if (jt.limits.any()) return "joint " + jt.name + " has stops";
    if (jt.stop_only) return "joint " + jt.name + " is stop_only";
  }
  std::vector<Edge> order;
  if (const std::string why = treeOrder(m, order); !why.empty()) return why;
  // The placement: every constraint within the constrained start's
  // tolerance (System::correctPositions: 1e-12 of the largest position, at
  // least 1 m), where that start leaves the poses as placed. !(<=) declines
  // a non-finite placement too.
  double scale = 1.0;
  for (const Body& b : m.bodies) scale = std::max(scale, b.position.norm());
  const std::vector<BodyPose> P0 = placedPoses(m);
  const std::vector<JointRuntime> rt = treeJointRuntimes(m, P0);
  ConstraintRows rows;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const Joint& jt = m.joints[j];
    jointConstraints(jt, rt[j], P0[jt.body_i], P0[jt.body_j], 0.0, rows);
    const double miss = rows.size() ? rows.phi.cwiseAbs().maxCoeff() : 0.0;
    if (!(miss <= kPlacementTolerance * scale)) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.3g", miss);
      return "joint " + jt.name + " does not hold as placed (misses by " + buf +
             " m or rad; the constrained start assembles it)";
    }
  }
  return "";
}

KinematicTree buildKinematicTree(const Model& m, const std::vector<BodyPose>& P0) {
  std::vector<Edge> order;
  if (const std::string why = treeOrder(m, order); !why.empty()) throw std::logic_error("not a kinematic tree: " + why);
  KinematicTree tree;
  tree.link_of_body.assign(m.bodies.size(), -1);
  tree.fixed.resize(m.bodies.size());
  for (std::size_t k = 0; k < m.bodies.size(); ++k)
    if (m.bodies[k].fixed) tree.fixed[k] = P0[k];
  for (const Edge& e : order) {
    const Joint& jt = m.joints[e.joint];
    TreeLink L;
    L.joint = e.joint;
    L.body = e.child;
    const bool child_is_j = jt.body_j == e.child;
    L.parent = child_is_j ? jt.body_i : jt.body_j;
    L.parent_link = tree.link_of_body[L.parent];
    L.prismatic = jt.type == JointType::Prismatic;
    L.s_parent = child_is_j ? jt.point_i : jt.point_j;
    L.s_child = child_is_j ? jt.point_j : jt.point_i;
    L.axis = (child_is_j ? jt.axis_i : jt.axis_j).normalized();
    const BodyPose &pp = P0[L.parent], &pc = P0[L.body];
    L.e0 = fc::quatProduct(fc::quatConjugate(pp.p.normalized()), pc.p.normalized());
    L.offset0 = pp.A.transpose() * ((pc.r + pc.A * L.s_child) - (pp.r + pp.A * L.s_parent));
    // The joint's angle turns body_j relative to body_i about axis_i; a link
    // from j to i turns i about axis_j, parallel or antiparallel to axis_i.
    const Vector3d ni = P0[jt.body_i].A * jt.axis_i.normalized(), nj = P0[jt.body_j].A * jt.axis_j.normalized();
    L.angle_sign = child_is_j ? 1.0 : -std::copysign(1.0, ni.dot(nj));
    tree.link_of_body[L.body] = tree.size();
    tree.links.push_back(L);
  }
  for (std::size_t f = 0; f < m.forces.size(); ++f) {
    const ForceElement& fe = m.forces[f];
    if (!fe.enabled) continue;
    if (fe.type == ForceType::Gravity) tree.gravity += fe.vector;
    else tree.other_forces.push_back(int(f));
  }
  return tree;
}

VectorXd treeRates(const KinematicTree& tree, const std::vector<BodyPose>& P0) {
  VectorXd qd(tree.size());
  for (int k = 0; k < tree.size(); ++k) {
    const TreeLink& L = tree.links[k];
    const BodyPose &pp = P0[L.parent], &pc = P0[L.body];
    const Vector3d n = pp.A * L.axis, wp = pp.A * pp.w, wc = pc.A * pc.w;
    if (L.prismatic) {
      // d/dt of n . (x_c - x_p) in the parent's frame: the relative velocity
      // of the two points less the parent's rotation of their offset.
      const Vector3d xp = pp.A * L.s_parent, xc = pc.A * L.s_child;
      const Vector3d d = (pc.r + xc) - (pp.r + xp);
      qd[k] = n.dot((pc.rdot + wc.cross(xc)) - (pp.rdot + wp.cross(xp)) - wp.cross(d));
    } else {
      qd[k] = n.dot(wc - wp);
    }
  }
  return qd;
}

void treePoses(const KinematicTree& tree, const VectorXd& q, const VectorXd& qd, std::vector<BodyPose>& P) {
  P.resize(tree.fixed.size());
  for (std::size_t k = 0; k < P.size(); ++k)
    if (tree.link_of_body[k] < 0) P[k] = tree.fixed[k];
  for (int k = 0; k < tree.size(); ++k) {
    const TreeLink& L = tree.links[k];
    const BodyPose& pp = P[L.parent];
    BodyPose& pc = P[L.body];
    const Vector3d wp = pp.A * pp.w, n = pp.A * L.axis;
    Vector3d x = pp.r + pp.A * L.s_parent;                  // joint point on the parent
    Vector3d xdot = pp.rdot + wp.cross(x - pp.r);           // its velocity
    Vector3d wc = wp;
    if (L.prismatic) {
      pc.p = fc::quatProduct(pp.p, L.e0);
      const Vector3d d = pp.A * (L.offset0 + L.axis * q[k]);
      xdot += wp.cross(d) + n * qd[k];
      x += d;                                               // now the child's point
    } else {
      pc.p = fc::quatProduct(fc::quatProduct(pp.p, fc::eulerParametersFromAxisAngle(L.axis, q[k])), L.e0);
      wc += n * qd[k];
    }
    pc.p.normalize();
    pc.A = fc::rotationMatrix(pc.p);
    pc.r = x - pc.A * L.s_child;
    pc.rdot = xdot + wc.cross(pc.r - x);
    pc.w = pc.A.transpose() * wc;
    pc.free = true;
  }
}

void treeAccelerations(const Model& m, const KinematicTree& tree, const std::vector<BodyPose>& P, const VectorXd& qd,
                       const VectorXd& Q, TreeWorkspace& ws, VectorXd& qdd) {
  const int n = tree.size();
  if (int(ws.S.size()) != n) {
    for (auto* v : {&ws.S, &ws.v, &ws.c, &ws.pA, &ws.U, &ws.a}) v->resize(n);
    ws.IA.resize(n);
    ws.D.resize(n);
    ws.u.resize(n);
  }
  qdd.resize(n);
  // Pass 1 (parents first): motion subspace, velocity, velocity-product
  // acceleration c_i, rigid-body inertia at O and bias force.
  for (int k = 0; k < n; ++k) {
    const TreeLink& L = tree.links[k];
    const Body& b = m.bodies[L.body];
    ws.S[k] = motionSubspace(L, P);
    ws.v[k] = spatialVelocity(P[L.body]);
    ws.c[k] = crossMotion(ws.v[k], ws.S[k] * qd[k]);
    spatialInertia(b, P[L.body], ws.IA[k]);
    ws.pA[k] = crossForce(ws.v[k], ws.IA[k] * ws.v[k]);
    if (Q.size()) ws.pA[k] -= spatialForce(b, P[L.body], Q);
  }
  // Pass 2 (children first): articulated inertias and bias forces.
  for (int k = n - 1; k >= 0; --k) {
    const TreeLink& L = tree.links[k];
    ws.U[k] = ws.IA[k] * ws.S[k];
    ws.D[k] = ws.S[k].dot(ws.U[k]);
    ws.u[k] = -ws.S[k].dot(ws.pA[k]);
    if (L.parent_link < 0) continue;
    const Matrix6d Ia = ws.IA[k] - ws.U[k] * ws.U[k].transpose() / ws.D[k];
    ws.pA[L.parent_link] += ws.pA[k] + Ia * ws.c[k] + ws.U[k] * (ws.u[k] / ws.D[k]);
    ws.IA[L.parent_link] += Ia;
  }
  // Pass 3 (parents first): accelerations; the fixed bodies accelerate at
  // -g, which puts gravity on every body.
  Vector6d a0;
  a0 << Vector3d::Zero(), -tree.gravity;
  for (int k = 0; k < n; ++k) {
    const TreeLink& L = tree.links[k];
    Vector6d& a = ws.a[k];
    a = (L.parent_link < 0 ? a0 : ws.a[L.parent_link]) + ws.c[k];
    qdd[k] = (ws.u[k] - ws.U[k].dot(a)) / ws.D[k];
    a += ws.S[k] * qdd[k];
  }
}

VectorXd treeProjectedRates(const Model& m, const KinematicTree& tree, const std::vector<BodyPose>& P0) {
  // The tree at rest at P0 without gravity, each body's momentum I_d v0_d
  // applied as a force (Q on its velocity coordinates, spatialForce's inverse).
  KinematicTree at_rest = tree;
  at_rest.gravity.setZero();
  std::vector<BodyPose> P = P0;
  VectorXd Q = VectorXd::Zero(m.nv);
  Matrix6d I;
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    P[k].rdot.setZero();
    P[k].w.setZero();
    if (b.fixed) continue;
    spatialInertia(b, P0[k], I);
    const Vector6d h = I * spatialVelocity(P0[k]);
    Q.segment<3>(b.dof_index) = h.tail<3>();
    Q.segment<3>(b.dof_index + 3) = P0[k].A.transpose() * (h.head<3>() - P0[k].r.cross(h.tail<3>()));
  }
  TreeWorkspace ws;
  VectorXd qd;
  treeAccelerations(m, at_rest, P, VectorXd::Zero(tree.size()), Q, ws, qd);
  return qd;
}

std::vector<JointReaction> treeReactions(const Model& m, const KinematicTree& tree, const std::vector<BodyPose>& P,
                                         const VectorXd& qd, const VectorXd& qdd, const VectorXd& Q) {
  const int n = tree.size();
  std::vector<Vector6d> f(n), a(n);
  Vector6d a0;
  a0 << Vector3d::Zero(), -tree.gravity;
  Matrix6d I;
  // Forward (parents first): accelerations as the ABA's pass 3, then each
  // body's inertial force less its external forces.
  for (int k = 0; k < n; ++k) {
    const TreeLink& L = tree.links[k];
    const Body& b = m.bodies[L.body];
    const Vector6d S = motionSubspace(L, P), v = spatialVelocity(P[L.body]);
    a[k] = (L.parent_link < 0 ? a0 : a[L.parent_link]) + crossMotion(v, S * qd[k]) + S * qdd[k];
    spatialInertia(b, P[L.body], I);
    f[k] = I * a[k] + crossForce(v, I * v);
    if (Q.size()) f[k] -= spatialForce(b, P[L.body], Q);
  }
  // Backward (children first): each subtree's force carried to its parent.
  for (int k = n - 1; k >= 0; --k)
    if (tree.links[k].parent_link >= 0) f[tree.links[k].parent_link] += f[k];
  std::vector<JointReaction> out(m.joints.size());
  for (int k = 0; k < n; ++k) {
    const TreeLink& L = tree.links[k];
    const Joint& jt = m.joints[L.joint];
    const Vector6d on_i = jt.body_i == L.body ? f[k] : Vector6d(-f[k]);
    const BodyPose& bi = P[jt.body_i];
    const Vector3d x = bi.r + bi.A * jt.point_i;  // the joint's point on body i
    JointReaction& r = out[L.joint];
    r.force = on_i.tail<3>();
    r.torque = on_i.head<3>() - x.cross(r.force);  // moment about x of a force at O
  }
  return out;
}

VectorXd constrainedState(const Model& m, const std::vector<BodyPose>& P, double dissipated, double applied_work) {
  VectorXd y = VectorXd::Zero(m.nq + m.nv + 2);
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    if (b.fixed) continue;
    y.segment<3>(b.pos_index) = P[k].r;
    y.segment<4>(b.pos_index + 3) = P[k].p;
    y.segment<3>(m.nq + b.dof_index) = P[k].rdot;
    y.segment<3>(m.nq + b.dof_index + 3) = P[k].w;
  }
  y[m.nq + m.nv] = dissipated;
  y[m.nq + m.nv + 1] = applied_work;
  return y;
}

}  // namespace fc::mbs
