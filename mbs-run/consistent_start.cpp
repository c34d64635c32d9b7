#include "mbs-run/consistent_start.h"

#include <algorithm>
#include <sstream>
#include <string>

#include "mbs-run/finite_guard.h"

namespace fc::mbs {

void requireSatisfiable(System& sys, double t, const Eigen::VectorXd& y, double atol) {
  const System::Violations v = sys.violations(t, y);
  const double limit = std::max(1e-6, 100.0 * atol);
  if (!(v.position > limit)) return;
  std::ostringstream s;
  s << "unsatisfiable constraints at t = " << t << ": after projection the joints still miss by " << v.position
    << " (m or rad, limit " << limit << "), largest at joint "
    << (v.worst_joint >= 0 ? sys.model().joints[v.worst_joint].name : std::string("?"))
    << "; the joints contradict each other (check their points and axes)";
  throw UnsatisfiableConstraints(s.str());
}

Eigen::VectorXd consistentStart(System& sys, double atol) {
  Eigen::VectorXd y = sys.initialState();
  if (const std::string cause = sys.nonFiniteCause(0.0, y); !cause.empty())
    throw NonFiniteState("non-finite state: " + cause + " is not finite at t = 0 s");
  sys.initializeJoints(y);
  sys.project(0.0, y);
  sys.initializeJoints(y);
  requireSatisfiable(sys, 0.0, y, atol);
  return y;
}

}  // namespace fc::mbs
