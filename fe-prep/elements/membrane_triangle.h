#pragma once
// Membrane part of the flat triangle: constant-strain triangle (CST) plus a
// drilling penalty that ties the drilling rotations theta_z to the in-plane
// rotation of the membrane, omega = (v_,x - u_,y)/2 (Hughes & Brezzi 1989):
//   U_drill = c/2 int (sum_i L_i theta_z,i - omega)^2 dA.
// It vanishes for every rigid motion (theta_z = omega), so it adds no spurious
// rigid-body stiffness, and it gives the drilling DOF of a flat mesh a stiffness
// (the paper's "small fictitious drilling stiffness", section 3.2).
#include <Eigen/Dense>

#include "fe-prep/elements/triangle_geometry.h"

namespace fc::fe {

// eps = [eps_x, eps_y, gamma_xy] = membraneStrain(g) * [u1 v1 u2 v2 u3 v3].
Eigen::Matrix<double, 3, 6> membraneStrain(const TriangleGeometry& g);

// Drilling penalty on the 9 DOF [u1 v1 tz1 u2 v2 tz2 u3 v3 tz3]; c has units of
// stiffness per area (N m / m^2).
Eigen::Matrix<double, 9, 9> drillingPenalty(const TriangleGeometry& g, double c);

}  // namespace fc::fe
