#include "common/laminate.h"

#include <cmath>

namespace fc {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Plane stress (sigma_33 = sigma_13 = sigma_23 = 0) condenses the 3-D compliance:
// the in-plane stiffness is the inverse of the in-plane block of S, the
// transverse-shear stiffness the inverse of the [13, 23] block. Exact for any
// anisotropy, and for orthotropic plies it is Reddy's eq. (3.3.14).
Eigen::Matrix3d inPlaneStiffness(const Matrix6d& C) {
  const Matrix6d S = C.inverse();
  const int idx[3] = {0, 1, 5};
  Eigen::Matrix3d s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s(i, j) = S(idx[i], idx[j]);
  return s.inverse();
}

Eigen::Matrix2d shearStiffness(const Matrix6d& C) {
  const Matrix6d S = C.inverse();
  const int idx[2] = {4, 3};  // [xz, yz]
  Eigen::Matrix2d s;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) s(i, j) = S(idx[i], idx[j]);
  return s.inverse();
}

}  // namespace

double Laminate::thickness() const {
  double h = 0;
  for (const auto& p : plies) h += p.thickness;
  return h;
}

Eigen::Matrix3d reducedStiffness(const Material& m) { return inPlaneStiffness(m.C); }

Eigen::Matrix3d rotatedReducedStiffness(const Material& m, double angle_rad) {
  return inPlaneStiffness(plyStiffnessInLaminateAxes(m.C, angle_rad));
}

Eigen::Matrix2d rotatedTransverseShear(const Material& m, double angle_rad) {
  return shearStiffness(plyStiffnessInLaminateAxes(m.C, angle_rad));
}

LaminateStiffness laminateStiffness(const Laminate& lam, const MaterialLibrary& materials,
                                    double shear_correction) {
  LaminateStiffness out;
  const double h = lam.thickness();
  out.thickness = h;
  double z0 = -0.5 * h;
  for (const auto& ply : lam.plies) {
    const auto it = materials.find(ply.material);
    if (it == materials.end())
      throw std::invalid_argument("laminate '" + lam.name + "': unknown material '" +
                                  ply.material + "'");
    const Material& m = it->second;
    const double a = ply.angle_deg * kPi / 180.0;
    const double z1 = z0 + ply.thickness;
    const Eigen::Matrix3d Q = rotatedReducedStiffness(m, a);
    const double h1 = z1 - z0, h2 = (z1 * z1 - z0 * z0) / 2, h3 = (z1 * z1 * z1 - z0 * z0 * z0) / 3;
    out.A += Q * h1;
    out.B += Q * h2;
    out.D += Q * h3;
    out.As += shear_correction * rotatedTransverseShear(m, a) * h1;
    out.mass_per_area += m.rho * h1;
    out.first_moment += m.rho * h2;
    out.rotary_per_area += m.rho * h3;
    z0 = z1;
  }
  return out;
}

Laminate homogeneousLaminate(const std::string& material, double thickness) {
  Laminate lam;
  lam.name = material;
  lam.plies.push_back({material, thickness, 0.0});
  return lam;
}

Laminate readPlies(const InputNode& plies, const MaterialLibrary& materials,
                   const std::string& name) {
  Laminate lam;
  lam.name = name;
  if (plies.size() == 0) plies.fail("a laminate needs at least one ply");
  for (std::size_t i = 0; i < plies.size(); ++i) {
    InputNode p = plies.at(i);
    p.allowKeys({"material", "thickness", "angle_deg"});
    Ply ply;
    ply.material = lookupMaterial(materials, p["material"]).name;
    // 0.1 um (a coating) to 1 m: beyond, a unit mistake that meshing cannot survive.
    ply.thickness = p["thickness"].asLength(1e-7, 1.0);
    ply.angle_deg = p.number("angle_deg", 0.0);
    lam.plies.push_back(ply);
  }
  return lam;
}

LaminateLibrary readLaminates(const InputNode& block, const MaterialLibrary& materials) {
  LaminateLibrary lib;
  for (const auto& [name, node] : namedEntries(block)) {
    // A laminate is a list of plies, or {plies: [...]}.
    lib[name] = readPlies(node.isMap() ? node["plies"] : node, materials, name);
  }
  return lib;
}

}  // namespace fc
