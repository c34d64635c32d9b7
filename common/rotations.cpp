#include "common/rotations.h"

#include <cmath>

namespace fc {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

Eigen::Matrix3d rotationMatrix(const Vector4d& p) {
  const double e0 = p(0);
  const Eigen::Vector3d e = p.tail<3>();
  return (2 * e0 * e0 - 1) * Eigen::Matrix3d::Identity() + 2 * (e * e.transpose() + e0 * skew(e));
}

Matrix34d Gmatrix(const Vector4d& p) {
  Matrix34d G;
  G.col(0) = -p.tail<3>();
  G.rightCols<3>() = skew(p.tail<3>()) + p(0) * Eigen::Matrix3d::Identity();
  return G;
}

Matrix34d Lmatrix(const Vector4d& p) {
  Matrix34d L;
  L.col(0) = -p.tail<3>();
  L.rightCols<3>() = -skew(p.tail<3>()) + p(0) * Eigen::Matrix3d::Identity();
  return L;
}

Vector4d eulerParametersFromMatrix(const Eigen::Matrix3d& A) {
  // Shepperd (1978): pick the largest of the four squared parameters to divide by.
  const double tr = A.trace();
  Vector4d q;
  const double d[4] = {tr, A(0, 0), A(1, 1), A(2, 2)};
  int k = 0;
  for (int i = 1; i < 4; ++i)
    if (d[i] > d[k]) k = i;
  if (k == 0) {
    const double e0 = 0.5 * std::sqrt(1 + tr);
    q << e0, (A(2, 1) - A(1, 2)) / (4 * e0), (A(0, 2) - A(2, 0)) / (4 * e0),
        (A(1, 0) - A(0, 1)) / (4 * e0);
  } else if (k == 1) {
    const double e1 = 0.5 * std::sqrt(1 + 2 * A(0, 0) - tr);
    q << (A(2, 1) - A(1, 2)) / (4 * e1), e1, (A(0, 1) + A(1, 0)) / (4 * e1),
        (A(0, 2) + A(2, 0)) / (4 * e1);
  } else if (k == 2) {
    const double e2 = 0.5 * std::sqrt(1 + 2 * A(1, 1) - tr);
    q << (A(0, 2) - A(2, 0)) / (4 * e2), (A(0, 1) + A(1, 0)) / (4 * e2), e2,
        (A(1, 2) + A(2, 1)) / (4 * e2);
  } else {
    const double e3 = 0.5 * std::sqrt(1 + 2 * A(2, 2) - tr);
    q << (A(1, 0) - A(0, 1)) / (4 * e3), (A(0, 2) + A(2, 0)) / (4 * e3),
        (A(1, 2) + A(2, 1)) / (4 * e3), e3;
  }
  if (q(0) < 0) q = -q;
  return q.normalized();
}

Vector4d eulerParametersFromAxisAngle(const Eigen::Vector3d& axis, double angle) {
  Vector4d q;
  q(0) = std::cos(0.5 * angle);
  q.tail<3>() = std::sin(0.5 * angle) * axis.normalized();
  return q;
}

Vector4d quatProduct(const Vector4d& a, const Vector4d& b) {
  Vector4d r;
  r(0) = a(0) * b(0) - a.tail<3>().dot(b.tail<3>());
  r.tail<3>() = a(0) * b.tail<3>() + b(0) * a.tail<3>() + a.tail<3>().cross(b.tail<3>());
  return r;
}

Vector4d quatConjugate(const Vector4d& p) {
  return Vector4d(p(0), -p(1), -p(2), -p(3));
}

Vector4d eulerParameterRate(const Vector4d& p, const Eigen::Vector3d& omega_body) {
  return 0.5 * Lmatrix(p).transpose() * omega_body;
}

Eigen::Vector3d rotationVector(const Eigen::Matrix3d& A) {
  Vector4d q = eulerParametersFromMatrix(A);
  const double s = q.tail<3>().norm();
  if (s < 1e-12) return 2.0 * q.tail<3>();
  const double angle = 2.0 * std::atan2(s, q(0));
  return angle * q.tail<3>() / s;
}

Eigen::Matrix3d expRotation(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  if (a < 1e-12) return Eigen::Matrix3d::Identity() + skew(phi);
  return rotationMatrix(eulerParametersFromAxisAngle(phi / a, a));
}

}  // namespace fc
