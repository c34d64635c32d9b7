#include "mbs-run/mechanics/rigid_body.h"

#include "common/rotations.h"

namespace fc::mbs {

Matrix6d rigidMassMatrix(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c,
                         const Eigen::Matrix3d& A) {
  const Eigen::Matrix3d cs = fc::skew(c);
  Matrix6d M;
  M.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  M.topRightCorner<3, 3>() = -m * A * cs;
  M.bottomLeftCorner<3, 3>() = m * cs * A.transpose();
  M.bottomRightCorner<3, 3>() = I_c - m * cs * cs;
  return M;
}

Vector6d rigidQuadraticVelocity(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c,
                                const Eigen::Matrix3d& A, const Eigen::Vector3d& w) {
  const Eigen::Matrix3d cs = fc::skew(c);
  const Eigen::Matrix3d Jo = I_c - m * cs * cs;
  Vector6d q;
  q.head<3>() = -m * A * w.cross(w.cross(c));
  q.tail<3>() = -w.cross(Jo * w);
  return q;
}

double rigidKineticEnergy(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c,
                          const Eigen::Matrix3d& A, const Eigen::Vector3d& rdot,
                          const Eigen::Vector3d& w) {
  Vector6d v;
  v << rdot, w;
  return 0.5 * v.dot(rigidMassMatrix(m, c, I_c, A) * v);
}

Eigen::Matrix3d rodInertia(double m, double length, double diameter) {
  const double r2 = 0.25 * diameter * diameter;
  const double axial = 0.5 * m * r2;
  const double transverse = m * (3.0 * r2 + length * length) / 12.0;
  return Eigen::Vector3d(axial, transverse, transverse).asDiagonal();
}

Eigen::Matrix3d plateInertia(double m, double a, double b, double t) {
  return Eigen::Vector3d(m * (b * b + t * t) / 12.0, m * (a * a + t * t) / 12.0,
                         m * (a * a + b * b) / 12.0)
      .asDiagonal();
}

}  // namespace fc::mbs
