#include "mbs-run/run/integrator_switching.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "mbs-run/run/run_summary.h"
#include "mbs-run/run/switch_trial.h"

namespace fc::mbs {

IntegratorSwitching::IntegratorSwitching(const RunPolicy& policy, Rhs f, StiffPart stiff, int size)
    : policy_(policy), f_(std::move(f)), stiff_(std::move(stiff)), tol_(policy.tolerances(size)) {
  if (policy.integrator == IntegratorKind::TrBdf2) {
    implicit_ = makeTrBdf2(f_, tol_);
    current_ = implicit_.get();
  } else if (policy.integrator == IntegratorKind::Imex) {
    implicit_ = makeImex(f_, stiff_, tol_);
    current_ = implicit_.get();
  } else {
    explicit_ = makeDormandPrince(f_, tol_);
    current_ = explicit_.get();
  }
  label_ = current_->name();
}

void IntegratorSwitching::restartAfterEvent(double t, const Eigen::VectorXd& y, std::vector<std::string>& log) {
  declines_ = 0;  // new dynamics: a new trial may switch at once
  retry_at_ = -std::numeric_limits<double>::infinity();
  if (policy_.switch_when_stiff && explicit_ && current_ != explicit_.get()) {
    current_ = explicit_.get();
    log.push_back(timeLabel(t) + " dopri5 (event)");
  }
  current_->reset(t, y);
}

bool IntegratorSwitching::switchIfStiff(double t, const Eigen::VectorXd& y, std::vector<std::string>& log) {
  if (!policy_.switch_when_stiff || current_ != explicit_.get()) return false;
  const double lambda = current_->stiffness();
  if (t < retry_at_ || !(lambda > policy_.stiff_frequency)) return false;
  // Measured choice (switch_trial.h): both methods over the next
  // kTrialSteps explicit steps; stay explicit for the rest of the segment
  // unless the implicit candidate is cheaper and as accurate.
  const double h = current_->t() - current_->tPrevious();
  // The candidate: IMEX where there are modes (their stiffness is what it
  // treats implicitly, with a structured solve), else TR-BDF2.
  const StiffModalPart split = stiff_ ? stiff_(t, y) : StiffModalPart{};
  const bool has_modes = split.modes() > 0;
  // Modal rates compared as the amplitudes they carry (trialImplicit).
  Eigen::VectorXd rate_scale = Eigen::VectorXd::Ones(y.size());
  for (int j = 0; j < split.modes(); ++j)
    rate_scale[split.v_index[j]] = 1.0 / std::max(1.0, std::sqrt(std::max(split.stiffness[j], 0.0)));
  const StiffPart stiff = stiff_;
  const MethodFactory candidate = [&](Rhs counted, long* renewals) {
    const StiffPart counted_stiff = [stiff, renewals](double ts, const Eigen::VectorXd& ys) {
      ++*renewals;
      return stiff(ts, ys);
    };
    return has_modes ? makeImex(counted, counted_stiff, tol_) : makeTrBdf2(counted, tol_);
  };
  const SwitchTrial trial =
      trialImplicit(f_, candidate, tol_, t, y, kTrialSteps * h, trialCosts(int(y.size()), split), rate_scale);
  if (!trial.implicit_better) {
    // Tried again after 2^k windows (k the declines so far in the segment):
    // a disagreement often comes from a transient (high modes ringing after
    // a release or an impact, which the L-stable candidate damps at once and
    // the physical damping within tens of milliseconds), not from the
    // dynamics; the doubling keeps the trials' cost within log2 of the run's
    // windows.
    retry_at_ = t + kTrialSteps * h * std::ldexp(1.0, ++declines_);
    log.push_back(timeLabel(t) + " dopri5 kept: " + trial.describe());
    return false;
  }
  if (!implicit_) implicit_ = has_modes ? makeImex(f_, stiff_, tol_) : makeTrBdf2(f_, tol_);
  current_ = implicit_.get();
  current_->reset(t, y);
  char buf[96];
  std::snprintf(buf, sizeof buf, " (dopri5 held at its stability boundary by |lambda| ~ %.3g rad/s; ", lambda);
  log.push_back(timeLabel(t) + " " + current_->name() + buf + trial.describe() + ")");
  label_ = "dopri5+" + current_->name();
  return true;
}

long IntegratorSwitching::steps() const {
  return (explicit_ ? explicit_->steps : 0) + (implicit_ ? implicit_->steps : 0);
}

long IntegratorSwitching::rejected() const {
  return (explicit_ ? explicit_->rejected : 0) + (implicit_ ? implicit_->rejected : 0);
}

}  // namespace fc::mbs
