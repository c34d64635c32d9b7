#pragma once
// Timed events (contracts.md `events:` with a `time`): applied in time order,
// the run stopping exactly at each; and the actions every event performs
// (lock, release, enable, disable), shared with the joint-angle crossings.
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "mbs-run/model/model.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs {

// Performs the event's actions on the system in configuration y.
void applyEvent(System& sys, const Event& ev, const Eigen::VectorXd& y);
// " lock R1 release R2 ..." for the event log.
std::string describeEvent(const Model& m, const Event& ev);

class TimedEvents {
 public:
  explicit TimedEvents(const Model& m);
  // True when an event is due at or before t.
  bool dueAt(double t) const { return next_ < events_.size() && events_[next_]->time <= t; }
  // The time the current step must not pass: the next event's, or t_end.
  double limit(double t_end) const { return next_ < events_.size() ? std::min(t_end, events_[next_]->time) : t_end; }
  // Applies the next event at t and returns it.
  const Event& applyNext(System& sys, const Eigen::VectorXd& y);

 private:
  std::vector<const Event*> events_;  // in time order
  std::size_t next_ = 0;
};

}  // namespace fc::mbs
