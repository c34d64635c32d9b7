#pragma once
// Points and frames attached to a flexible body (joints and forces act there).
// A marker carries its undeformed body-frame position s0 and its translational
// and rotational mode shapes Psi, Theta (3 x nm; for an interface of a body file,
// the transposed columns 0-2 and 3-5 of /interfaces/NAME/shapes). Then
//   s = s0 + Psi w,  x = r + A s,  xdot = J_x v,  J_x = [I, -A s~, A Psi]
//   frame: A_m = A R(Theta w) A_m0,  omega_m (global) = J_w v,  J_w = [0, A, A Theta]
// with v = [rdot, omega', wdot]. R(phi) is the exponential map: the first-order
// I + phi~ of the shared convention, kept orthonormal so joint angles stay exact.
#include <Eigen/Dense>

#include "common/flexbody.h"

namespace fc::mbs {

struct Marker {
  Eigen::Vector3d s0 = Eigen::Vector3d::Zero();
  Eigen::MatrixXd Psi;    // (3, nm)
  Eigen::MatrixXd Theta;  // (3, nm)
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();  // marker axes in body axes, undeformed
};

// The interface's own shapes, first nm modes (nm <= rows of its shapes).
Marker markerFromInterface(const FlexInterface& it, int nm,
                           const Eigen::Matrix3d& axes = Eigen::Matrix3d::Identity());
// A point that moves with the body frame only (rigid bodies, or nm = 0).
Marker rigidMarker(const Eigen::Vector3d& s0, int nm,
                   const Eigen::Matrix3d& axes = Eigen::Matrix3d::Identity());

Eigen::Vector3d markerLocalPosition(const Marker& m, const Eigen::VectorXd& w);
Eigen::Vector3d markerPosition(const Eigen::Vector3d& r, const Eigen::Matrix3d& A,
                               const Marker& m, const Eigen::VectorXd& w);
Eigen::Matrix3d markerOrientation(const Eigen::Matrix3d& A, const Marker& m,
                                  const Eigen::VectorXd& w);
// (3, 6+nm) velocity Jacobians.
Eigen::MatrixXd markerTranslationJacobian(const Eigen::Matrix3d& A, const Marker& m,
                                          const Eigen::VectorXd& w);
Eigen::MatrixXd markerRotationJacobian(const Eigen::Matrix3d& A, const Marker& m);
// The velocity-dependent parts of the marker's accelerations, Jdot v:
//   translation A (omega'~ omega'~ s + 2 omega'~ Psi wdot), rotation A omega'~ Theta wdot.
Eigen::Vector3d markerAccelerationBias(const Eigen::Matrix3d& A, const Marker& m,
                                       const Eigen::VectorXd& w, const Eigen::VectorXd& wdot,
                                       const Eigen::Vector3d& omega);
Eigen::Vector3d markerAngularAccelerationBias(const Eigen::Matrix3d& A, const Marker& m,
                                              const Eigen::VectorXd& wdot,
                                              const Eigen::Vector3d& omega);
// Generalized forces (6+nm) of a global force f at the marker and of a global torque n.
Eigen::VectorXd markerForce(const Eigen::Matrix3d& A, const Marker& m, const Eigen::VectorXd& w,
                            const Eigen::Vector3d& f);
Eigen::VectorXd markerTorque(const Eigen::Matrix3d& A, const Marker& m, const Eigen::Vector3d& n);

}  // namespace fc::mbs
