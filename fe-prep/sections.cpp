// Closed-form sections of homogeneous isotropic beams (see body_spec.h).
#include <cmath>

#include "fe-prep/body_spec.h"

namespace fc::feprep {
namespace {

// A and the second moments I2 = int x3^2, I3 = int x2^2 about the centroid.
SectionMatrices assemble(double A, double I2, double I3, double J, double k, double E, double nu, double rho) {
  const double G = E / (2 * (1 + nu));
  SectionMatrices s;
  s.K.setZero();
  s.K.diagonal() << E * A, k * G * A, k * G * A, G * J, E * I2, E * I3;
  s.M.setZero();
  s.M.diagonal() << rho * A, rho * A, rho * A, rho * (I2 + I3), rho * I2, rho * I3;
  return s;
}

}  // namespace

SectionMatrices solidCircleSection(double d, double E, double nu, double rho) {
  const double A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64;
  return assemble(A, I, I, 2 * I, 6 * (1 + nu) / (7 + 6 * nu), E, nu, rho);
}

SectionMatrices tubeSection(double D, double t, double E, double nu, double rho) {
  const double Di = D - 2 * t, m = Di / D;
  const double A = M_PI * (D * D - Di * Di) / 4, I = M_PI * (std::pow(D, 4) - std::pow(Di, 4)) / 64;
  const double q = (1 + m * m) * (1 + m * m);
  const double k = 6 * (1 + nu) * q / ((7 + 6 * nu) * q + (20 + 12 * nu) * m * m);
  return assemble(A, I, I, 2 * I, k, E, nu, rho);
}

SectionMatrices rectangleSection(double b, double h, double E, double nu, double rho) {
  // Saint-Venant torsion constant of a rectangle, series truncated (Roark, table 10.7):
  // J = a c^3 (1/3 - 0.21 c/a (1 - c^4 / (12 a^4))), a >= c; better than 0.5 %.
  const double a = std::max(b, h), c = std::min(b, h);
  const double J = a * c * c * c * (1.0 / 3 - 0.21 * c / a * (1 - std::pow(c / a, 4) / 12));
  return assemble(b * h, b * h * h * h / 12, h * b * b * b / 12, J, 10 * (1 + nu) / (12 + 11 * nu), E, nu, rho);
}

}  // namespace fc::feprep
