#pragma once
// Classical lamination theory's ply matrices, written out independently of
// common/laminate.h so that the stress-recovery tests check it against the
// textbook (Jones, Mechanics of Composite Materials, 2nd ed., eqs. 2.61 and 2.86;
// Reddy, Mechanics of Laminated Composite Plates and Shells, 2nd ed., sec. 2.3).
#include <Eigen/Dense>
#include <cmath>

namespace fc::feprep::test {

// The reduced stiffness Q of an orthotropic ply in its material axes (plane stress),
// engineering shear strain: sigma = Q [eps_1, eps_2, gamma_12].
inline Eigen::Matrix3d reducedStiffness(double E1, double E2, double G12, double nu12) {
  const double nu21 = nu12 * E2 / E1, d = 1 - nu12 * nu21;
  Eigen::Matrix3d Q;
  Q << E1 / d, nu12 * E2 / d, 0, nu12 * E2 / d, E2 / d, 0, 0, 0, G12;
  return Q;
}

// Reuter's strain transformation from laminate to ply axes for a ply at `deg`
// degrees, engineering strains: [eps_1, eps_2, gamma_12] = T [eps_x, eps_y, gamma_xy].
inline Eigen::Matrix3d reuterT(double deg) {
  const double a = deg * M_PI / 180, c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d T;
  T << c * c, s * s, c * s, s * s, c * c, -c * s, -2 * c * s, 2 * c * s, c * c - s * s;
  return T;
}

}  // namespace fc::feprep::test
