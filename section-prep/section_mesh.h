#pragma once
// The cross-section as the solver sees it: a 2-D mesh in the (x2, x3) plane with
// per-element materials and orientations, in the conventions of VABS (Yu, VABS
// manual; Hodges 2006, ch. 4) so that VABS inputs map onto it one to one.
#include <Eigen/Dense>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/materials.h"

namespace fc::section {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Stiffness in the material axes (y1 = fibre, y3 = ply normal), Voigt order
// [11, 22, 33, 23, 13, 12] with engineering shear strains, as fc::Material::C.
struct SectionMaterial {
  std::string name;
  Matrix6d C = Matrix6d::Zero();
  double rho = 0.0;
  // Ply strengths (`strength:` of the material), for recovery's failure indices.
  std::optional<PlyStrength> strength;
};

// Why a material cannot be used by section-prep's displacement elements, or "".
// Nearly incompressible materials (bulk over shear modulus above ~3e4, i.e.
// nu > 0.49998 when isotropic) lock them: measured on a solid circle, the shear
// stiffness is right to 1e-4 up to nu = 0.49999 but 7% off at 0.499999 and 300x
// too small at 0.49999999 (docs/robustness.md). Voigt C's eigenvalues are 3K and
// G-like values, so the bound is on its condition number.
std::string materialProblem(const SectionMaterial& m);

enum class ElementShape { Triangle, Quadrilateral };

// Node slots follow VABS: quadrilateral corners 0-3 counter-clockwise, mid-sides
// 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0), centre 8. Triangle corners 0-2, slot 3
// unused, mid-sides 4 (0-1), 5 (1-2), 6 (2-0). Absent nodes are -1, so every
// element from 3 to 9 nodes has one description.
struct SectionElement {
  ElementShape shape = ElementShape::Triangle;
  std::array<int, 9> nodes{{-1, -1, -1, -1, -1, -1, -1, -1, -1}};
  int material = 0;            // index into SectionMesh::materials
  double theta3_deg = 0.0;     // ply angle: fibre from x1, about the ply normal y3
  // Element orientation theta1: angle from x2 to the ply's y2 axis about x1.
  // Either one value (theta1_nodal false, theta1_deg[0]) or one per node slot,
  // interpolated with the shape functions (VABS's old input format).
  bool theta1_nodal = false;
  std::array<double, 9> theta1_deg{};
  int user_id = 0;             // element number in the user's file, for messages
  int source_line = 0;         // its line in that file (VABS .sg), 0 when meshed here
};

struct SectionMesh {
  std::string source_file;     // the .sg file read, for located errors ("" when meshed)
  std::vector<Eigen::Vector2d> nodes;
  std::vector<SectionElement> elements;
  std::vector<SectionMaterial> materials;
};

}  // namespace fc::section
