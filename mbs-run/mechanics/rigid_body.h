#pragma once
// Inertia of a rigid body whose frame origin need not be its centre of mass, in
// the velocity coordinates v = [rdot (global), omega' (body axes)]. With c the
// CoM in body axes, I_c the inertia about the CoM and J_o = I_c - m c~ c~ the
// inertia about the frame origin (parallel-axis theorem), the kinetic energy is
//   T = 1/2 m rdot^2 - m rdot . (A c~ omega') + 1/2 omega'^T J_o omega'
// which gives (Newton-Euler about a body-fixed point, e.g. Shabana, Dynamics of
// Multibody Systems, 3rd ed., sec. 3.7)
//   M   = [[m I, -m A c~], [m c~ A^T, J_o]]
//   Q_v = [-m A w~ w~ c, -w~ J_o w]      (w = omega').
// For c = 0 this is the familiar diag(m I, I_c) with the gyroscopic -w~ I_c w.
#include <Eigen/Dense>

namespace fc::mbs {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

Matrix6d rigidMassMatrix(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c,
                         const Eigen::Matrix3d& A);
Vector6d rigidQuadraticVelocity(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c,
                                const Eigen::Matrix3d& A, const Eigen::Vector3d& w);
double rigidKineticEnergy(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_c,
                          const Eigen::Matrix3d& A, const Eigen::Vector3d& rdot,
                          const Eigen::Vector3d& w);
// Uniform slender rod of length L along body x, centred: I = m L^2/12 about y, z.
Eigen::Matrix3d rodInertia(double m, double length, double diameter);
// Uniform rectangular plate (a along x, b along y, thickness t along z), centred.
Eigen::Matrix3d plateInertia(double m, double a, double b, double t);

}  // namespace fc::mbs
