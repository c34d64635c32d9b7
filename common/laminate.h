#pragma once
// Laminates: classical lamination theory plus first-order shear deformation
// (Reddy, Mechanics of Laminated Composite Plates and Shells, 2nd ed., ch. 3).
// The ABD and transverse-shear matrices here are exactly what fe-prep's shells use.
#include <Eigen/Dense>
#include <map>
#include <optional>
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

// Transverse shear stiffness of a laminate from its stacking (docs/laminate-shear.md):
// for bending about each laminate
// axis in turn (cylindrical bending, Whitney 1973; Vlachoutsis 1992) the bending
// stress sigma = Qbar_aa (z - z_n) kappa gives, by equilibrium, the piecewise
// quadratic shear stress tau(z) = Q g(z) / R, and the stiffness A_aa = R^2 / I with
//   z_n = int Qbar_aa z dz / int Qbar_aa dz,   R = int Qbar_aa (z - z_n)^2 dz,
//   g(z) = - int_{-h/2}^{z} Qbar_aa (s - z_n) ds,   I = int g^2 / G_az dz
// equates the shear strain energy of tau(z) with that of a constant shear strain.
// The factors k_a = A_aa / int G_az dz scale the summed ply shear stiffness,
// As_ab = sqrt(k_a k_b) int G_ab dz (so As stays symmetric positive definite and
// the xz-yz coupling of off-axis plies is kept). A homogeneous plate gives k = 5/6
// exactly; thin stiff faces on a soft core give sandwich theory's G_c d^2 / c.
struct TransverseShear {
  Eigen::Matrix2d As = Eigen::Matrix2d::Zero();   // [Q_x, Q_y] = As [gamma_xz, gamma_yz]
  Eigen::Vector2d factor = Eigen::Vector2d::Zero();  // k_x, k_y against the summed G t
};
TransverseShear transverseShearFromStacking(const Laminate& lam, const MaterialLibrary& materials);

// With shear_correction given, As is that factor times the summed ply shear
// stiffness (a user's or a Nastran PSHELL's TS/T); without it, As follows from the
// stacking (transverseShearFromStacking), which for a homogeneous plate is 5/6.
LaminateStiffness laminateStiffness(const Laminate& lam, const MaterialLibrary& materials,
                                    std::optional<double> shear_correction = std::nullopt);

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
