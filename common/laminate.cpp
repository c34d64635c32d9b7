#include "common/laminate.h"

#include <cmath>
#include <stdexcept>

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

TransverseShear transverseShearFromStacking(const Laminate& lam, const MaterialLibrary& materials) {
  // Per ply: bottom z, thickness, Qbar_11 and Qbar_22 (bending stiffness about
  // each axis), and the ply's shear stiffness in laminate axes.
  struct Layer {
    double z0, t;
    double E[2];
    Eigen::Matrix2d G;
  };
  std::vector<Layer> layers;
  double z = -0.5 * lam.thickness();
  for (const auto& ply : lam.plies) {
    const auto it = materials.find(ply.material);
    if (it == materials.end())
      throw std::invalid_argument("laminate '" + lam.name + "': unknown material '" + ply.material + "'");
    const double a = ply.angle_deg * kPi / 180.0;
    const Eigen::Matrix3d Q = rotatedReducedStiffness(it->second, a);
    layers.push_back({z, ply.thickness, {Q(0, 0), Q(1, 1)}, rotatedTransverseShear(it->second, a)});
    z += ply.thickness;
  }
  // Three-point Gauss-Legendre on each ply: g^2 is a quartic in z, integrated exactly.
  const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  TransverseShear out;
  Eigen::Matrix2d summed = Eigen::Matrix2d::Zero();
  for (const Layer& L : layers) summed += L.G * L.t;
  for (int d = 0; d < 2; ++d) {
    // Neutral axis of cylindrical bending about this axis (N = 0): z_n.
    double s0 = 0, s1 = 0;
    for (const Layer& L : layers) {
      s0 += L.E[d] * L.t;
      s1 += L.E[d] * L.t * (L.z0 + 0.5 * L.t);
    }
    const double zn = s1 / s0;
    double R = 0, I = 0, g0 = 0;  // g0 = g at the ply's bottom; g(-h/2) = 0
    for (const Layer& L : layers) {
      const double a0 = L.z0 - zn, a1 = a0 + L.t;
      R += L.E[d] * (a1 * a1 * a1 - a0 * a0 * a0) / 3;
      for (int q = 0; q < 3; ++q) {
        const double s = a0 + 0.5 * L.t * (1 + gx[q]);
        const double g = g0 - 0.5 * L.E[d] * (s * s - a0 * a0);
        I += 0.5 * L.t * gw[q] * g * g / L.G(d, d);
      }
      g0 -= 0.5 * L.E[d] * (a1 * a1 - a0 * a0);
    }
    out.factor(d) = R * R / I / summed(d, d);
  }
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) out.As(i, j) = std::sqrt(out.factor(i) * out.factor(j)) * summed(i, j);
  return out;
}

LaminateStiffness laminateStiffness(const Laminate& lam, const MaterialLibrary& materials,
                                    std::optional<double> shear_correction) {
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
    if (shear_correction) out.As += *shear_correction * rotatedTransverseShear(m, a) * h1;
    out.mass_per_area += m.rho * h1;
    out.first_moment += m.rho * h2;
    out.rotary_per_area += m.rho * h3;
    z0 = z1;
  }
  if (!shear_correction) out.As = transverseShearFromStacking(lam, materials).As;
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
