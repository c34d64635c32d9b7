#include "common/materials.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fc {

namespace {

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

void requirePositive(const std::string& name, const char* what, double v) {
  if (!(v > 0) || !std::isfinite(v))
    throw std::invalid_argument("material '" + name + "': " + what + " must be positive, got " +
                                num(v));
}

// Physical ranges (SI units). Moduli: soft gels ~1e3 Pa to diamond 1.2e12 Pa,
// with room up to 1e15 Pa for the "100x steel" surrogates used to model
// near-rigid parts. Densities: aerogels ~1 kg/m^3 to osmium 2.26e4 kg/m^3.
// Outside them a value is a unit mistake (GPa typed as Pa) or a typo, and the
// arithmetic of the section and element kernels (products of moduli and
// lengths^4) underflows to 0 or NaN.
constexpr double kModulusMin = 1e3, kModulusMax = 1e15;
constexpr double kDensityMin = 0.1, kDensityMax = 1e5;

void requireModulus(const std::string& name, const char* what, double v) {
  requirePositive(name, what, v);
  if (v < kModulusMin || v > kModulusMax)
    throw std::invalid_argument("material '" + name + "': " + what + " = " + num(v) +
                                " Pa is outside the physical range [" + num(kModulusMin) + ", " +
                                num(kModulusMax) + "] Pa (SI units: a modulus in GPa is e9 Pa)");
}

void requireDensity(const std::string& name, double v) {
  requirePositive(name, "rho", v);
  if (v < kDensityMin || v > kDensityMax)
    throw std::invalid_argument("material '" + name + "': rho = " + num(v) +
                                " kg/m^3 is outside the physical range [" + num(kDensityMin) +
                                ", " + num(kDensityMax) + "] kg/m^3");
}

// Positive-definite stiffness is the admissibility condition for any linear
// elastic material (strain energy > 0); the Poisson bounds follow from it.
void requirePositiveDefinite(const std::string& name, const Matrix6d& C) {
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(0.5 * (C + C.transpose()));
  if ((C - C.transpose()).norm() > 1e-9 * C.norm())
    throw std::invalid_argument("material '" + name + "': stiffness matrix is not symmetric");
  if (es.eigenvalues().minCoeff() <= 0) {
    std::ostringstream os;
    os << "material '" << name
       << "': stiffness is not positive definite (smallest eigenvalue "
       << es.eigenvalues().minCoeff()
       << "): the Poisson ratios are outside the admissible bounds for these moduli";
    throw std::invalid_argument(os.str());
  }
}

// Strengths: from soft foams (~1e5 Pa) to carbon fibre (~7e9 Pa, the
// strongest fibres), with room either side; the floor 1e4 Pa lies above every
// strength typed in MPa (at most a few thousand), the unit mistake that would
// make every failure index absurd.
constexpr double kStrengthMin = 1e4, kStrengthMax = 1e11;

}  // namespace

PlyStrength readStrength(const InputNode& s) {
  s.allowKeys({"Xt", "Xc", "Yt", "Yc", "S12"});
  PlyStrength out;
  const std::pair<const char*, double*> keys[] = {
      {"Xt", &out.Xt}, {"Xc", &out.Xc}, {"Yt", &out.Yt}, {"Yc", &out.Yc}, {"S12", &out.S12}};
  for (const auto& [key, value] : keys) {
    const InputNode v = s[key];  // missing: located error naming the key
    *value = v.asPositive();
    if (*value < kStrengthMin || *value > kStrengthMax)
      v.fail("strength " + std::string(key) + " = " + num(*value) + " Pa is outside the physical range [" +
             num(kStrengthMin) + ", " + num(kStrengthMax) +
             "] Pa (SI units: a strength in MPa is e6 Pa; compression strengths are positive magnitudes)");
  }
  return out;
}

Matrix6d orthotropicCompliance(double E1, double E2, double E3, double G12, double G13,
                               double G23, double nu12, double nu13, double nu23) {
  Matrix6d S = Matrix6d::Zero();
  S(0, 0) = 1 / E1;
  S(1, 1) = 1 / E2;
  S(2, 2) = 1 / E3;
  S(0, 1) = S(1, 0) = -nu12 / E1;
  S(0, 2) = S(2, 0) = -nu13 / E1;
  S(1, 2) = S(2, 1) = -nu23 / E2;
  S(3, 3) = 1 / G23;
  S(4, 4) = 1 / G13;
  S(5, 5) = 1 / G12;
  return S;
}

Material makeOrthotropic(const std::string& name, double E1, double E2, double E3, double G12,
                         double G13, double G23, double nu12, double nu13, double nu23,
                         double rho) {
  requireModulus(name, "E1", E1);
  requireModulus(name, "E2", E2);
  requireModulus(name, "E3", E3);
  requireModulus(name, "G12", G12);
  requireModulus(name, "G13", G13);
  requireModulus(name, "G23", G23);
  requireDensity(name, rho);
  for (double nu : {nu12, nu13, nu23})
    if (!std::isfinite(nu))
      throw std::invalid_argument("material '" + name + "': Poisson ratios must be finite numbers");
  // Bounds |nu_ij| < sqrt(E_i/E_j) (Lempriere 1968), checked first for a precise message.
  auto bound = [&](const char* which, double nu, double Ei, double Ej) {
    if (std::abs(nu) >= std::sqrt(Ei / Ej))
      throw std::invalid_argument("material '" + name + "': |" + which + "| = " +
                                  std::to_string(std::abs(nu)) + " must be below sqrt(" +
                                  std::to_string(Ei) + "/" + std::to_string(Ej) + ")");
  };
  bound("nu12", nu12, E1, E2);
  bound("nu13", nu13, E1, E3);
  bound("nu23", nu23, E2, E3);
  const Matrix6d S = orthotropicCompliance(E1, E2, E3, G12, G13, G23, nu12, nu13, nu23);
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(S);
  if (es.eigenvalues().minCoeff() <= 0)
    throw std::invalid_argument(
        "material '" + name +
        "': compliance is not positive definite (1 - nu12 nu21 - nu23 nu32 - nu13 nu31 - 2 nu21 "
        "nu32 nu13 <= 0): inadmissible Poisson ratios");
  Material m;
  m.name = name;
  m.kind = Material::Kind::Orthotropic;
  m.rho = rho;
  m.C = S.inverse();
  m.C = 0.5 * (m.C + m.C.transpose());
  m.E1 = E1, m.E2 = E2, m.E3 = E3, m.G12 = G12, m.G13 = G13, m.G23 = G23;
  m.nu12 = nu12, m.nu13 = nu13, m.nu23 = nu23;
  return m;
}

Material makeIsotropic(const std::string& name, double E, double nu, double rho) {
  requireModulus(name, "E", E);
  if (!(nu > -1.0 && nu < 0.5))
    throw std::invalid_argument("material '" + name + "': Poisson ratio nu = " +
                                std::to_string(nu) + " must lie in (-1, 0.5)");
  const double G = E / (2 * (1 + nu));
  Material m = makeOrthotropic(name, E, E, E, G, G, G, nu, nu, nu, rho);
  m.kind = Material::Kind::Isotropic;
  return m;
}

Material makeAnisotropic(const std::string& name, const Matrix6d& C, double rho) {
  requireDensity(name, rho);
  if (!C.allFinite())
    throw std::invalid_argument("material '" + name + "': C holds a non-finite number");
  requirePositiveDefinite(name, C);
  // Eigenvalues of C are moduli (Kelvin's eigenstiffnesses): same physical range.
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(0.5 * (C + C.transpose()));
  if (es.eigenvalues().minCoeff() < kModulusMin || es.eigenvalues().maxCoeff() > 3 * kModulusMax)
    throw std::invalid_argument("material '" + name + "': the eigenvalues of C, " +
                                num(es.eigenvalues().minCoeff()) + " to " +
                                num(es.eigenvalues().maxCoeff()) +
                                " Pa, leave the physical range of moduli [" + num(kModulusMin) +
                                ", " + num(3 * kModulusMax) + "] Pa (SI units expected)");
  Material m;
  m.name = name;
  m.kind = Material::Kind::Anisotropic;
  m.rho = rho;
  m.C = 0.5 * (C + C.transpose());
  const double nan = std::nan("");
  m.E1 = m.E2 = m.E3 = m.G12 = m.G13 = m.G23 = m.nu12 = m.nu13 = m.nu23 = nan;
  return m;
}

MaterialLibrary readMaterials(const InputNode& block) {
  MaterialLibrary lib;
  for (const auto& [name, node] : namedEntries(block)) {
    const std::string type = node["type"].asString();
    try {
      if (type == "isotropic") {
        node.allowKeys({"type", "E", "nu", "rho", "strength"});
        lib[name] = makeIsotropic(name, node["E"].asPositive(), node["nu"].asDouble(),
                                  node["rho"].asPositive());
      } else if (type == "orthotropic") {
        node.allowKeys({"type", "E1", "E2", "E3", "G12", "G13", "G23", "nu12", "nu13", "nu23",
                        "rho", "strength"});
        lib[name] = makeOrthotropic(
            name, node["E1"].asPositive(), node["E2"].asPositive(), node["E3"].asPositive(),
            node["G12"].asPositive(), node["G13"].asPositive(), node["G23"].asPositive(),
            node["nu12"].asDouble(), node["nu13"].asDouble(), node["nu23"].asDouble(),
            node["rho"].asPositive());
      } else if (type == "honeycomb") {
        // A sandwich core: through-thickness modulus E3 and transverse shear moduli
        // G13 (ribbon, L) and G23 (W) govern; the in-plane moduli of a honeycomb
        // are three orders below its shear moduli (Gibson & Ashby, Cellular
        // Solids, 2nd ed., ch. 4) and default to 1e-3 min(G13, G23); Poisson
        // ratios default to 0 (the cells' walls do not couple the directions).
        node.allowKeys({"type", "E3", "G13", "G23", "rho", "E1", "E2", "G12", "nu12", "nu13", "nu23"});
        const double G13 = node["G13"].asPositive(), G23 = node["G23"].asPositive();
        const double soft = 1e-3 * std::min(G13, G23);
        lib[name] = makeOrthotropic(name, node.has("E1") ? node["E1"].asPositive() : soft,
                                    node.has("E2") ? node["E2"].asPositive() : soft, node["E3"].asPositive(),
                                    node.has("G12") ? node["G12"].asPositive() : soft, G13, G23,
                                    node.number("nu12", 0.0), node.number("nu13", 0.0),
                                    node.number("nu23", 0.0), node["rho"].asPositive());
      } else if (type == "anisotropic") {
        node.allowKeys({"type", "C", "rho", "strength"});
        lib[name] = makeAnisotropic(name, node["C"].asMatrix(6, 6), node["rho"].asPositive());
      } else {
        node["type"].fail("unknown material type '" + type +
                          "'; expected isotropic, orthotropic, honeycomb or anisotropic");
      }
    } catch (const std::invalid_argument& e) {
      node.fail(e.what());
    }
    if (node.has("strength")) lib[name].strength = readStrength(node["strength"]);
  }
  return lib;
}

const Material& lookupMaterial(const MaterialLibrary& lib, const InputNode& node) {
  const std::string name = node.asString();
  auto it = lib.find(name);
  if (it != lib.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& kv : lib) names.push_back(kv.first);
  std::string msg = "unknown material '" + name + "'" + didYouMean(name, names);
  msg += names.empty() ? "; no materials are defined" : "; defined materials: ";
  for (std::size_t i = 0; i < names.size(); ++i) msg += (i ? ", " : "") + names[i];
  node.fail(msg);
}

Matrix6d rotateStiffness(const Matrix6d& C, const Eigen::Matrix3d& R) {
  // Stress transformation for Voigt order [11,22,33,23,13,12]: sigma' = T sigma,
  // and with engineering shear strains eps = T^T eps', so C' = T C T^T.
  static const int pi[6] = {0, 1, 2, 1, 0, 0};
  static const int pj[6] = {0, 1, 2, 2, 2, 1};
  Matrix6d T;
  for (int I = 0; I < 6; ++I) {
    const int i = pi[I], j = pj[I];
    for (int J = 0; J < 6; ++J) {
      const int k = pi[J], l = pj[J];
      if (J < 3)
        T(I, J) = R(i, k) * R(j, l);
      else
        T(I, J) = R(i, k) * R(j, l) + R(i, l) * R(j, k);
    }
  }
  return T * C * T.transpose();
}

Matrix6d plyStiffnessInLaminateAxes(const Matrix6d& C, double angle_rad) {
  // Material components map to laminate components through Rz(angle).
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  Eigen::Matrix3d R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return rotateStiffness(C, R);
}

}  // namespace fc
