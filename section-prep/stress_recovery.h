#pragma once
// Stresses in the section for given beam resultants (dehomogenization, as
// VABS's recovery run): the linear combination of the recovery basis that
// analyzeSection computes (cross_section.h, ElementRecovery), the stresses in
// each element's material axes, and the ply failure indices. Theory and
// sources: docs/section-prep.md, "Stress recovery".
#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "common/failure_criteria.h"
#include "common/materials.h"
#include "section-prep/cross_section.h"

namespace fc::section {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// A symmetric tensor in Voigt order [11, 22, 33, 23, 13, 12] (tensor shear
// components for stresses; pass engineering = true for strains, whose shear
// entries are gamma = 2 eps) seen in the frame whose axes are R's columns:
// s' = R^T s R.
Vector6d voigtToAxes(const Vector6d& v, const Eigen::Matrix3d& R, bool engineering);

// The in-plane ply components [s_11, s_22, t_12] of a material-axes Voigt vector.
Eigen::Vector3d plyComponents(const Vector6d& v);

// contracts.md's Tsai-Wu index F1 s1 + F2 s2 + F11 s1^2 + F22 s2^2 + F66 t12^2
// + 2 F12 s1 s2, F12 = -sqrt(F11 F22)/2 (Tsai & Wu, J. Compos. Mater. 5 (1971) 58).
double tsaiWuIndex(const PlyStrength& st, const Eigen::Vector3d& s);
// Max-stress index: the largest of s1/Xt (s1 >= 0) or -s1/Xc, s2/Yt or -s2/Yc,
// |t12|/S12 (Jones, Mechanics of Composite Materials, 2nd ed., sec. 2.9).
double maxStressIndex(const PlyStrength& st, const Eigen::Vector3d& s);
// Tsai-Wu strength ratio: the factor R on the stresses (on the loads, all
// scaled together) at which the index reaches 1: a R^2 + b R = 1 with a the
// quadratic and b the linear part of the index; +inf when no positive R fails.
double tsaiWuStrengthRatio(const PlyStrength& st, const Eigen::Vector3d& s);

struct RecoveredElement {
  Vector6d stress = Vector6d::Zero(), strain = Vector6d::Zero();  // section frame
  Eigen::Vector3d ply_stress = Eigen::Vector3d::Zero();  // [s_11, s_22, t_12], material axes
  Eigen::Vector3d ply_strain = Eigen::Vector3d::Zero();  // [e_11, e_22, g_12]
  bool has_strength = false;
  double tsai_wu = 0, max_stress = 0, strength_ratio = 0;  // only with has_strength
  // Hashin's 3D mode indices from all six stresses in material axes (only
  // with has_strength; common/failure_criteria.h).
  HashinIndices hashin;
};

// `F` = [F1, F2, F3, M1, M2, M3] (N, N m, the /stiffness/timoshenko order).
// `strengths` per mesh material (std::nullopt where a material has none).
std::vector<RecoveredElement> recoverStresses(const std::vector<ElementRecovery>& basis,
                                              const std::vector<int>& element_material,
                                              const std::vector<std::optional<PlyStrength>>& strengths,
                                              const Vector6d& F);

}  // namespace fc::section
