#include "mbs-run/mechanics/flexible/marker.h"

#include <stdexcept>
#include <string>

#include "common/rotations.h"

namespace fc::mbs {

Marker markerFromInterface(const FlexInterface& it, int nm, const Eigen::Matrix3d& axes) {
  if (nm < 0 || nm > it.shapes.rows())
    throw std::invalid_argument("interface " + it.name + " has shapes for " +
                                std::to_string(it.shapes.rows()) + " modes, " + std::to_string(nm) +
                                " asked");
  Marker m;
  m.s0 = it.position;
  m.Psi = it.shapes.topLeftCorner(nm, 3).transpose();
  m.Theta = it.shapes.block(0, 3, nm, 3).transpose();
  m.A0 = axes;
  return m;
}

Marker rigidMarker(const Eigen::Vector3d& s0, int nm, const Eigen::Matrix3d& axes) {
  Marker m;
  m.s0 = s0;
  m.Psi = Eigen::MatrixXd::Zero(3, nm);
  m.Theta = Eigen::MatrixXd::Zero(3, nm);
  m.A0 = axes;
  return m;
}

Eigen::Vector3d markerLocalPosition(const Marker& m, const Eigen::VectorXd& w) {
  return m.s0 + m.Psi * w;
}

Eigen::Vector3d markerPosition(const Eigen::Vector3d& r, const Eigen::Matrix3d& A, const Marker& m,
                               const Eigen::VectorXd& w) {
  return r + A * markerLocalPosition(m, w);
}

Eigen::Matrix3d markerOrientation(const Eigen::Matrix3d& A, const Marker& m, const Eigen::VectorXd& w) {
  return A * expRotation(m.Theta * w) * m.A0;
}

Eigen::MatrixXd markerTranslationJacobian(const Eigen::Matrix3d& A, const Marker& m,
                                          const Eigen::VectorXd& w) {
  const long nm = m.Psi.cols();
  Eigen::MatrixXd J(3, 6 + nm);
  J.leftCols<3>().setIdentity();
  J.middleCols<3>(3) = -A * skew(markerLocalPosition(m, w));
  if (nm > 0) J.rightCols(nm) = A * m.Psi;
  return J;
}

Eigen::MatrixXd markerRotationJacobian(const Eigen::Matrix3d& A, const Marker& m) {
  const long nm = m.Theta.cols();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, 6 + nm);
  J.middleCols<3>(3) = A;
  if (nm > 0) J.rightCols(nm) = A * m.Theta;
  return J;
}

Eigen::Vector3d markerAccelerationBias(const Eigen::Matrix3d& A, const Marker& m,
                                       const Eigen::VectorXd& w, const Eigen::VectorXd& wdot,
                                       const Eigen::Vector3d& omega) {
  const Eigen::Vector3d s = markerLocalPosition(m, w);
  const Eigen::Vector3d u = m.Psi.cols() > 0 ? Eigen::Vector3d(m.Psi * wdot) : Eigen::Vector3d::Zero();
  return A * (omega.cross(omega.cross(s)) + 2.0 * omega.cross(u));
}

Eigen::Vector3d markerAngularAccelerationBias(const Eigen::Matrix3d& A, const Marker& m,
                                              const Eigen::VectorXd& wdot,
                                              const Eigen::Vector3d& omega) {
  if (m.Theta.cols() == 0) return Eigen::Vector3d::Zero();
  return A * omega.cross(Eigen::Vector3d(m.Theta * wdot));
}

Eigen::VectorXd markerForce(const Eigen::Matrix3d& A, const Marker& m, const Eigen::VectorXd& w,
                            const Eigen::Vector3d& f) {
  return markerTranslationJacobian(A, m, w).transpose() * f;
}

Eigen::VectorXd markerTorque(const Eigen::Matrix3d& A, const Marker& m, const Eigen::Vector3d& n) {
  return markerRotationJacobian(A, m).transpose() * n;
}

}  // namespace fc::mbs
