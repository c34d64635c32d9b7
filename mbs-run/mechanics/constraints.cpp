#include "mbs-run/mechanics/constraints.h"

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

namespace {
// The three reference vectors of a revolute angle as attached vectors (value,
// rate, Jacobian), and the angle's atan2 arguments x = f_j . f_i, y = f_j . h_i.
struct AngleVectors {
  Attached fi, hi, fj;
  double x, y;
};
AngleVectors angleVectors(const Joint& jt, const BodyPose& bi, const BodyPose& bj) {
  const RevoluteFrame fr = revoluteFrame(jt);
  AngleVectors a{attachedVector(bi, fr.fi, jt.shapes_i.theta), attachedVector(bi, fr.hi, jt.shapes_i.theta),
                 attachedVector(bj, fr.fj, jt.shapes_j.theta), 0.0, 0.0};
  a.x = a.fj.x.dot(a.fi.x);
  a.y = a.fj.x.dot(a.hi.x);
  return a;
}
}  // namespace

double rawRevoluteAngle(const Joint& jt, const BodyPose& bi, const BodyPose& bj) {
  const AngleVectors a = angleVectors(jt, bi, bj);
  return std::atan2(a.y, a.x);
}

double revoluteAngle(const Joint& jt, const JointRuntime& rt, const BodyPose& bi, const BodyPose& bj) {
  const double a = rawRevoluteAngle(jt, bi, bj) + rt.angle_offset;
  return rt.last_angle + wrapToPi(a - rt.last_angle);
}

// Derivation. theta = atan2(y, x) gives dtheta = (x dy - y dx) / rho^2,
// rho^2 = x^2 + y^2. Each reference vector u_d = A (u + (Theta w) x u) is the
// attached vector of kinematics.h, whose rate is exactly J_u v with
// J_u = [0, -A u_d~, -A u~ Theta] (the modal rotation enters linearly, so
// d/dt (Theta w) x u = (Theta wdot) x u with no neglected term). Then
//   dy/dt = f_j . (J_hi v_i) + h_i . (J_fj v_j),  dx/dt = f_j . (J_fi v_i) + f_i . (J_fj v_j)
// and collecting the coefficients of v_i and v_j gives gi and gj (header).
// Written out, with u0 / ud a body-frame vector undeformed / turned by the
// modal rotation, a = x h_i - y f_i (global), b = x h_id - y f_id and
// b0 = x h_i0 - y f_i0 (body i axes), c = A_i^T f_j, e = A_j^T a:
//   rho^2 gi = [0, (b x c)^T, -c^T b0~ Theta_i],
//   rho^2 gj = [0, (f_jd x e)^T, -e^T f_j0~ Theta_j].
// On rigid bodies with the joint assembled (f_j = x f_i + y h_i, rho = 1):
// b x c = -n and f_jd x e = n in the bodies' axes, the torque pair of a
// spring acting about the axis n.
void revoluteAngleJacobian(const Joint& jt, const BodyPose& bi, const BodyPose& bj, Eigen::RowVectorXd& gi,
                           Eigen::RowVectorXd& gj) {
  const AngleVectors a = angleVectors(jt, bi, bj);
  const double rho2 = a.x * a.x + a.y * a.y;
  gi.setZero(bi.nv());
  gj.setZero(bj.nv());
  if (!(rho2 > 0.0)) return;  // f_j along the axis: the angle is undefined
  gi = a.fj.x.transpose() * (a.x * a.hi.J - a.y * a.fi.J) / rho2;
  gj = (a.x * a.hi.x - a.y * a.fi.x).transpose() * a.fj.J / rho2;
}

double revoluteRate(const Joint& jt, const BodyPose& bi, const BodyPose& bj) {
  // The same expression with the vectors' rates J_u v (kinematics.h).
  const AngleVectors a = angleVectors(jt, bi, bj);
  const double rho2 = a.x * a.x + a.y * a.y;
  if (!(rho2 > 0.0)) return 0.0;
  const double ydot = a.fj.x.dot(a.hi.xdot) + a.hi.x.dot(a.fj.xdot);
  const double xdot = a.fj.x.dot(a.fi.xdot) + a.fi.x.dot(a.fj.xdot);
  return (a.x * ydot - a.y * xdot) / rho2;
}

namespace {
// Whether a body's attachment carries modal rotations (a flexible body's
// interface or point with nm rotational shapes).
bool turnsWithModes(const BodyPose& b, const Eigen::MatrixXd& theta) {
  return b.modal.size() > 0 && theta.cols() == b.modal.size();
}
// Joint frame of a body: its axes turned by the modal rotation at the joint
// (first order, as the constraint vectors): F = A (I + (Theta w)~), so that
// F u is the attached vector of u (kinematics.h).
Eigen::Matrix3d jointFrame(const BodyPose& b, const Eigen::MatrixXd& theta) {
  if (!turnsWithModes(b, theta)) return b.A;
  return b.A * (Eigen::Matrix3d::Identity() + fc::skew(theta * b.modal));
}
}  // namespace

void captureFixed(const Joint& jt, JointRuntime& rt, const BodyPose& bi, const BodyPose& bj) {
  const Vector3d xi = attachedPoint(bi, jt.point_i, jt.shapes_i.psi).x;
  const Vector3d xj = attachedPoint(bj, jt.point_j, jt.shapes_j.psi).x;
  const Eigen::Matrix3d Fi = jointFrame(bi, jt.shapes_i.theta), Fj = jointFrame(bj, jt.shapes_j.theta);
  // The rows hold F_i o = x_j - x_i (the offset turning with the modal
  // rotation at point i) and (F_i R e_k) . (F_j e_(k+1)) = 0. F is orthonormal
  // only to first order in the modal rotation, so R = F_i^-1 F_j^-T (the
  // columns of F_i R are the dual basis of F_j's, (F_i R e_k) . (F_j e_m) =
  // delta_km) makes them vanish exactly at capture; on rigid bodies it is
  // A_i^T A_j, computed as before.
  if (turnsWithModes(bi, jt.shapes_i.theta)) rt.fixed_offset = Fi.inverse() * (xj - xi);
  else rt.fixed_offset = bi.A.transpose() * (xj - xi);
  if (turnsWithModes(bj, jt.shapes_j.theta)) rt.fixed_rotation = Fi.inverse() * Fj.inverse().transpose();
  else rt.fixed_rotation = Fi.inverse() * Fj;
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
    case JointType::Revolute: {
      const bool held = rt.locked || jt.drive.active || rt.contact != 0;
      if (jt.stop_only) return held ? 1 : 0;
      return held ? 6 : 5;
    }
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
      if (jt.stop_only) {  // only the angle row, while locked or resting on a stop
        dot1(vi(rt.lock_vector), vj(revoluteFrame(jt).fj), o, 0);
        break;
      }
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
      } else if (rt.locked || rt.contact != 0) {
        dot1(vi(rt.lock_vector), vj(fr.fj), o, 5);
      }
      break;
    }
    case JointType::Fixed: {
      if (turnsWithModes(bi, th_i)) {
        // The captured offset turns with the modal rotation at point i, as
        // the rotational rows' vectors do: x_i + F_i o.
        Attached xo = attachedPoint(bi, jt.point_i, psi_i);
        const Attached o_vec = vi(rt.fixed_offset);
        xo.x += o_vec.x;
        xo.xdot += o_vec.xdot;
        xo.extra += o_vec.extra;
        xo.J += o_vec.J;
        spherical(xo, xj, o, 0);
      } else {
        spherical(attachedPoint(bi, jt.point_i + rt.fixed_offset, psi_i), xj, o, 0);
      }
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
