#include "mbs-run/run_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mbs-run/run_summary.h"

namespace fc::mbs {

QualityLimits qualityLimits(const RunSummary& r, double rtol, double atol) {
  QualityLimits q;
  // Floors: 10 steps (a short run's few steps still carry an error), and the
  // rounding of the energy terms themselves (1e-13 of their size). Cap: a
  // tenth of the scale, which a blow-up would otherwise raise with itself.
  // Plus 1e-12 J absolute: the energies of bodies at rest are rounding
  // (4e-14 J with an equal "error" on the static scenes of test_reactions).
  q.energy = std::clamp(double(std::max(r.steps, 10L)) * rtol, 1e-13, kMaxRelativeEnergyError) * r.energy_scale +
             kEnergyFloor;
  q.violation = 10.0 * (atol + rtol * r.length_scale);
  return q;
}

std::string qualityStatus(const RunSummary& r, double rtol, double atol) {
  const QualityLimits q = qualityLimits(r, rtol, atol);
  std::string s;
  char buf[320];
  if (!(r.energy_balance_error <= q.energy)) {
    std::snprintf(buf, sizeof buf,
                  "energy balance error %.3g J exceeds %.3g J (min(%ld steps x rtol %.3g, %g) x largest energy term %.3g J)",
                  r.energy_balance_error, q.energy, std::max(r.steps, 10L), rtol, kMaxRelativeEnergyError, r.energy_scale);
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
