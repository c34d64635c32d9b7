#include "mbs-run/run_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mbs-run/simulation.h"

namespace fc::mbs {

QualityLimits qualityLimits(const Results& r, double rtol, double atol) {
  QualityLimits q;
  // Floors: 10 steps (a short run's few steps still carry an error), and the
  // rounding of the energy terms themselves (1e-13 of their size).
  q.energy = std::max(double(std::max(r.steps, 10L)) * rtol, 1e-13) * r.energy_scale;
  double L = 1.0;
  for (const auto& body : r.position)
    for (const auto& x : body) L = std::max(L, x.norm());
  q.violation = 10.0 * (atol + rtol * L);
  return q;
}

std::string qualityStatus(const Results& r, double rtol, double atol) {
  const QualityLimits q = qualityLimits(r, rtol, atol);
  std::string s;
  char buf[320];
  if (!(r.energy_balance_error <= q.energy)) {
    std::snprintf(buf, sizeof buf,
                  "energy balance error %.3g J exceeds %.3g J (%ld steps x rtol %.3g x largest energy term %.3g J)",
                  r.energy_balance_error, q.energy, std::max(r.steps, 10L), rtol, r.energy_scale);
    s += buf;
  }
  if (!(r.max_violation <= q.violation)) {
    std::snprintf(buf, sizeof buf, "%sconstraint violation %.3g exceeds %.3g (10 x (atol + rtol x largest position))",
                  s.empty() ? "" : "; ", r.max_violation, q.violation);
    s += buf;
  }
  if (s.empty()) return "completed";
  return "inaccurate: " + s + "; the answer is not within the tolerances asked (tighten rtol, or use dopri5)";
}

}  // namespace fc::mbs
