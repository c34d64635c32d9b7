#pragma once
// Kinematics of points and vectors attached to a rigid body frame, in the
// velocity coordinates shared by every body: v = [rdot (global), omega' (body)].
// For a body-fixed point s (body frame), x = r + A s and
//   xdot  = J v,               J = [I, -A s~]
//   xddot = J vdot + A w~ w~ s (the "extra" term, quadratic in w = omega')
// and for a body-fixed vector u, g = A u, J = [0, -A u~], extra = A w~ w~ u.
// These are the building blocks of every constraint (Nikravesh 1988, ch. 6-7).
#include <Eigen/Dense>

namespace fc::mbs {

using Matrix36d = Eigen::Matrix<double, 3, 6>;

// Pose and velocity of one body frame. Fixed bodies have zero velocity and no
// velocity coordinates (free = false).
struct BodyPose {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  Eigen::Vector4d p = Eigen::Vector4d(1, 0, 0, 0);
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d rdot = Eigen::Vector3d::Zero();
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  // angular velocity, body axes
  bool free = false;
};

// A body-fixed point or vector evaluated at a pose.
struct Attached {
  Eigen::Vector3d x;      // global position (point) or global vector
  Eigen::Vector3d xdot;   // its time derivative
  Eigen::Vector3d extra;  // xddot - J vdot
  Matrix36d J;            // d(xdot)/dv
};

Attached attachedPoint(const BodyPose& b, const Eigen::Vector3d& s);
Attached attachedVector(const BodyPose& b, const Eigen::Vector3d& u);

// Two unit vectors completing `axis` to a right-handed orthonormal triad
// (u, w, axis); deterministic so that revolute angles are reproducible.
void orthonormalComplement(const Eigen::Vector3d& axis, Eigen::Vector3d& u, Eigen::Vector3d& w);

}  // namespace fc::mbs
