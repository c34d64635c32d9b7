#include "laminates.h"

#include <cmath>

namespace fc::fe::test {

LaminateStiffness isotropicPlate(double E, double nu, double rho, double h, double kappa) {
  OrthoPly p{E, E, E / (2 * (1 + nu)), E / (2 * (1 + nu)), E / (2 * (1 + nu)), nu, rho, h, 0.0};
  return orthotropicLaminate({p}, kappa);
}

LaminateStiffness orthotropicLaminate(const std::vector<OrthoPly>& plies, double kappa) {
  LaminateStiffness s;
  double h = 0;
  for (const auto& p : plies) h += p.thickness;
  s.thickness = h;
  double z0 = -h / 2;
  for (const auto& p : plies) {
    const double z1 = z0 + p.thickness;
    const double nu21 = p.nu12 * p.E2 / p.E1, den = 1 - p.nu12 * nu21;
    const double Q11 = p.E1 / den, Q22 = p.E2 / den, Q12 = p.nu12 * p.E2 / den, Q66 = p.G12;
    const double t = p.angle_deg * M_PI / 180.0, c = std::cos(t), sn = std::sin(t);
    const double c2 = c * c, s2 = sn * sn;
    Eigen::Matrix3d Q;
    Q(0, 0) = Q11 * c2 * c2 + 2 * (Q12 + 2 * Q66) * s2 * c2 + Q22 * s2 * s2;
    Q(0, 1) = (Q11 + Q22 - 4 * Q66) * s2 * c2 + Q12 * (s2 * s2 + c2 * c2);
    Q(1, 1) = Q11 * s2 * s2 + 2 * (Q12 + 2 * Q66) * s2 * c2 + Q22 * c2 * c2;
    Q(0, 2) = (Q11 - Q12 - 2 * Q66) * sn * c * c2 + (Q12 - Q22 + 2 * Q66) * sn * s2 * c;
    Q(1, 2) = (Q11 - Q12 - 2 * Q66) * sn * s2 * c + (Q12 - Q22 + 2 * Q66) * sn * c * c2;
    Q(2, 2) = (Q11 + Q22 - 2 * Q12 - 2 * Q66) * s2 * c2 + Q66 * (s2 * s2 + c2 * c2);
    Q(1, 0) = Q(0, 1);
    Q(2, 0) = Q(0, 2);
    Q(2, 1) = Q(1, 2);
    Eigen::Matrix2d Qs;  // [xz, yz]: Q55, Q45, Q44
    Qs(0, 0) = p.G13 * c2 + p.G23 * s2;
    Qs(1, 1) = p.G13 * s2 + p.G23 * c2;
    Qs(0, 1) = Qs(1, 0) = (p.G13 - p.G23) * c * sn;
    s.A += Q * (z1 - z0);
    s.B += Q * (z1 * z1 - z0 * z0) / 2;
    s.D += Q * (z1 * z1 * z1 - z0 * z0 * z0) / 3;
    s.As += kappa * Qs * (z1 - z0);
    s.mass_per_area += p.rho * (z1 - z0);
    s.first_moment += p.rho * (z1 * z1 - z0 * z0) / 2;
    s.rotary_per_area += p.rho * (z1 * z1 * z1 - z0 * z0 * z0) / 3;
    z0 = z1;
  }
  return s;
}

}  // namespace fc::fe::test
