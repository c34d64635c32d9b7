#include "mbs-run/run/run_policy.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fc::mbs {

Tolerances RunPolicy::tolerances(int size) const {
  Tolerances tol;
  tol.rtol = rtol;
  tol.atol = atol;
  tol.max_step = max_step;
  tol.mask = Eigen::VectorXd::Ones(size);
  tol.mask.tail(2).setZero();
  return tol;
}

RunPolicy runPolicy(const Model& model) {
  const Settings& st = model.settings;
  RunPolicy p;
  // `auto` is decided here, once: chooseIntegrator's method, switching to an
  // implicit one when stiff only when that is Dormand-Prince; a named method
  // runs throughout.
  p.integrator = st.integrator == IntegratorKind::Auto ? chooseIntegrator(model) : st.integrator;
  p.switch_when_stiff = st.integrator == IntegratorKind::Auto && p.integrator == IntegratorKind::DormandPrince;
  p.rtol = st.rtol;
  p.atol = absoluteTolerance(st);
  p.max_step = st.max_step > 0 ? st.max_step : 10.0 * st.output_step;
  return p;
}

double absoluteTolerance(const Settings& st) { return st.atol > 0 ? st.atol : 1e-3 * st.rtol; }

IntegratorKind chooseIntegrator(const Model& m) {
  // Highest natural frequency a force element can introduce (spring stiffness
  // over the lightest attached mass or inertia). Dormand-Prince's stability
  // boundary is |h lambda| ~ 3.3: above ~2000 rad/s the explicit step would be
  // set by stability (< 1.6 ms) rather than accuracy, where TR-BDF2 wins.
  double wmax = 0.0;
  auto lightest = [&](int i, int j, bool rotary) {
    double v = std::numeric_limits<double>::infinity();
    for (int k : {i, j}) {
      const Body& b = m.bodies[k];
      if (b.fixed) continue;
      v = std::min(v, rotary ? b.inertia_com.diagonal().maxCoeff() : b.mass);
    }
    return v;
  };
  for (const ForceElement& f : m.forces) {
    if (f.type == ForceType::TranslationalSpringDamper) {
      wmax = std::max(wmax, std::sqrt(f.stiffness / lightest(f.body_i, f.body_j, false)));
    } else if (f.type == ForceType::RotationalSpringDamper) {
      double slope = 0.0;
      for (std::size_t k = 1; k < f.torque.x.size(); ++k)
        slope = std::max(slope, std::abs((f.torque.y[k] - f.torque.y[k - 1]) / (f.torque.x[k] - f.torque.x[k - 1])));
      const Joint& jt = m.joints[f.joint];
      wmax = std::max(wmax, std::sqrt(slope / lightest(jt.body_i, jt.body_j, true)));
    }
  }
  // Modal frequencies are deliberately not counted: joints often clamp the
  // stiffest modes (the SAR crank's 1 kHz modes with R1 locked), so which
  // modes are stiff is known only from the constrained motion; the run
  // measures it (RunPolicy::switch_when_stiff, integrator_switching.cpp).
  return wmax > 2000.0 ? IntegratorKind::TrBdf2 : IntegratorKind::DormandPrince;
}

namespace {
struct NamedIntegrator {
  const char* name;
  IntegratorKind kind;
};
constexpr NamedIntegrator kIntegrators[] = {
    {"auto", IntegratorKind::Auto},
    {"dopri5", IntegratorKind::DormandPrince},
    {"trbdf2", IntegratorKind::TrBdf2},
    {"imex", IntegratorKind::Imex},
};
}  // namespace

std::optional<IntegratorKind> integratorNamed(const std::string& name) {
  for (const NamedIntegrator& n : kIntegrators)
    if (name == n.name) return n.kind;
  return std::nullopt;
}

const std::vector<std::string>& integratorNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const NamedIntegrator& n : kIntegrators) v.push_back(n.name);
    return v;
  }();
  return names;
}

}  // namespace fc::mbs
