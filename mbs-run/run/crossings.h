#pragma once
// Joint-angle crossing events (contracts.md `events:` with a `joint`): the
// first time after the start at which a revolute angle passes a value, found
// as a sign change over an accepted step and located on the integrator's
// dense output by bisection to machine precision in time. Each fires once.
#include <Eigen/Dense>

#include <vector>

#include "mbs-run/integrators/integrator.h"
#include "mbs-run/model/model.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs {

class CrossingEvents {
 public:
  explicit CrossingEvents(const Model& m);
  struct Hit {
    const Event* event = nullptr;  // null: no crossing in the step
    double time = 0.0;
  };
  // The earliest armed crossing over the integrator's last step, from state
  // y0 at t0 to its current state; disarms the event found.
  Hit locate(const System& sys, const Integrator& integ, double t0, const Eigen::VectorXd& y0);
  // Arms a located crossing again (an earlier stop event cut the step short).
  void rearm(const Event* e);

 private:
  std::vector<const Event*> events_;
  std::vector<char> fired_;
};

}  // namespace fc::mbs
