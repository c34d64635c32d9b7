#include "mbs-run/run/events.h"

#include <algorithm>
#include <sstream>

namespace fc::mbs {

void applyEvent(System& sys, const Event& ev, const Eigen::VectorXd& y) {
  for (int j : ev.enable_joints) sys.setJointEnabled(j, true, y);
  for (int j : ev.disable_joints) sys.setJointEnabled(j, false, y);
  for (int j : ev.lock) sys.setJointLocked(j, true, y);
  for (int j : ev.release) sys.setJointLocked(j, false, y);
  for (int f : ev.enable_forces) sys.setForceEnabled(f, true);
  for (int f : ev.disable_forces) sys.setForceEnabled(f, false);
}

std::string describeEvent(const Model& m, const Event& ev) {
  std::ostringstream s;
  auto names = [&](const char* what, const std::vector<int>& idx, bool joints) {
    if (idx.empty()) return;
    s << " " << what;
    for (int i : idx) s << " " << (joints ? m.joints[i].name : m.forces[i].name);
  };
  names("lock", ev.lock, true);
  names("release", ev.release, true);
  names("enable", ev.enable_joints, true);
  names("enable", ev.enable_forces, false);
  names("disable", ev.disable_joints, true);
  names("disable", ev.disable_forces, false);
  return s.str();
}

TimedEvents::TimedEvents(const Model& m) {
  for (const Event& e : m.events)
    if (e.joint < 0) events_.push_back(&e);
  std::stable_sort(events_.begin(), events_.end(), [](const Event* a, const Event* b) { return a->time < b->time; });
}

const Event& TimedEvents::applyNext(System& sys, const Eigen::VectorXd& y) {
  const Event& ev = *events_[next_++];
  applyEvent(sys, ev, y);
  return ev;
}

}  // namespace fc::mbs
