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
// TR-BDF2) did less work (all of it counted: evaluations, Jacobian columns,
// split renewals, factorisations and solves, by the operation counts of
// TrialCosts) and ended within kTrialAgree tolerance units of
// Dormand-Prince (whose error at its stability-bound steps is far below the
// tolerance). The work is counted, not timed, so the same scene decides the
// same way on an idle and a loaded machine.
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
  long implicit_attempts = 0, implicit_split_renewals = 0;  // steps tried (accepted and rejected), splits renewed
  double explicit_work = 0.0, implicit_work = 0.0;  // in evaluations of f (TrialCosts)
  double difference = 0.0;             // weighted RMS of the two end states' difference, tolerance units
  bool explicit_ok = false, implicit_ok = false;  // reached the window's end
  std::string describe() const;
};

// The operation counts (floating-point operations) the trial weighs its work
// by, from the model's sizes: an evaluation of f is dominated by the
// constrained solve over the nv velocity coordinates, (2/3) nv^3 + 2 nv^2;
// an attempted implicit step by its factorisation and solves (IMEX: the
// (nm + ne) stage system, (2/3) m^3 + 2 m^2 nm to form it, and six stages of
// 2 m^2 + 4 nv m; TR-BDF2: the n x n iteration matrix, (2/3) n^3 + 6 n^2 for
// its factorisation and three Newton solves); a renewal of the IMEX split by
// one factorisation of the constrained system and nm + ne solves with it,
// (2/3) nv^3 + 2 (nm + ne) nv^2. Each is an upper bound of the step's work
// (IMEX refactorises only when h changes, TR-BDF2 when it moves by 30 %),
// the same on every machine.
struct TrialCosts {
  double evaluation = 1.0, attempted_step = 0.0, split_renewal = 0.0;
};
// state_size n; split: the scene's modal split (no modes: TR-BDF2 is the candidate, nv = (n - 2) / 2).
TrialCosts trialCosts(int state_size, const StiffModalPart& split);

// Cost ratio the implicit method must beat (its work over Dormand-Prince's), and
// the agreement it must reach, in units of the error tolerance.
constexpr double kTrialCostRatio = 0.7;
constexpr double kTrialAgree = 10.0;

// The candidate implicit method, built on the evaluation-counting f it is
// given; it adds one to *split_renewals each time it renews its split.
using MethodFactory = std::function<std::unique_ptr<Integrator>(Rhs, long* split_renewals)>;

// rate_scale: per state component, the factor its difference and values are
// measured with (empty: all 1). For a modal rate it is 1 / omega_j: the end
// states are compared in each mode's amplitude sqrt(dq^2 + (dqdot/omega)^2),
// its energy norm, not in its rate, where a 14 kHz mode ringing at 1e-10 m
// (the release's transient, which the L-stable candidate damps at once and
// the physical damping within milliseconds) weighs 9e4 times its amplitude
// and 50-100 tolerance units (docs/mbs-run.md, "Projections and stiff modes").
SwitchTrial trialImplicit(const Rhs& f, const MethodFactory& candidate, const Tolerances& tol, double t,
                          const Eigen::VectorXd& y, double window, const TrialCosts& costs,
                          const Eigen::VectorXd& rate_scale = {});

}  // namespace fc::mbs
