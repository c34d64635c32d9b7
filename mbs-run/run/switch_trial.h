#pragma once
// `integrator: auto`'s measured choice. When Dormand-Prince is held
// at its stability boundary, TR-BDF2 may or may not do better: it is cheaper
// only if its accuracy-bound steps are longer than the explicit stability-
// bound ones, and it is wrong where its numerical damping changes the physics
// (a clamped-root body on a hinge: the frame rotation and the modes span a
// stiff, gyroscopically stabilised motion that damping destabilises; the
// 16-mode pendulum ended 5.6e6 m off). So before switching, both
// methods integrate the same window from the same state, and the switch is
// made only if the implicit method (IMEX for scenes with modes, else
// TR-BDF2) took less CPU time (all its work included: Jacobian, modal
// responses, factorisations) and ended within kTrialAgree tolerance units of
// Dormand-Prince (whose error at its stability-bound steps is far below the
// tolerance).
#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <string>

#include "mbs-run/integrators/integrator.h"

namespace fc::mbs {

struct SwitchTrial {
  bool implicit_better = false;
  double window = 0.0;                 // [s]
  std::string candidate;               // the implicit method's name
  long explicit_evaluations = 0, implicit_evaluations = 0;
  double explicit_cpu = 0.0, implicit_cpu = 0.0;  // [s], process CPU time of each trial
  double difference = 0.0;             // weighted RMS of the two end states' difference, tolerance units
  bool explicit_ok = false, implicit_ok = false;  // reached the window's end
  std::string describe() const;
};

// Cost ratio the implicit method must beat (its CPU time over Dormand-Prince's), and
// the agreement it must reach, in units of the error tolerance.
constexpr double kTrialCostRatio = 0.7;
constexpr double kTrialAgree = 10.0;

// The candidate implicit method, built on the evaluation-counting f it is given.
using MethodFactory = std::function<std::unique_ptr<Integrator>(Rhs)>;

// rate_scale: per state component, the factor its difference and values are
// measured with (empty: all 1). For a modal rate it is 1 / omega_j: the end
// states are compared in each mode's amplitude sqrt(dq^2 + (dqdot/omega)^2),
// its energy norm, not in its rate, where a 14 kHz mode ringing at 1e-10 m
// (the release's transient, which the L-stable candidate damps at once and
// the physical damping within milliseconds) weighs 9e4 times its amplitude
// and 50-100 tolerance units (docs/mbs-run.md, "Projections and stiff modes").
SwitchTrial trialImplicit(const Rhs& f, const MethodFactory& candidate, const Tolerances& tol, double t,
                          const Eigen::VectorXd& y, double window, const Eigen::VectorXd& rate_scale = {});

}  // namespace fc::mbs
