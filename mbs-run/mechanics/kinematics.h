#pragma once
// Kinematics of points and vectors attached to a body frame, in the velocity
// coordinates shared by every body: v = [rdot (global), omega' (body), wdot
// (modal rates, flexible bodies only)]. For a point with undeformed position s0
// and translational mode shapes Psi, s = s0 + Psi w and x = r + A s:
//   xdot  = J v,   J = [I, -A s~, A Psi]
//   xddot = J vdot + A (w'~ w'~ s + 2 w'~ Psi wdot)         (w' = omega')
// and for a vector u turning with the modal rotation Theta w at its point,
// u_d = u + (Theta w) x u (first order in w, the shared convention):
//   J = [0, -A u_d~, -A u~ Theta],  extra = A (w'~ w'~ u_d + 2 w'~ ((Theta wdot) x u)).
// For rigid bodies Psi and Theta have no columns and these are Nikravesh's
// (1988, ch. 6-7) rigid-body expressions.
#include <Eigen/Dense>

namespace fc::mbs {

// Pose and velocity of one body frame. Fixed bodies have zero velocity and no
// velocity coordinates (free = false).
struct BodyPose {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  Eigen::Vector4d p = Eigen::Vector4d(1, 0, 0, 0);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d rdot = Eigen::Vector3d::Zero();
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  // angular velocity, body axes
  Eigen::VectorXd modal, modal_rate;            // (nm), empty for rigid bodies
  bool free = false;
  int nv() const { return 6 + static_cast<int>(modal.size()); }
};

// A body-fixed point or vector evaluated at a pose.
struct Attached {
  Eigen::Vector3d x;      // global position (point) or global vector
  Eigen::Vector3d xdot;   // its time derivative
  Eigen::Vector3d extra;  // xddot - J vdot
  Eigen::MatrixXd J;      // (3, 6 + nm) d(xdot)/dv
};

// psi / theta: (3, nm) shapes at the point; pass empty (3, 0) for rigid bodies.
Attached attachedPoint(const BodyPose& b, const Eigen::Vector3d& s0, const Eigen::MatrixXd& psi);
Attached attachedVector(const BodyPose& b, const Eigen::Vector3d& u, const Eigen::MatrixXd& theta);
// Rigid-body shorthands (no modal terms).
Attached attachedPoint(const BodyPose& b, const Eigen::Vector3d& s0);
Attached attachedVector(const BodyPose& b, const Eigen::Vector3d& u);

// Two unit vectors completing `axis` to a right-handed orthonormal triad
// (u, w, axis); deterministic so that revolute angles are reproducible.
void orthonormalComplement(const Eigen::Vector3d& axis, Eigen::Vector3d& u, Eigen::Vector3d& w);

}  // namespace fc::mbs
