#include "mbs-run/kinematics.h"

#include "common/rotations.h"

namespace fc::mbs {

Attached attachedPoint(const BodyPose& b, const Eigen::Vector3d& s) {
  Attached a;
  const Eigen::Vector3d ws = b.w.cross(s);
  a.x = b.r + b.A * s;
  a.xdot = b.rdot + b.A * ws;
  a.extra = b.A * b.w.cross(ws);
  a.J.leftCols<3>().setIdentity();
  a.J.rightCols<3>() = -b.A * fc::skew(s);
  return a;
}

Attached attachedVector(const BodyPose& b, const Eigen::Vector3d& u) {
  Attached a;
  const Eigen::Vector3d wu = b.w.cross(u);
  a.x = b.A * u;
  a.xdot = b.A * wu;
  a.extra = b.A * b.w.cross(wu);
  a.J.leftCols<3>().setZero();
  a.J.rightCols<3>() = -b.A * fc::skew(u);
  return a;
}

void orthonormalComplement(const Eigen::Vector3d& axis, Eigen::Vector3d& u, Eigen::Vector3d& w) {
  const Eigen::Vector3d n = axis.normalized();
  // Start from the coordinate axis least aligned with n, so u is well defined.
  Eigen::Index k;
  n.cwiseAbs().minCoeff(&k);
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e[k] = 1.0;
  u = (e - n * n.dot(e)).normalized();
  w = n.cross(u);
}

}  // namespace fc::mbs
