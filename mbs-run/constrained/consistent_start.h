#pragma once
// The consistent start both formulations share (run/constrained_dynamics.cpp
// and run/tree_dynamics.cpp), and the check after every projection that the joints
// can hold at all.
#include <Eigen/Dense>

#include <stdexcept>

#include "mbs-run/constrained/system.h"

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

// The largest deformation the consistent start puts into a flexible body to
// close its joints, as a share of the body's size at an interface (and in
// rad): beyond it the scene is refused as not placed assembled (linear modes
// describe deflections of a few percent of a body's size).
constexpr double kAssemblyDeflection = 0.1;

// The scene's initial state made consistent: its ingredients checked for
// non-finite numbers (NonFiniteState naming the first, before the projection
// spreads it over every coordinate), held poses captured, the state
// assembled (System::assemble: the frames first, the modes as given unless
// the joints need a deformation) and the revolute angle offsets measured in
// the consistent configuration. A start that cannot be assembled throws
// UnsatisfiableConstraints saying why in the scene's terms: a body its
// joints would deform beyond kAssemblyDeflection (which body, which joint's
// points how far apart as placed), an assembly that ran out of passes while
// still closing the gap, else requireSatisfiable's contradicting joints.
Eigen::VectorXd consistentStart(System& sys, double atol);

}  // namespace fc::mbs
