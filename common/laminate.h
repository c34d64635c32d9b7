#pragma once
// Laminates: classical lamination theory plus first-order shear deformation
// (Reddy, Mechanics of Laminated Composite Plates and Shells, 2nd ed., ch. 3).
// The ABD and transverse-shear matrices here are exactly what fe-prep's shells use.
#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

#include "common/materials.h"

namespace fc {

struct Ply {
  std::string material;
  double thickness = 0.0;
  double angle_deg = 0.0;  // fibre direction from the laminate x axis, positive about z
};

// Plies listed from the bottom face (z = -h/2) upwards.
struct Laminate {
  std::string name;
  std::vector<Ply> plies;
  double thickness() const;
};

struct LaminateStiffness {
  // Strains [eps_x, eps_y, gamma_xy], curvatures [k_x, k_y, k_xy]:
  //   N = A eps + B k,  M = B eps + D k.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero(),
                  D = Eigen::Matrix3d::Zero();
  // Transverse shear [Q_x, Q_y] = As [gamma_xz, gamma_yz], shear correction included.
  Eigen::Matrix2d As = Eigen::Matrix2d::Zero();
  double thickness = 0.0;
  double mass_per_area = 0.0;     // sum rho_k t_k
  double first_moment = 0.0;      // sum rho_k int z dz (0 for symmetric lay-ups)
  double rotary_per_area = 0.0;   // sum rho_k int z^2 dz
};

// Plane-stress reduced stiffness Q in material axes (Reddy eq. 3.3.14).
Eigen::Matrix3d reducedStiffness(const Material& m);
// Q-bar of a ply at `angle_rad` (Reddy eq. 3.3.25), order [xx, yy, xy].
Eigen::Matrix3d rotatedReducedStiffness(const Material& m, double angle_rad);
// Transverse shear stiffness of a ply in laminate axes, order [xz, yz].
Eigen::Matrix2d rotatedTransverseShear(const Material& m, double angle_rad);

// shear_correction multiplies the transverse shear stiffness (5/6 by default,
// exact for a homogeneous plate in the energy sense).
LaminateStiffness laminateStiffness(const Laminate& lam, const MaterialLibrary& materials,
                                    double shear_correction = 5.0 / 6.0);

// A homogeneous single-material plate as a one-ply laminate.
Laminate homogeneousLaminate(const std::string& material, double thickness);

using LaminateLibrary = std::map<std::string, Laminate>;
// Reads a `laminates:` block (with `include: FILE`); plies are checked against the
// material library.
LaminateLibrary readLaminates(const InputNode& block, const MaterialLibrary& materials);
// Reads an inline list of plies: [{material, thickness, angle_deg}, ...].
Laminate readPlies(const InputNode& plies, const MaterialLibrary& materials,
                   const std::string& name = "");

}  // namespace fc
