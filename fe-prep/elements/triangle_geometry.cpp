#include "fe-prep/elements/triangle_geometry.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fc::fe {

TriangleGeometry triangleGeometry(const Eigen::Matrix<double, 3, 2>& xy) {
  TriangleGeometry g;
  g.xy = xy;
  const double twice_area = (xy(1, 0) - xy(0, 0)) * (xy(2, 1) - xy(0, 1)) -
                            (xy(2, 0) - xy(0, 0)) * (xy(1, 1) - xy(0, 1));
  double scale = 0.0;
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    const Eigen::Vector2d d = (xy.row(j) - xy.row(k)).transpose();
    g.side_length(k) = d.norm();
    scale = std::max(scale, g.side_length(k));
  }
  // Relative test: a sliver with area ~ roundoff * h^2 has no usable gradients.
  if (!(twice_area > 1e-12 * scale * scale))
    throw std::invalid_argument("triangle element: degenerate or clockwise triangle (2A = " +
                                std::to_string(twice_area) + ")");
  g.area = 0.5 * twice_area;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    g.grad(i, 0) = (xy(j, 1) - xy(k, 1)) / twice_area;
    g.grad(i, 1) = (xy(k, 0) - xy(j, 0)) / twice_area;
  }
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    g.tangent.row(k) = (xy.row(j) - xy.row(k)) / g.side_length(k);
  }
  return g;
}

const TrianglePoint* quadraticRule() {
  static const TrianglePoint rule[3] = {
      {Eigen::Vector3d(2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0), 1.0 / 3.0},
      {Eigen::Vector3d(1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0), 1.0 / 3.0},
      {Eigen::Vector3d(1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0), 1.0 / 3.0}};
  return rule;
}

}  // namespace fc::fe
