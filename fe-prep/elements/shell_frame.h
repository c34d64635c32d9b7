#pragma once
// Local frame of a flat shell triangle: e3 the unit normal (counter-clockwise
// nodes), e1 the laminate's x axis projected onto the plane, e2 = e3 x e1.
#include <Eigen/Dense>

namespace fc::fe {

struct ShellFrame {
  Eigen::Matrix3d R;                // rows e1, e2, e3: v_local = R v_body
  Eigen::Matrix<double, 3, 2> xy;   // in-plane coordinates of the nodes (node 1 at origin)
};

// Throws std::invalid_argument if the triangle is degenerate or material_x is
// (nearly) normal to it, since then the fibre direction is undefined.
ShellFrame shellFrame(const Eigen::Matrix3d& xyz, const Eigen::Vector3d& material_x);

}  // namespace fc::fe
