#include "fe-prep/elements/beam_geometric_stiffness.h"

#include <stdexcept>

namespace fc::fe {
namespace {

// One bending plane, DOF (v_a, th_a, v_b, th_b), th = dv/dx (Przemieniecki 15.12).
Eigen::Matrix4d planeGeometricStiffness(double L, double phi) {
  const double a = 6.0 / 5.0 + 2.0 * phi + phi * phi;
  const double b = 2.0 / 15.0 + phi / 6.0 + phi * phi / 12.0;
  const double c = 1.0 / 30.0 + phi / 6.0 + phi * phi / 12.0;
  Eigen::Matrix4d k;
  k << a, L / 10, -a, L / 10,
       L / 10, b * L * L, -L / 10, -c * L * L,
       -a, -L / 10, a, -L / 10,
       L / 10, -c * L * L, -L / 10, b * L * L;
  return k / (L * (1.0 + phi) * (1.0 + phi));
}

}  // namespace

Matrix12d beamGeometricStiffness(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                                 const Eigen::Vector3d& section_x2, const Matrix6d& Ks, double N) {
  double L = 0.0;
  const Eigen::Matrix3d R = beamSectionAxes(xa, xb, section_x2, L);  // v_local = R v_body

  // Shear parameters from the compliance (VABS order: 1 = shear x2, 2 = shear x3,
  // 4 = bending about x2 (displacement u3), 5 = bending about x3 (u2)).
  const Matrix6d C = Ks.inverse();
  const double phi2 = 12.0 * C(1, 1) / (C(5, 5) * L * L);  // u2, th3 plane
  const double phi3 = 12.0 * C(2, 2) / (C(4, 4) * L * L);  // u3, th2 plane
  Matrix12d local = Matrix12d::Zero();
  const Eigen::Matrix4d k2 = planeGeometricStiffness(L, phi2);
  const int d2[4] = {1, 5, 7, 11};  // u2_a, th3_a, u2_b, th3_b: th3 = +du2/dx
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) local(d2[i], d2[j]) += k2(i, j);
  // u3, th2 plane: th2 = -du3/dx, so the rotation DOF enter with a minus sign.
  const Eigen::Matrix4d k3 = planeGeometricStiffness(L, phi3);
  const int d3[4] = {2, 4, 8, 10};
  const double s3[4] = {1.0, -1.0, 1.0, -1.0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) local(d3[i], d3[j]) += s3[i] * s3[j] * k3(i, j);

  const Matrix12d T = beamBlockRotation(R);
  return N * (T.transpose() * local * T);
}

double beamAxialForce(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, const Matrix12d& K,
                      const Vector12d& u) {
  const Eigen::Vector3d e1 = (xb - xa).normalized();
  const Vector12d f = K * u;  // end forces on the element's nodes
  // At node b the element pulls back with -N e1; the force that holds it there is +N e1.
  return f.segment<3>(6).dot(e1);
}

}  // namespace fc::fe
