#pragma once
// Shape functions of VABS's element family: triangles with 3 to 6 nodes and
// quadrilaterals with 4 to 9 nodes, any mid-side node optional. Quadrilaterals
// use the variable-number-of-nodes construction of Bathe (Finite Element
// Procedures, 1996, fig. 5.4); triangles the same construction on area
// coordinates (Zienkiewicz & Taylor, vol. 1, sec. 8.8).
#include <array>

#include "section-prep/section_mesh.h"

namespace fc::section {

struct ShapeValues {
  std::array<double, 9> N{};     // by node slot; 0 for absent slots
  std::array<double, 9> dNdr{};  // derivatives in the natural coordinates
  std::array<double, 9> dNds{};
};

// `present[k]` tells whether slot k holds a node. For quadrilaterals (r, s) lie
// in [-1, 1]^2; for triangles r, s are the area coordinates L2, L3 (L1 = 1-r-s).
ShapeValues shapeFunctions(ElementShape shape, const std::array<bool, 9>& present, double r,
                           double s);

struct QuadraturePoint {
  double r, s, w;
};
// Gauss 2x2 for 4-node quadrilaterals and 3x3 for the higher ones, exact for
// every section integral on parallelograms; on distorted quadrilaterals no
// rule is exact, and these are the ones whose results coincide with VABS's
// (to 1e-11 on the reference/vabs cases; 3x3 on 4-node quads differs by 6e-6).
// Triangles: Strang-Fix/Dunavant 7 points (degree 5), exact up to 6-node
// straight-sided triangles.
const std::vector<QuadraturePoint>& quadratureRule(ElementShape shape, int node_count);

}  // namespace fc::section
