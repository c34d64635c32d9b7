#pragma once
// Closed-form and tabulated plate frequencies the fe-prep tests compare with.
#include <Eigen/Dense>
#include <cmath>

namespace fc::feprep::test {

// Navier solution, simply supported rectangular plate a x b (x along a), classical
// (Kirchhoff) theory, specially orthotropic D (D16 = D26 = 0):
//   omega_mn^2 = pi^4 / rho_A [D11 (m/a)^4 + 2 (D12 + 2 D66) (m/a)^2 (n/b)^2 + D22 (n/b)^4]
// (Reddy, Mechanics of Laminated Composite Plates and Shells, 2nd ed., eq. 5.3.x; Leissa,
// Vibration of Plates, NASA SP-160, eq. 4.20 for the isotropic case).
inline double navierClassical(const Eigen::Matrix3d& D, double rho_A, double a, double b, int m, int n) {
  const double p = m * M_PI / a, q = n * M_PI / b;
  return std::sqrt((D(0, 0) * std::pow(p, 4) + 2 * (D(0, 1) + 2 * D(2, 2)) * p * p * q * q + D(1, 1) * std::pow(q, 4)) /
                   rho_A);
}

// Navier solution of first-order shear deformation theory, simply supported
// (SS-1) cross-ply plate, flexural mode (Reddy, 2nd ed., sec. 6.6.x): the smallest
// root of det(S - omega^2 diag(I0, I2, I2)) = 0 with, alpha = m pi / a, beta = n pi / b,
//   S = [[As55 a^2 + As44 b^2, As55 a,                As44 b              ],
//        [As55 a,              D11 a^2 + D66 b^2 + As55, (D12 + D66) a b     ],
//        [As44 b,              (D12 + D66) a b,       D66 a^2 + D22 b^2 + As44]]
// As = transverse shear stiffness (correction included), I2 = rotary inertia per area.
inline double navierFirstOrderShear(const Eigen::Matrix3d& D, const Eigen::Matrix2d& As, double I0, double I2,
                                    double a, double b, int m, int n) {
  const double al = m * M_PI / a, be = n * M_PI / b;
  const double A55 = As(0, 0), A44 = As(1, 1);
  Eigen::Matrix3d S;
  S << A55 * al * al + A44 * be * be, A55 * al, A44 * be,  //
      A55 * al, D(0, 0) * al * al + D(2, 2) * be * be + A55, (D(0, 1) + D(2, 2)) * al * be,  //
      A44 * be, (D(0, 1) + D(2, 2)) * al * be, D(2, 2) * al * al + D(1, 1) * be * be + A44;
  const Eigen::Vector3d Mdiag(I0, I2, I2);
  const Eigen::Matrix3d Mi = Mdiag.cwiseInverse().cwiseSqrt().asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Mi * S * Mi);
  return std::sqrt(es.eigenvalues()(0));
}

// Leissa, Vibration of Plates (NASA SP-160, 1969), table 4.51 (square cantilever
// plate, C-F-F-F, nu = 0.3): lambda = omega a^2 sqrt(rho h / D).
inline constexpr double kLeissaCantileverSquare[5] = {3.4917, 8.5246, 21.429, 27.331, 31.111};
// Leissa table 4.80 / Gorman (free square plate, nu = 0.3), first three elastic modes.
inline constexpr double kLeissaFreeSquare[3] = {13.468, 19.596, 24.270};

}  // namespace fc::feprep::test
