#pragma once
// Constraint equations of the joints, built from three primitives:
//   spherical  x_j - x_i = 0                       (3 rows)
//   dot-1      a_i . b_j = 0   (two body vectors perpendicular)
//   dot-2      a_i . (x_j - x_i) = 0               (Nikravesh 1988, sec. 7.3)
// For each row: the value Phi, its Jacobian blocks on the velocity coordinates of
// body i and j, the explicit time derivative Phi_t (driven joints) and
// c = Phi_ddot - Phi_v vdot, so that the acceleration equation is Phi_v vdot = -c.
#include <Eigen/Dense>

#include <vector>

#include "mbs-run/mechanics/kinematics.h"
#include "mbs-run/model/model.h"

namespace fc::mbs {

// What a joint holds at run time (captured when it becomes active or locked).
struct JointRuntime {
  bool enabled = true;
  bool locked = false;
  // Revolute with limits: -1 resting on its min stop, +1 on its max stop, 0
  // free; while resting the angle is held by the lock row (lock_vector).
  int contact = 0;
  // Fixed joint: the offset of the point of j from the point of i in the
  // joint frame of i (body i axes turned by the modal rotation at point i),
  // and the rotation whose columns, turned with body i's joint frame, are
  // held perpendicular to the axes of j's joint frame (A_i^T A_j on rigid
  // bodies), both captured at activation.
  Eigen::Vector3d fixed_offset = Eigen::Vector3d::Zero();
  Eigen::Matrix3d fixed_rotation = Eigen::Matrix3d::Identity();
  // Locked revolute / prismatic: body-i vector whose dot product with the
  // reference vector of j is sin(angle - held angle).
  Eigen::Vector3d lock_vector = Eigen::Vector3d::Zero();
  // Revolute angle = raw atan2 angle + angle_offset, unwrapped about last_angle.
  double angle_offset = 0.0;
  double last_angle = 0.0;
};

// What a joint transmits, as the results report it (sampling.h): the force
// on the joint's first body (body_i) and the moment about its point on
// body_i, both global; zero while the joint is disabled.
struct JointReaction {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
};

struct ConstraintRows {
  Eigen::MatrixXd Ji, Jj;  // (n, 6 + nm_i), (n, 6 + nm_j)
  Eigen::VectorXd phi, phit, c;
  int size() const { return static_cast<int>(phi.size()); }
  void resize(int n, int nvi, int nvj);
};

// Reference vectors of a revolute (or prismatic) joint: axis on i, f_i and
// h_i = axis x f_i perpendicular to it on body i, f_j perpendicular to axis_j on j.
struct RevoluteFrame {
  Eigen::Vector3d fi, hi, fj;
};
RevoluteFrame revoluteFrame(const Joint& jt);

// Raw relative angle of body j about the axis of body i, in (-pi, pi]; on
// flexible bodies the reference vectors turn with the modal rotation at the
// joint's points.
double rawRevoluteAngle(const Joint& jt, const BodyPose& bi, const BodyPose& bj);
// Unwrapped angle (continuous past pi) given the runtime's last known angle.
double revoluteAngle(const Joint& jt, const JointRuntime& rt, const BodyPose& bi, const BodyPose& bj);
// Exact gradient of the angle with respect to the velocity coordinates of
// both bodies, d(angle)/dt = gi v_i + gj v_j (v = [rdot, omega', wdot]): the
// angle is atan2(y, x) with x = f_j . f_i, y = f_j . h_i of the attached
// (modally rotated) reference vectors, whose rates are J_u v exactly
// (kinematics.h), so
//   gi = f_j^T (x J_hi - y J_fi) / (x^2 + y^2),  gj = (x h_i - y f_i)^T J_fj / (x^2 + y^2).
// On rigid bodies whose revolute constraints hold (f_j perpendicular to the
// axis) this is [0, -(A_i^T n)^T] and [0, (A_j^T n)^T], n the global axis.
// A spring applies Q = -M(angle) g^T through it: its power is exactly
// -dV/dt of V = int M, and a damper's exactly -c (g v)^2.
void revoluteAngleJacobian(const Joint& jt, const BodyPose& bi, const BodyPose& bj, Eigen::RowVectorXd& gi,
                           Eigen::RowVectorXd& gj);
// d(angle)/dt = gi v_i + gj v_j (the exact rate of revoluteAngle); on rigid
// bodies with the joint assembled, axis . (omega_j - omega_i), global.
double revoluteRate(const Joint& jt, const BodyPose& bi, const BodyPose& bj);

// Captures the current relative pose into rt (fixed joint activation, locking).
void captureFixed(const Joint& jt, JointRuntime& rt, const BodyPose& bi, const BodyPose& bj);
void captureLock(const Joint& jt, JointRuntime& rt, const BodyPose& bi, const BodyPose& bj);

// Number of equations of the joint in its current runtime state (0 if disabled).
int constraintCount(const Joint& jt, const JointRuntime& rt);
// Rows of one joint at time t. Translational rows (if any) come first, so the
// reaction force on body i is minus their multipliers' force (see dynamics).
void jointConstraints(const Joint& jt, const JointRuntime& rt, const BodyPose& bi,
                      const BodyPose& bj, double t, ConstraintRows& out);

}  // namespace fc::mbs
