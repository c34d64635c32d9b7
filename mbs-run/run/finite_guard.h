#pragma once
// Non-finite states: a NaN or inf in f(t, y) (a huge length in the scene,
// NaN/inf in a body file, a force blowing up) once made the integrators retry
// forever. The guard wraps the right-hand side: after a bounded number of
// consecutive non-finite evaluations (the integrator's retries with smaller
// steps) it throws NonFiniteState naming the body, force element or joint that
// went non-finite first. It also lets a termination signal stop a step that
// is still retrying.
#include <Eigen/Dense>

#include <functional>
#include <stdexcept>
#include <string>

#include "mbs-run/integrators/integrator.h"
#include "mbs-run/run/sampling.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs {

class FiniteGuard {
 public:
  // Consecutive non-finite evaluations tolerated: a few rejected steps of
  // Dormand-Prince (6 stages each) or Newton iterations of TR-BDF2.
  static constexpr int kMaxNonFinite = 30;
  // What went non-finite at (t, y): "body B's mass", ...; "" when it cannot say.
  using Cause = std::function<std::string(double, const Eigen::VectorXd&)>;
  // Guards f; cause names the culprit (System::nonFiniteCause for the
  // constrained formulation).
  FiniteGuard(Rhs f, Cause cause) : f_(std::move(f)), cause_(std::move(cause)) {}
  // f(t, y) checked.
  Rhs rhs();
  // From then on a recorded termination signal throws fc::Terminated from
  // inside the step (once the initial row is written, so a stopped run's file
  // always holds the initial state).
  void watchSignals() { watch_signals_ = true; }
  // Throws NonFiniteState when an output row holds a NaN or inf.
  static void checkSample(const Model& m, const Sample& s);

 private:
  void evaluate(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot);
  Rhs f_;
  Cause cause_;
  int consecutive_ = 0;
  bool watch_signals_ = false;
  std::string first_cause_;
};

}  // namespace fc::mbs
