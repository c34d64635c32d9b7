#include "mbs-run/run/run_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "mbs-run/run/run_summary.h"

namespace fc::mbs {

QualityLimits qualityLimits(const RunSummary& r, double rtol, double atol) {
  QualityLimits q;
  // Per accepted step the error control keeps each component's local error
  // within rtol |y_i| + atol, which changes E = T + V + D - W by at most
  // rtol sum |g_i y_i| + atol sum |g_i| (g = dE/dy: mechanics/energy_sensitivity.h),
  // the local errors adding up over the steps. The relative part is taken as
  // rtol x the largest energy term (sum |g_i y_i| is that term's size with
  // absolute values and lever arms: 6x it on the 16-mode beam pendulum,
  // which would loosen the check where it must catch wrong runs); the
  // absolute part atol sum |g_i| is what a system whose energy terms are
  // still small against their slope needs (a 1 000-rod chain just
  // released). Floors: 10 steps (a short run's few steps still carry an
  // error) and the rounding of the energy terms themselves (1e-13 of their
  // size); plus 1e-12 J absolute: the energies of bodies at rest are
  // rounding (4e-14 J with an equal "error" on the static scenes of
  // test_reactions). Cap: a tenth of the largest energy term, which a
  // blow-up would otherwise raise with itself.
  const double steps = double(std::max(r.steps, 10L));
  const double bound = steps * (rtol * r.energy_scale + atol * r.energy_sensitivity.absolute);
  q.energy = std::min(std::max(bound, 1e-13 * r.energy_scale), kMaxRelativeEnergyError * r.energy_scale) +
             kEnergyFloor;
  q.violation = 10.0 * (atol + rtol * r.length_scale);
  return q;
}

std::string qualityStatus(const RunSummary& r, double rtol, double atol) {
  const QualityLimits q = qualityLimits(r, rtol, atol);
  std::string s;
  char buf[480];
  if (!(r.energy_balance_error <= q.energy)) {
    std::snprintf(buf, sizeof buf,
                  "energy balance error %.3g J exceeds %.3g J (%ld steps x (rtol %.3g x largest energy term %.3g J + "
                  "atol %.3g x %.3g J per unit of state error); at most %g of the largest term)",
                  r.energy_balance_error, q.energy, std::max(r.steps, 10L), rtol, r.energy_scale, atol,
                  r.energy_sensitivity.absolute, kMaxRelativeEnergyError);
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

std::string stepFailure(double t, const std::string& integrator, double rtol, double atol) {
  std::ostringstream s;
  // The usual cause at tight tolerances: the error test (or TR-BDF2's Newton
  // iteration) asks for more digits than f(y) carries (the multiplier
  // iteration stops at a 1e-10 residual), so say what to change.
  s << "solver failure: step size too small at t = " << t << " (" << integrator << ", rtol " << rtol << ", atol "
    << atol << "): the error test cannot be met; at tight tolerances the right-hand side's"
    << " precision is the limit - loosen rtol" << (integrator == "dopri5" ? "" : " or use dopri5");
  return s.str();
}

std::string StallMonitor::check(double t, const std::string& integrator) {
  if (++steps_ % kWindow != 0) return "";
  const double mean_step = (t - t_window_) / kWindow;
  t_window_ = t;
  const double remaining = mean_step > 0.0 ? (t_end_ - t) / mean_step : std::numeric_limits<double>::infinity();
  if (!(remaining > kMaxRemainingSteps)) return "";
  std::ostringstream s;
  s << "solver failure: no progress at t = " << t << " s: the last " << kWindow << " steps (" << integrator
    << ") averaged " << mean_step << " s, so the " << (t_end_ - t) << " s left would take " << remaining
    << " more; the model has a time scale near " << mean_step
    << " s (a very stiff spring or damper on a light body, or a nearly singular mass matrix: a body whose"
    << " interface modes or static shapes hold a stiff local motion); check those, or try integrator: imex"
    << " or trbdf2";
  return s.str();
}

}  // namespace fc::mbs
