#include "mbs-run/mechanics/kinematics.h"

#include "common/rotations.h"

namespace fc::mbs {

namespace {
const Eigen::MatrixXd kNoShapes = Eigen::MatrixXd::Zero(3, 0);
}

Attached attachedPoint(const BodyPose& b, const Eigen::Vector3d& s0, const Eigen::MatrixXd& psi) {
  const int nm = static_cast<int>(b.modal.size());
  Attached a;
  Eigen::Vector3d s = s0;
  Eigen::Vector3d rel_rate = Eigen::Vector3d::Zero();  // Psi wdot, body axes
  // Shapes of another size (the rigid shorthands on a flexible body) mean a
  // point that moves with the frame only.
  const bool shaped = nm > 0 && psi.cols() == nm;
  if (shaped) {
    s += psi * b.modal;
    rel_rate = psi * b.modal_rate;
  }
  const Eigen::Vector3d ws = b.w.cross(s);
  a.x = b.r + b.A * s;
  a.xdot = b.rdot + b.A * (ws + rel_rate);
  a.extra = b.A * (b.w.cross(ws) + 2.0 * b.w.cross(rel_rate));
  a.J.resize(3, 6 + nm);
  a.J.leftCols<3>().setIdentity();
  a.J.middleCols<3>(3) = -b.A * fc::skew(s);
  if (nm > 0) {
    if (shaped) a.J.rightCols(nm) = b.A * psi;
    else a.J.rightCols(nm).setZero();
  }
  return a;
}

Attached attachedVector(const BodyPose& b, const Eigen::Vector3d& u, const Eigen::MatrixXd& theta) {
  const int nm = static_cast<int>(b.modal.size());
  Attached a;
  Eigen::Vector3d ud = u;
  Eigen::Vector3d spin_u = Eigen::Vector3d::Zero();  // (Theta wdot) x u, body axes
  const bool shaped = nm > 0 && theta.cols() == nm;
  if (shaped) {
    ud += Eigen::Vector3d(theta * b.modal).cross(u);
    spin_u = Eigen::Vector3d(theta * b.modal_rate).cross(u);
  }
  const Eigen::Vector3d wu = b.w.cross(ud);
  a.x = b.A * ud;
  a.xdot = b.A * (wu + spin_u);
  a.extra = b.A * (b.w.cross(wu) + 2.0 * b.w.cross(spin_u));
  a.J.resize(3, 6 + nm);
  a.J.leftCols<3>().setZero();
  a.J.middleCols<3>(3) = -b.A * fc::skew(ud);
  if (nm > 0) {
    if (shaped) a.J.rightCols(nm) = -b.A * fc::skew(u) * theta;
    else a.J.rightCols(nm).setZero();
  }
  return a;
}

Attached attachedPoint(const BodyPose& b, const Eigen::Vector3d& s0) { return attachedPoint(b, s0, kNoShapes); }
Attached attachedVector(const BodyPose& b, const Eigen::Vector3d& u) { return attachedVector(b, u, kNoShapes); }

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
