#pragma once
// Flat laminated shell triangle: DST bending (discrete shear triangle, Batoz &
// Lardeur 1989, in the side-local form of Katili 1993; reduces to DKT, Batoz,
// Bathe & Ho 1980, for thin plates), constant-strain membrane with
// membrane-bending coupling (B), and a small fictitious drilling stiffness so
// that coplanar nodes do not leave K singular (paper, section 3.2). Theory,
// conventions and validation: docs/elements.md.
//
// Degrees of freedom, 6 per node, in the BODY frame: [u1 u2 u3 theta1 theta2 theta3]
// with theta the small rotation vector (right-handed about the body axes), the
// convention of the flexible body file (contracts.md).
#include <Eigen/Dense>

#include "common/laminate.h"

namespace fc::fe {

enum class ShellKind { DKT, DST };

using Matrix18d = Eigen::Matrix<double, 18, 18>;
using Vector18d = Eigen::Matrix<double, 18, 1>;

struct ShellMatrices {
  Matrix18d K;       // stiffness
  Matrix18d M;       // consistent mass
  Vector18d lumped;  // diagonal (lumped) mass: 3 translational + 3 rotary per node
};

// xyz: row i = coordinates of node i (body frame), counter-clockwise about the
// intended normal. material_x: the laminate's x axis (0-degree fibre direction),
// projected onto the element plane. drilling: fictitious drilling stiffness as a
// fraction of the smallest diagonal bending-rotation stiffness of the element.
ShellMatrices shellTriangle(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam,
                            ShellKind kind, const Eigen::Vector3d& material_x,
                            double drilling = 1.0e-4);

// Generalised strains at area coordinates L (the centroid: L = (1/3, 1/3, 1/3))
// for the 18 body-frame DOF q of shellTriangle: e = G q with
// e = [eps_x, eps_y, gamma_xy, kappa_x, kappa_y, kappa_xy] in the element's
// laminate axes (shellFrame: x the projected material_x, z the normal), the
// membrane strains of the CST and the curvatures of the DKT/DST plate, so that
// the in-plane strain at height z is eps + z kappa and [N; M] = ABD e exactly
// as in the stiffness. Stress recovery (docs/stresses.md) uses it per mode.
Eigen::Matrix<double, 6, 18> shellStrainOperator(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam,
                                                 ShellKind kind, const Eigen::Vector3d& material_x,
                                                 const Eigen::Vector3d& L);

}  // namespace fc::fe
