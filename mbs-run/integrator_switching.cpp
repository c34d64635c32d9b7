#include "mbs-run/integrator_switching.h"

#include <cstdio>

#include "mbs-run/run_summary.h"

namespace fc::mbs {

IntegratorSwitching::IntegratorSwitching(const Settings& settings, Rhs f, const Tolerances& tol)
    : settings_(settings), f_(std::move(f)), tol_(tol) {
  if (settings.integrator == IntegratorKind::TrBdf2) {
    implicit_ = makeTrBdf2(f_, tol_);
    current_ = implicit_.get();
  } else {
    explicit_ = makeDormandPrince(f_, tol_);
    current_ = explicit_.get();
  }
  label_ = current_->name();
}

void IntegratorSwitching::restartAfterEvent(double t, const Eigen::VectorXd& y, std::vector<std::string>& log) {
  if (settings_.switch_when_stiff && explicit_ && current_ != explicit_.get()) {
    current_ = explicit_.get();
    log.push_back(timeLabel(t) + " dopri5 (event)");
  }
  current_->reset(t, y);
}

bool IntegratorSwitching::switchIfStiff(double t, const Eigen::VectorXd& y, std::vector<std::string>& log) {
  if (!settings_.switch_when_stiff || current_ != explicit_.get()) return false;
  const double lambda = current_->stiffness();
  if (!(lambda > settings_.stiff_frequency)) return false;
  if (!implicit_) implicit_ = makeTrBdf2(f_, tol_);
  current_ = implicit_.get();
  current_->reset(t, y);
  char buf[96];
  std::snprintf(buf, sizeof buf, " trbdf2 (dopri5 held at its stability boundary by |lambda| ~ %.3g rad/s)", lambda);
  log.push_back(timeLabel(t) + buf);
  label_ = "dopri5+trbdf2";
  return true;
}

long IntegratorSwitching::steps() const {
  return (explicit_ ? explicit_->steps : 0) + (implicit_ ? implicit_->steps : 0);
}

long IntegratorSwitching::rejected() const {
  return (explicit_ ? explicit_->rejected : 0) + (implicit_ ? implicit_->rejected : 0);
}

}  // namespace fc::mbs
