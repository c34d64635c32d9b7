#pragma once
// Geometry of a straight-sided triangle in its own plane: area coordinates
// L_i, their constant gradients and the three sides (0->1, 1->2, 2->0).
#include <Eigen/Dense>

namespace fc::fe {

struct TriangleGeometry {
  Eigen::Matrix<double, 3, 2> xy;     // row i: in-plane coordinates of node i
  double area = 0.0;                  // positive for counter-clockwise nodes
  Eigen::Matrix<double, 3, 2> grad;   // row i: gradient of L_i (constant)
  Eigen::Vector3d side_length;        // side k joins nodes k and (k+1)%3
  Eigen::Matrix<double, 3, 2> tangent;  // row k: unit vector from node k to node k+1
};

// Throws std::invalid_argument for a degenerate or clockwise triangle, because
// every operator below divides by the (signed) area.
TriangleGeometry triangleGeometry(const Eigen::Matrix<double, 3, 2>& xy);

// Three interior points
// (2/3, 1/6, 1/6) and permutations, weights A/3; exact for quadratics.
struct TrianglePoint {
  Eigen::Vector3d L;
  double weight_fraction;  // multiply by the area
};
const TrianglePoint* quadraticRule();  // 3 points

}  // namespace fc::fe
