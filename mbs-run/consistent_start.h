#pragma once
// The consistent start both formulations share (simulation.cpp and
// tree_simulation.cpp), and the check after every projection that the joints
// can hold at all.
#include <Eigen/Dense>

#include <stdexcept>

#include "mbs-run/system.h"

namespace fc::mbs {

// Joints that contradict each other: the run ends with this status.
class UnsatisfiableConstraints : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// After projecting at the start or after an event, constraints that cannot
// all hold (contradicting joints) leave a violation far above what the
// projection reaches otherwise (1e-12 of the scene's size): throws
// UnsatisfiableConstraints naming the worst joint rather than integrate a
// compromise.
void requireSatisfiable(System& sys, double t, const Eigen::VectorXd& y, double atol);

// The scene's initial state made consistent: its ingredients checked for
// non-finite numbers (NonFiniteState naming the first, before the projection
// spreads it over every coordinate), held poses captured, the state
// projected onto the constraints and the revolute angle offsets measured in
// the consistent configuration; then requireSatisfiable.
Eigen::VectorXd consistentStart(System& sys, double atol);

}  // namespace fc::mbs
