#pragma once
// Euler parameters p = [e0, e1, e2, e3] (scalar first), as in Nikravesh,
// Computer-Aided Analysis of Mechanical Systems (1988), ch. 6:
//   A(p) = (2 e0^2 - 1) I + 2 (e e^T + e0 e~),   r_global = r + A s'
//   omega (global) = 2 G pdot,  omega' (body) = 2 L pdot,
//   G = [-e, e~ + e0 I],        L = [-e, -e~ + e0 I].
#include <Eigen/Dense>

namespace fc {

using Vector4d = Eigen::Vector4d;
using Matrix34d = Eigen::Matrix<double, 3, 4>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v);
Eigen::Matrix3d rotationMatrix(const Vector4d& p);
Matrix34d Gmatrix(const Vector4d& p);
Matrix34d Lmatrix(const Vector4d& p);
// Euler parameters of a rotation matrix (Shepperd's method, e0 >= 0).
Vector4d eulerParametersFromMatrix(const Eigen::Matrix3d& A);
Vector4d eulerParametersFromAxisAngle(const Eigen::Vector3d& axis, double angle);
// Quaternion product: the rotation p then q (applied first p) is quatProduct(q, p).
Vector4d quatProduct(const Vector4d& a, const Vector4d& b);
Vector4d quatConjugate(const Vector4d& p);
// pdot from body angular velocity: pdot = 1/2 L^T omega'.
Vector4d eulerParameterRate(const Vector4d& p, const Eigen::Vector3d& omega_body);
// Rotation vector (axis * angle, angle in [0, pi]) of a rotation matrix.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& A);
// Exponential map: rotation matrix of the rotation vector phi.
Eigen::Matrix3d expRotation(const Eigen::Vector3d& phi);

}  // namespace fc
