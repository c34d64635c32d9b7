#pragma once
// Linear elastic materials. Stiffness in Voigt order [11, 22, 33, 23, 13, 12]
// with engineering shear strains (gamma = 2 eps), as VABS and most FE codes.
#include <Eigen/Dense>
#include <map>
#include <optional>
#include <string>

#include "common/input.h"

namespace fc {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Ply strengths for failure indices (contracts.md `strength: {Xt, Xc, Yt, Yc, S12}`),
// all positive magnitudes in Pa: tension and compression along the fibre (1) and
// across it (2), and in-plane shear (12).
struct PlyStrength {
  double Xt = 0, Xc = 0, Yt = 0, Yc = 0, S12 = 0;
};

struct Material {
  enum class Kind { Isotropic, Orthotropic, Anisotropic };
  std::string name;
  Kind kind = Kind::Isotropic;
  double rho = 0.0;
  Matrix6d C = Matrix6d::Zero();  // stiffness in material axes
  // Engineering constants (isotropic and orthotropic; NaN for anisotropic).
  double E1 = 0, E2 = 0, E3 = 0, G12 = 0, G13 = 0, G23 = 0, nu12 = 0, nu13 = 0, nu23 = 0;
  std::optional<PlyStrength> strength;  // `strength:` key, when given

  Matrix6d compliance() const { return C.inverse(); }
};

// Constructors check admissibility (positive moduli, Poisson bounds, positive-
// definite stiffness) and throw std::invalid_argument with the reason.
Material makeIsotropic(const std::string& name, double E, double nu, double rho);
Material makeOrthotropic(const std::string& name, double E1, double E2, double E3, double G12,
                         double G13, double G23, double nu12, double nu13, double nu23,
                         double rho);
Material makeAnisotropic(const std::string& name, const Matrix6d& C, double rho);

// Compliance of an orthotropic material in its axes (Voigt order, engineering
// shear), without admissibility checks: for readers of other formats (VABS) that
// check the resulting stiffness themselves.
Matrix6d orthotropicCompliance(double E1, double E2, double E3, double G12, double G13,
                               double G23, double nu12, double nu13, double nu23);

using MaterialLibrary = std::map<std::string, Material>;

// Reads a `materials:` block (with `include: FILE`); bad entries raise InputError.
//   {type: isotropic, E, nu, rho}
//   {type: orthotropic, E1, E2, E3, G12, G13, G23, nu12, nu13, nu23, rho}
//   {type: honeycomb, E3, G13, G23, rho} a sandwich core (orthotropic; optional
//     E1, E2, G12 default to 1e-3 min(G13, G23), nu12, nu13, nu23 to 0)
//   {type: anisotropic, C: 6x6 (Voigt, material axes), rho}
// each optionally with strength: {Xt, Xc, Yt, Yc, S12} (Pa, all positive).
MaterialLibrary readMaterials(const InputNode& block);
// Reads a `strength: {Xt, Xc, Yt, Yc, S12}` map; every value positive and in a
// physical range, else InputError at the key.
PlyStrength readStrength(const InputNode& strength);
// Looks up `node`'s scalar as a material name, with a did-you-mean error.
const Material& lookupMaterial(const MaterialLibrary& lib, const InputNode& node);

// Bond transformation (Ting, Anisotropic Elasticity, 1996, ch. 2): the stiffness
// seen in a new frame when vector components transform as v' = R v.
// C' = T C T^T with T the stress transformation built from R.
Matrix6d rotateStiffness(const Matrix6d& C, const Eigen::Matrix3d& R);
// Stiffness of a ply whose fibre (axis 1) lies at `angle_rad` from the laminate x
// axis, positive about axis 3: the ply's stiffness in laminate axes.
Matrix6d plyStiffnessInLaminateAxes(const Matrix6d& C, double angle_rad);

}  // namespace fc
