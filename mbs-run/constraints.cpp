#include "mbs-run/constraints.h"

#include <cmath>

#include "common/rotations.h"

namespace fc::mbs {

using Eigen::Vector3d;

void ConstraintRows::resize(int n, int nvi, int nvj) {
  Ji.setZero(n, nvi);
  Jj.setZero(n, nvj);
  phi.setZero(n);
  phit.setZero(n);
  c.setZero(n);
}

namespace {

constexpr double kPi = 3.14159265358979323846;

void spherical(const Attached& xi, const Attached& xj, ConstraintRows& o, int row) {
  o.phi.segment<3>(row) = xj.x - xi.x;
  o.Ji.middleRows<3>(row) = -xi.J;
  o.Jj.middleRows<3>(row) = xj.J;
  o.c.segment<3>(row) = xj.extra - xi.extra;
}

// a on body i, b on body j.
void dot1(const Attached& a, const Attached& b, ConstraintRows& o, int row) {
  o.phi[row] = a.x.dot(b.x);
  o.Ji.row(row) = b.x.transpose() * a.J;
  o.Jj.row(row) = a.x.transpose() * b.J;
  o.c[row] = b.x.dot(a.extra) + a.x.dot(b.extra) + 2.0 * a.xdot.dot(b.xdot);
}

// a on body i, d = x_j - x_i.
void dot2(const Attached& a, const Attached& xi, const Attached& xj, ConstraintRows& o, int row) {
  const Vector3d d = xj.x - xi.x, ddot = xj.xdot - xi.xdot;
  o.phi[row] = a.x.dot(d);
  o.Ji.row(row) = d.transpose() * a.J - a.x.transpose() * xi.J;
  o.Jj.row(row) = a.x.transpose() * xj.J;
  o.c[row] = d.dot(a.extra) + a.x.dot(xj.extra - xi.extra) + 2.0 * a.xdot.dot(ddot);
}

// Driven angle: a(t) = A_i (cos(beta) h_i - sin(beta) f_i) (turning with the
// modal rotation at the joint), beta = beta(t), b = f_j. Phi = sin(raw - beta);
// the time derivatives of beta enter Phi_t and c.
void drivenDot1(const BodyPose& bi, const Eigen::MatrixXd& theta_i, const RevoluteFrame& fr, const Attached& b,
                double beta, double beta_dot, double beta_ddot, ConstraintRows& o, int row) {
  const Vector3d a_body = std::cos(beta) * fr.hi - std::sin(beta) * fr.fi;
  const Vector3d a1_body = -std::sin(beta) * fr.hi - std::cos(beta) * fr.fi;  // d a / d beta
  const Attached a = attachedVector(bi, a_body, theta_i);
  const Attached a1 = attachedVector(bi, a1_body, theta_i);
  const Vector3d adot_total = a.xdot + beta_dot * a1.x;
  const Vector3d aextra_total = a.extra + 2.0 * beta_dot * a1.xdot + beta_ddot * a1.x - beta_dot * beta_dot * a.x;
  o.phi[row] = a.x.dot(b.x);
  o.Ji.row(row) = b.x.transpose() * a.J;
  o.Jj.row(row) = a.x.transpose() * b.J;
  o.phit[row] = beta_dot * a1.x.dot(b.x);
  o.c[row] = b.x.dot(aextra_total) + a.x.dot(b.extra) + 2.0 * adot_total.dot(b.xdot);
}

double wrapToPi(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0) a += 2.0 * kPi;
  return a - kPi;
}

}  // namespace

RevoluteFrame revoluteFrame(const Joint& jt) {
  RevoluteFrame f;
  Vector3d w;
  orthonormalComplement(jt.axis_i, f.fi, w);
  f.hi = jt.axis_i.normalized().cross(f.fi);
  orthonormalComplement(jt.axis_j, f.fj, w);
  return f;
}

double rawRevoluteAngle(const Joint& jt, const BodyPose& bi, const BodyPose& bj) {
  const RevoluteFrame fr = revoluteFrame(jt);
  const Vector3d fi = attachedVector(bi, fr.fi, jt.shapes_i.theta).x;
  const Vector3d hi = attachedVector(bi, fr.hi, jt.shapes_i.theta).x;
  const Vector3d fj = attachedVector(bj, fr.fj, jt.shapes_j.theta).x;
  return std::atan2(fj.dot(hi), fj.dot(fi));
}

double revoluteAngle(const Joint& jt, const JointRuntime& rt, const BodyPose& bi, const BodyPose& bj) {
  const double a = rawRevoluteAngle(jt, bi, bj) + rt.angle_offset;
  return rt.last_angle + wrapToPi(a - rt.last_angle);
}

double revoluteRate(const Joint& jt, const BodyPose& bi, const BodyPose& bj) {
  // Angular velocity of each joint frame: A (omega' + Theta wdot).
  auto spin = [](const BodyPose& b, const Eigen::MatrixXd& theta) {
    Vector3d w = b.w;
    if (b.modal.size() > 0 && theta.cols() == b.modal.size()) w += theta * b.modal_rate;
    return Vector3d(b.A * w);
  };
  const Vector3d axis = attachedVector(bi, jt.axis_i.normalized(), jt.shapes_i.theta).x;
  return axis.dot(spin(bj, jt.shapes_j.theta) - spin(bi, jt.shapes_i.theta));
}

namespace {
// Joint frame of a body: its axes turned by the modal rotation at the joint
// (first order, as the constraint vectors).
Eigen::Matrix3d jointFrame(const BodyPose& b, const Eigen::MatrixXd& theta) {
  if (b.modal.size() == 0 || theta.cols() != b.modal.size()) return b.A;
  return b.A * (Eigen::Matrix3d::Identity() + fc::skew(theta * b.modal));
}
}  // namespace

void captureFixed(const Joint& jt, JointRuntime& rt, const BodyPose& bi, const BodyPose& bj) {
  const Vector3d xi = attachedPoint(bi, jt.point_i, jt.shapes_i.psi).x;
  const Vector3d xj = attachedPoint(bj, jt.point_j, jt.shapes_j.psi).x;
  rt.fixed_offset = bi.A.transpose() * (xj - xi);
  rt.fixed_rotation = jointFrame(bi, jt.shapes_i.theta).inverse() * jointFrame(bj, jt.shapes_j.theta);
}

void captureLock(const Joint& jt, JointRuntime& rt, const BodyPose& bi, const BodyPose& bj) {
  const RevoluteFrame fr = revoluteFrame(jt);
  // f_j seen in body i's joint frame now; the held direction is perpendicular to it.
  const Vector3d fj_in_i =
      jointFrame(bi, jt.shapes_i.theta).inverse() * attachedVector(bj, fr.fj, jt.shapes_j.theta).x;
  const Vector3d n = jt.axis_i.normalized();
  rt.lock_vector = n.cross(fj_in_i - n * n.dot(fj_in_i)).normalized();
}

int constraintCount(const Joint& jt, const JointRuntime& rt) {
  if (!rt.enabled) return 0;
  switch (jt.type) {
    case JointType::Spherical: return 3;
    case JointType::Revolute: return (rt.locked || jt.drive.active) ? 6 : 5;
    case JointType::Fixed: return 6;
    case JointType::Universal: return 4;
    case JointType::Cylindrical: return 4;
    case JointType::Prismatic: return 5;
  }
  return 0;
}

void jointConstraints(const Joint& jt, const JointRuntime& rt, const BodyPose& bi,
                      const BodyPose& bj, double t, ConstraintRows& o) {
  o.resize(constraintCount(jt, rt), bi.nv(), bj.nv());
  if (o.size() == 0) return;
  const Eigen::MatrixXd &psi_i = jt.shapes_i.psi, &psi_j = jt.shapes_j.psi;
  const Eigen::MatrixXd &th_i = jt.shapes_i.theta, &th_j = jt.shapes_j.theta;
  auto vi = [&](const Vector3d& u) { return attachedVector(bi, u, th_i); };
  auto vj = [&](const Vector3d& u) { return attachedVector(bj, u, th_j); };
  const Attached xj = attachedPoint(bj, jt.point_j, psi_j);
  switch (jt.type) {
    case JointType::Spherical:
      spherical(attachedPoint(bi, jt.point_i, psi_i), xj, o, 0);
      break;
    case JointType::Universal:
      spherical(attachedPoint(bi, jt.point_i, psi_i), xj, o, 0);
      dot1(vi(jt.axis_i), vj(jt.axis_j), o, 3);
      break;
    case JointType::Revolute: {
      spherical(attachedPoint(bi, jt.point_i, psi_i), xj, o, 0);
      Vector3d uj, wj;
      orthonormalComplement(jt.axis_j, uj, wj);
      const Attached ai = vi(jt.axis_i.normalized());
      dot1(ai, vj(uj), o, 3);
      dot1(ai, vj(wj), o, 4);
      const RevoluteFrame fr = revoluteFrame(jt);
      if (jt.drive.active) {
        drivenDot1(bi, th_i, fr, vj(fr.fj), jt.drive.angle(t) - rt.angle_offset, jt.drive.rate(t),
                   jt.drive.accel(t), o, 5);
      } else if (rt.locked) {
        dot1(vi(rt.lock_vector), vj(fr.fj), o, 5);
      }
      break;
    }
    case JointType::Fixed: {
      spherical(attachedPoint(bi, jt.point_i + rt.fixed_offset, psi_i), xj, o, 0);
      const Eigen::Matrix3d& R = rt.fixed_rotation;
      for (int k = 0; k < 3; ++k) dot1(vi(R.col(k)), vj(Eigen::Vector3d::Unit((k + 1) % 3)), o, 3 + k);
      break;
    }
    case JointType::Cylindrical:
    case JointType::Prismatic: {
      const Attached xi = attachedPoint(bi, jt.point_i, psi_i);
      Vector3d ui, wi, uj, wj;
      orthonormalComplement(jt.axis_i, ui, wi);
      orthonormalComplement(jt.axis_j, uj, wj);
      const Attached ai = vi(jt.axis_i.normalized());
      dot2(vi(ui), xi, xj, o, 0);
      dot2(vi(wi), xi, xj, o, 1);
      dot1(ai, vj(uj), o, 2);
      dot1(ai, vj(wj), o, 3);
      if (jt.type == JointType::Prismatic) {
        const RevoluteFrame fr = revoluteFrame(jt);
        dot1(vi(rt.lock_vector), vj(fr.fj), o, 4);
      }
      break;
    }
  }
}

}  // namespace fc::mbs
