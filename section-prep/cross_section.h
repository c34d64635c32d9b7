#pragma once
// Cross-sectional stiffness and inertia of a prismatic beam by the
// variational-asymptotic method, discretised with 2-D finite elements as in
// VABS: Cesnik & Hodges (J. Am. Helicopter Soc. 42, 1997) for the classical
// model, Yu, Hodges, Volovoi & Cesnik (IJSS 39, 2002) for the generalized
// Timoshenko model; notation of Hodges, Nonlinear Composite Beam Theory (2006),
// ch. 4. Straight, untwisted beams.
#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "section-prep/section_mesh.h"

namespace fc::section {

// Stress recovery (dehomogenization) basis: the 3-D strain and stress at each
// section element's centroid for a unit value of each Timoshenko resultant in
// turn, [F1, F2, F3, M1, M2, M3] (the /stiffness/timoshenko order), from the
// first-order warping w = V0 e + V1 e' (docs/section-prep.md, "Stress recovery").
struct ElementRecovery {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();  // (x2, x3)
  // Columns: the element's material axes y1 (fibre), y2, y3 (ply normal) in the
  // section frame; for an isotropic material y1 = x1 (theta3 taken as 0).
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  // Row = component [11, 22, 33, 23, 13, 12] in the section frame (engineering
  // shear strains), column = resultant.
  Matrix6d strain = Matrix6d::Zero(), stress = Matrix6d::Zero();
};

struct SectionProperties {
  // Order [extension, twist, bending about x2, bending about x3].
  Eigen::Matrix4d classical = Eigen::Matrix4d::Zero();
  // Order [extension, shear x2, shear x3, twist, bending x2, bending x3] (VABS).
  Matrix6d timoshenko = Matrix6d::Zero();
  Matrix6d mass = Matrix6d::Zero();  // same order, about the origin
  double mass_per_length = 0.0;
  double area = 0.0;
  Eigen::Vector2d geometric_center = Eigen::Vector2d::Zero();
  Eigen::Vector2d mass_center = Eigen::Vector2d::Zero();
  Eigen::Vector2d tension_center = Eigen::Vector2d::Zero();
  Eigen::Vector2d shear_center = Eigen::Vector2d::Zero();
  bool has_timoshenko = false;
  // One per mesh element (empty when the Timoshenko model was not asked for).
  std::vector<ElementRecovery> recovery;
  long n_nodes = 0, n_elements = 0, n_dof = 0;
  // Process CPU seconds per phase (the benchmark and docs report them).
  double cpu_assembly = 0, cpu_factorisation = 0, cpu_solves = 0;
};

struct AnalysisOptions {
  bool timoshenko = true;
  // The stress recovery basis (needs the Timoshenko model's first-order warping).
  bool recovery = true;
  // Called with a phase name and the fraction done (for fc::Progress).
  std::function<void(const std::string&, double)> progress;
};

// Throws std::runtime_error naming the element for degenerate geometry, and
// when the section is not one connected body (the warping problem is then
// singular beyond the four rigid modes).
SectionProperties analyzeSection(const SectionMesh& mesh, const AnalysisOptions& options = {});

// Whether C is isotropic (to 1e-9 of its largest entry): such an element has
// no fibre, and recovery takes the beam axis as its 1-axis (contracts.md).
bool isIsotropicMaterial(const Matrix6d& C);

// Derived quantities, exposed for tests.
Matrix6d sectionMassMatrix(double mu, const Eigen::Vector2d& first_moment,
                           const Eigen::Matrix2d& second_moment);
Eigen::Vector2d shearCenterFromTimoshenko(const Matrix6d& K);
Eigen::Vector2d tensionCenterFromClassical(const Eigen::Matrix4d& K);

}  // namespace fc::section
