#include "fe-prep/elements/shell_frame.h"

#include <algorithm>
#include <stdexcept>

namespace fc::fe {

ShellFrame shellFrame(const Eigen::Matrix3d& xyz, const Eigen::Vector3d& material_x) {
  const Eigen::Vector3d a = (xyz.row(1) - xyz.row(0)).transpose();
  const Eigen::Vector3d b = (xyz.row(2) - xyz.row(0)).transpose();
  const Eigen::Vector3d n = a.cross(b);
  const double scale = std::max({a.squaredNorm(), b.squaredNorm(), 1e-300});
  if (n.norm() <= 1e-12 * scale)
    throw std::invalid_argument("shell triangle: the three nodes are (nearly) collinear");
  const Eigen::Vector3d e3 = n.normalized();
  const double mx = material_x.norm();
  const Eigen::Vector3d p = material_x - material_x.dot(e3) * e3;
  // Below ~0.1 degree from the normal the projected fibre direction is noise.
  if (!(mx > 0.0) || p.norm() < 1e-3 * mx)
    throw std::invalid_argument(
        "shell triangle: material_x is normal to the element, so the ply angles are undefined");
  const Eigen::Vector3d e1 = p.normalized();
  const Eigen::Vector3d e2 = e3.cross(e1);
  ShellFrame f;
  f.R.row(0) = e1.transpose();
  f.R.row(1) = e2.transpose();
  f.R.row(2) = e3.transpose();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d d = (xyz.row(i) - xyz.row(0)).transpose();
    f.xy(i, 0) = e1.dot(d);
    f.xy(i, 1) = e2.dot(d);
  }
  return f;
}

}  // namespace fc::fe
