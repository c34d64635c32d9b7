#include "mbs-run/run/finite_guard.h"

#include <cstdio>

#include "common/termination.h"

namespace fc::mbs {

namespace {
std::string at(double t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, " at t = %.10g s", t);
  return buf;
}
}  // namespace

Rhs FiniteGuard::rhs() {
  return [this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) { evaluate(t, y, ydot); };
}

void FiniteGuard::evaluate(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  if (watch_signals_) fc::throwIfTerminated();
  try {
    f_(t, y, ydot);
  } catch (const std::runtime_error&) {
    // A factorisation that fails on a non-finite matrix: say what is non-finite.
    const std::string cause = cause_(t, y);
    if (!cause.empty()) throw NonFiniteState("non-finite state: " + cause + " is not finite" + at(t));
    throw;
  }
  if (ydot.allFinite()) {
    consecutive_ = 0;
    return;
  }
  if (consecutive_++ == 0) {
    const std::string cause = cause_(t, y);
    first_cause_ = (cause.empty() ? std::string("the constraint solve") : cause) + at(t);
  }
  if (consecutive_ >= kMaxNonFinite)
    throw NonFiniteState("non-finite state: the accelerations stayed non-finite over " +
                         std::to_string(consecutive_) + " evaluations with smaller steps; first non-finite: " +
                         first_cause_);
}

void FiniteGuard::checkSample(const Model& m, const Sample& s) {
  auto fail = [&](const std::string& what) {
    throw NonFiniteState("non-finite state: " + what + " is not finite" + at(s.time));
  };
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const BodySample& b = s.bodies[k];
    if (!b.position.allFinite() || !b.orientation.allFinite() || !b.velocity.allFinite() ||
        !b.angular_velocity.allFinite() || !b.modal.allFinite() || !b.modal_rate.allFinite())
      fail("the motion of body " + m.bodies[k].name);
  }
  for (std::size_t j = 0; j < s.joints.size(); ++j)
    if (!std::isfinite(s.joints[j].angle) || !s.joints[j].reaction_force.allFinite() ||
        !s.joints[j].reaction_torque.allFinite())
      fail("the reaction of joint " + m.joints[j].name);
  const Energies& e = s.energy;
  for (double v : {e.kinetic, e.potential, e.strain, e.dissipated, e.applied_work})
    if (!std::isfinite(v)) fail("the energy");
  if (!std::isfinite(s.violation)) fail("the constraint violation");
}

}  // namespace fc::mbs
