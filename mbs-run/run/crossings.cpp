#include "mbs-run/run/crossings.h"

#include <algorithm>
#include <cmath>

namespace fc::mbs {

CrossingEvents::CrossingEvents(const Model& m) {
  for (const Event& e : m.events)
    if (e.joint >= 0) events_.push_back(&e);
  fired_.assign(events_.size(), 0);
}

CrossingEvents::Hit CrossingEvents::locate(const System& sys, const Integrator& integ, double t0,
                                           const Eigen::VectorXd& y0) {
  Hit hit;
  std::size_t hit_index = 0;
  const double t1 = integ.t();
  const Eigen::VectorXd& y1 = integ.y();
  for (std::size_t k = 0; k < events_.size(); ++k) {
    if (fired_[k]) continue;
    const Event& ev = *events_[k];
    const double g0 = sys.jointAngle(ev.joint, y0) - ev.angle;
    const double g1 = sys.jointAngle(ev.joint, y1) - ev.angle;
    const bool cross = (g0 < 0 && g1 >= 0 && ev.direction >= 0) || (g0 > 0 && g1 <= 0 && ev.direction <= 0);
    if (!cross) continue;
    double a = t0, b = t1;
    for (int it = 0; it < 200 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++it) {
      const double mid = 0.5 * (a + b);
      const double gm = sys.jointAngle(ev.joint, integ.interpolate(mid)) - ev.angle;
      if ((gm < 0) == (g0 < 0) && gm != 0.0) a = mid; else b = mid;
    }
    if (!hit.event || b < hit.time) {
      hit.event = &ev;
      hit.time = b;
      hit_index = k;
    }
  }
  // Only the crossing that fires is disarmed: a later one in the same step
  // is found again on the step that follows the event.
  if (hit.event) fired_[hit_index] = 1;
  return hit;
}

void CrossingEvents::rearm(const Event* e) {
  for (std::size_t k = 0; k < events_.size(); ++k)
    if (events_[k] == e) fired_[k] = 0;
}

}  // namespace fc::mbs
