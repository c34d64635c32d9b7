#pragma once
// Material axes of a ply in the section, as VABS defines them (VABS manual,
// "element orientation"): rotate the beam frame (x1, x2, x3) about x1 by
// theta1 to get the ply's (x1, y2, y3), y3 the ply normal; then rotate about y3
// by theta3 (the lay-up angle) to put y1 along the fibre.
#include <Eigen/Dense>

#include "section-prep/section_mesh.h"

namespace fc::section {

// Columns: the material axes y1, y2, y3 in beam components.
Eigen::Matrix3d materialAxes(double theta1_rad, double theta3_rad);

// Stiffness seen in frame B when R's columns are frame A's axes in B
// components: C_B = T C_A T^T, T the Voigt [11,22,33,23,13,12] stress
// transformation (Ting, Anisotropic Elasticity, 1996, sec. 2.6).
Matrix6d rotateVoigtStiffness(const Matrix6d& C, const Eigen::Matrix3d& R);

}  // namespace fc::section
