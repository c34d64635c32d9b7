#pragma once
// Geometric stiffening of a reduced flexible body (theory and limits in
// docs/mbs-run.md, "Geometric stiffening"; the file's data in docs/body-file.md,
// "Geometric stiffness"). With `geometric_stiffening: true` the modal rows get
//   - K_G(p) w,   K_G(p) = sum_c p_c K_c,
// K_c the modal geometric stiffness of fe-prep's twelve unit inertial load cases
// and p the body's current load parameters, all in body axes:
//   p = [a0 (3), w_x^2, w_y^2, w_z^2, w_x w_y, w_y w_z, w_z w_x, alpha (3)],
//   a0 = A^T (rddot - g): the frame origin's acceleration minus gravity,
//   omega', alpha' = d omega'/dt: the frame's angular velocity and acceleration.
// The velocity cases are known from the state; a0 and alpha come from the
// accelerations of the same evaluation (mbs-run/constrained/system.cpp solves once without
// them and once more with them).
#include <Eigen/Dense>

#include <array>
#include <map>
#include <string>

namespace fc::mbs {

using StiffeningParameters = Eigen::Matrix<double, 12, 1>;

struct GeometricStiffening {
  std::array<Eigen::MatrixXd, 12> K;  // (nm, nm) per case, the file's order
  bool acceleration_cases = false;    // some a0 or alpha case is non-zero (then a second solve is needed)
  // Loads applied at interfaces (/geometric_stiffness/interfaces/NAME/matrices):
  // per interface the (nm, nm) matrices of a unit force x y z and moment x y z
  // in body axes at its point; the factors are the force and moment the body
  // receives there from the joints attached to it (mbs-run/constrained/system.cpp, from the
  // multipliers of a first solve, as the acceleration cases).
  std::map<std::string, std::array<Eigen::MatrixXd, 6>> interfaces;
};

// The leading (modes, modes) block of each case of /geometric_stiffness/matrices.
// Throws fc::H5Error naming the file when it has no such data or a wrong shape,
// std::invalid_argument for non-finite or non-symmetric matrices.
GeometricStiffening readGeometricStiffening(const std::string& file, int modes);

// p from omega', alpha' and a0 (body axes).
StiffeningParameters stiffeningParameters(const Eigen::Vector3d& omega, const Eigen::Vector3d& alpha,
                                          const Eigen::Vector3d& a0);

// sum_c p_c K_c over the cases selected: velocity (the six omega products) and/or
// acceleration (a0 and alpha).
Eigen::MatrixXd stiffeningMatrix(const GeometricStiffening& g, const StiffeningParameters& p, bool velocity_cases,
                                 bool acceleration_cases);

}  // namespace fc::mbs
