#include "section-prep/stress_recovery.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fc::section {

namespace {
constexpr int kPair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
}

Vector6d voigtToAxes(const Vector6d& v, const Eigen::Matrix3d& R, bool engineering) {
  Eigen::Matrix3d t;
  for (int I = 0; I < 6; ++I) {
    const double x = (I >= 3 && engineering) ? 0.5 * v(I) : v(I);
    t(kPair[I][0], kPair[I][1]) = t(kPair[I][1], kPair[I][0]) = x;
  }
  const Eigen::Matrix3d r = R.transpose() * t * R;
  Vector6d out;
  for (int I = 0; I < 6; ++I) {
    const double x = r(kPair[I][0], kPair[I][1]);
    out(I) = (I >= 3 && engineering) ? 2 * x : x;
  }
  return out;
}

Eigen::Vector3d plyComponents(const Vector6d& v) { return {v(0), v(1), v(5)}; }

namespace {
struct Coefficients {
  double F1, F2, F11, F22, F66, F12;
};
Coefficients coefficients(const PlyStrength& st) {
  Coefficients c{};
  c.F1 = 1 / st.Xt - 1 / st.Xc;
  c.F2 = 1 / st.Yt - 1 / st.Yc;
  c.F11 = 1 / (st.Xt * st.Xc);
  c.F22 = 1 / (st.Yt * st.Yc);
  c.F66 = 1 / (st.S12 * st.S12);
  c.F12 = -0.5 * std::sqrt(c.F11 * c.F22);
  return c;
}
}  // namespace

double tsaiWuIndex(const PlyStrength& st, const Eigen::Vector3d& s) {
  const Coefficients c = coefficients(st);
  return c.F1 * s(0) + c.F2 * s(1) + c.F11 * s(0) * s(0) + c.F22 * s(1) * s(1) +
         c.F66 * s(2) * s(2) + 2 * c.F12 * s(0) * s(1);
}

double maxStressIndex(const PlyStrength& st, const Eigen::Vector3d& s) {
  const double f1 = s(0) >= 0 ? s(0) / st.Xt : -s(0) / st.Xc;
  const double f2 = s(1) >= 0 ? s(1) / st.Yt : -s(1) / st.Yc;
  return std::max({f1, f2, std::abs(s(2)) / st.S12});
}

double tsaiWuStrengthRatio(const PlyStrength& st, const Eigen::Vector3d& s) {
  const Coefficients c = coefficients(st);
  const double b = c.F1 * s(0) + c.F2 * s(1);
  const double a = c.F11 * s(0) * s(0) + c.F22 * s(1) * s(1) + c.F66 * s(2) * s(2) +
                   2 * c.F12 * s(0) * s(1);
  // a >= 0 (the quadratic form is positive definite for |F12| < sqrt(F11 F22)).
  if (a <= 0) return b > 0 ? 1 / b : std::numeric_limits<double>::infinity();
  return (-b + std::sqrt(b * b + 4 * a)) / (2 * a);
}

std::vector<RecoveredElement> recoverStresses(const std::vector<ElementRecovery>& basis,
                                              const std::vector<int>& element_material,
                                              const std::vector<std::optional<PlyStrength>>& strengths,
                                              const Vector6d& F) {
  std::vector<RecoveredElement> out(basis.size());
  for (std::size_t e = 0; e < basis.size(); ++e) {
    RecoveredElement& r = out[e];
    r.stress = basis[e].stress * F;
    r.strain = basis[e].strain * F;
    const Vector6d material_stress = voigtToAxes(r.stress, basis[e].axes, false);
    r.ply_stress = plyComponents(material_stress);
    r.ply_strain = plyComponents(voigtToAxes(r.strain, basis[e].axes, true));
    const auto& st = strengths.at(static_cast<std::size_t>(element_material.at(e)));
    if (st) {
      r.has_strength = true;
      r.tsai_wu = tsaiWuIndex(*st, r.ply_stress);
      r.max_stress = maxStressIndex(*st, r.ply_stress);
      r.strength_ratio = tsaiWuStrengthRatio(*st, r.ply_stress);
      r.hashin = hashinIndices(*st, material_stress);
    }
  }
  return out;
}

}  // namespace fc::section
