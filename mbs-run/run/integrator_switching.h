#pragma once
// Which integrator runs each segment. A named method (dopri5, trbdf2, imex)
// runs throughout. With `integrator: auto` a segment between events starts
// with Dormand-Prince; when a stiff eigenvalue (a fast mode the joints do not
// clamp, such as the SAR crank's 1 kHz modes once R1 is released) holds the
// explicit steps at the stability boundary, a trial decides whether the
// implicit candidate (IMEX for a scene with modes, else TR-BDF2) takes over;
// an event changes the dynamics, so the next segment starts explicit again.
#include <Eigen/Dense>

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mbs-run/integrators/integrator.h"
#include "mbs-run/run/run_policy.h"

namespace fc::mbs {

class IntegratorSwitching {
 public:
  // stiff: the modal stiffness part for the IMEX method (System::modalSplit);
  // size: the length of the state (RunPolicy::tolerances).
  IntegratorSwitching(const RunPolicy& policy, Rhs f, StiffPart stiff, int size);
  Integrator& current() { return *current_; }
  // The method's name, "dopri5+imex" (or "+trbdf2") once auto has switched.
  const std::string& label() const { return label_; }
  // After an event at (t, y): auto goes back to the explicit method, a named
  // method restarts (its history is invalid).
  void restartAfterEvent(double t, const Eigen::VectorXd& y, std::vector<std::string>& log);
  // After an accepted step: when auto's Dormand-Prince is held at its
  // stability boundary above the stiff frequency, a trial of both methods
  // (switch_trial.h) decides; it moves to the implicit candidate only if that
  // is cheaper and as accurate, and otherwise keeps dopri5 for twice as long
  // as before the last trial (from one window on) before trying again. True if it switched.
  bool switchIfStiff(double t, const Eigen::VectorXd& y, std::vector<std::string>& log);
  long steps() const;
  long rejected() const;

 private:
  RunPolicy policy_;
  Rhs f_;
  StiffPart stiff_;
  Tolerances tol_;
  std::unique_ptr<Integrator> explicit_, implicit_;
  Integrator* current_ = nullptr;
  std::string label_;
  int declines_ = 0;  // trials that kept dopri5 in this segment
  double retry_at_ = -std::numeric_limits<double>::infinity();  // no trial before
};

// Length of auto's switch trial in Dormand-Prince steps (switch_trial.h).
constexpr double kTrialSteps = 300.0;

}  // namespace fc::mbs
