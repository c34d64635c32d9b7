#include "mbs-run/run/constrained_dynamics.h"

#include <optional>
#include <stdexcept>

#include "mbs-run/constrained/consistent_start.h"
#include "mbs-run/constrained/system.h"
#include "mbs-run/run/crossings.h"
#include "mbs-run/run/events.h"
#include "mbs-run/run/joint_limits.h"
#include "mbs-run/run/run_summary.h"

namespace fc::mbs {

using Eigen::VectorXd;

namespace {

// Projects an accepted state onto the constraints when its drift is one the
// error control could see: below a tenth of atol (in m, rad, m/s, rad/s) the
// stabilised accelerations keep it bounded, and every projection costs two or
// three factorisations and, by changing y, the first stage the next step would
// reuse (FSAL). True if it projected.
bool projectDrift(System& sys, double t, VectorXd& y, double atol, bool always) {
  const System::Violations viol = sys.violations(t, y);
  const bool project = always || viol.position > 0.1 * atol || viol.velocity > 0.1 * atol;
  if (project) sys.project(t, y, true);  // drift: modes held (System::project)
  return project;
}

// The kinetic energy a velocity jump removes (a lock or a joint switched on
// while the bodies move is a plastic impact: the projection that follows is
// its impulse) goes into the dissipated-energy quadrature, so that
// T + V + D - W stays continuous across it.
void projectKeepingEnergy(System& sys, double t, VectorXd& y) {
  const double T0 = sys.energies(t, y).kinetic;
  sys.project(t, y);
  const double lost = T0 - sys.energies(t, y).kinetic;
  if (lost > 0.0) y[sys.model().nq + sys.model().nv] += lost;
}

class ConstrainedDynamics : public Dynamics {
 public:
  ConstrainedDynamics(const Model& m, std::string why_not_tree)
      : m_(m), why_(std::move(why_not_tree)), sys_(m), timed_(m), crossings_(m) {}

  std::string formulation() const override { return "constrained (" + why_ + ")"; }

  VectorXd start(double atol, std::vector<std::string>& log) override {
    atol_ = atol;
    // Stops on revolute joints (joint_limits.h): a rebound rests when its
    // remaining bounces fit in the step it was found in, or rise less than
    // atol [rad].
    stops_.emplace(m_, atol);
    VectorXd y = consistentStart(sys_, atol);
    stops_->start(sys_, 0.0, y, log);
    if (stops_->active()) sys_.project(0.0, y);
    return y;
  }
  int size() const override { return sys_.size(); }
  void derivative(double t, const VectorXd& y, VectorXd& ydot) override { sys_.derivative(t, y, ydot); }
  std::string nonFiniteCause(double t, const VectorXd& y) override { return sys_.nonFiniteCause(t, y); }
  StiffPart stiffPart() override {
    return [this](double t, const VectorXd& yy) { return sys_.modalSplit(t, yy); };
  }
  Sample sample(double t, const VectorXd& y) override { return takeSample(sys_, t, y); }
  double energy(double t, const VectorXd& y) override { return sys_.energies(t, y).total(); }

  bool applyDueEvent(double t, VectorXd& y, std::vector<std::string>& log) override {
    if (!timed_.dueAt(t)) return false;
    log.push_back(timeLabel(t) + describeEvent(m_, timed_.applyNext(sys_, y)));
    projectKeepingEnergy(sys_, t, y);
    requireSatisfiable(sys_, t, y, atol_);
    return true;
  }
  double stepLimit(double t_end) const override { return timed_.limit(t_end); }

  // The earliest of a joint-angle crossing and a stop event in the step (at
  // equal times the stop acts first; the crossing is found again on the step
  // that follows).
  double locateEvent(Integrator& integ, double t, const VectorXd& y) override {
    hit_ = crossings_.locate(sys_, integ, t, y);
    double t_new = hit_.event ? hit_.time : integ.t();
    stop_.reset();
    if (stops_->active()) {
      stop_ = stops_->locate(sys_, [&integ](double tt) { return integ.interpolate(tt); }, t, y, t_new,
                             hit_.event ? integ.interpolate(t_new) : integ.y());
      if (stop_) {
        if (hit_.event) crossings_.rearm(hit_.event);
        hit_.event = nullptr;
        t_new = stop_->time;
      }
    }
    return t_new;
  }
  bool eventLocated() const override { return hit_.event || stop_; }

  bool accept(double t, VectorXd& y, bool at_event) override {
    sys_.updateAngleReferences(y);
    return projectDrift(sys_, t, y, atol_, at_event);
  }

  bool applyLocatedEvent(double t, VectorXd& y, double step, std::vector<std::string>& log) override {
    if (hit_.event) {
      if (!hit_.event->lock.empty())  // a latch: its arrival rate before the lock acts (margins.h)
        latches_.push_back(latchArrival(sys_, m_, hit_.event->joint, hit_.event->angle, t, y));
      applyEvent(sys_, *hit_.event, y);
      log.push_back(timeLabel(t) + " joint " + m_.joints[hit_.event->joint].name + " crossed " +
                    std::to_string(hit_.event->angle) + ";" + describeEvent(m_, *hit_.event));
      projectKeepingEnergy(sys_, t, y);
      requireSatisfiable(sys_, t, y, atol_);
      return true;
    }
    // Stop events that repeat without time advancing would be a Zeno
    // sequence the rest rule should have prevented: stop, saying so.
    same_time_stops_ = (t == last_stop_time_) ? same_time_stops_ + 1 : 0;
    last_stop_time_ = t;
    if (same_time_stops_ > 20)
      throw std::runtime_error("joint " + m_.joints[stop_->joint].name +
                               ": stop events repeat without time advancing (Zeno sequence)");
    // The step the event was found in is the rest rule's time resolution.
    log.push_back(stops_->apply(sys_, *stop_, t, y, step));
    sys_.project(t, y);
    return false;
  }
  bool timedEventDue(double t) const override { return timed_.dueAt(t); }

  long evaluations() const override { return sys_.stats().evaluations; }
  int maxAlIterations() const override { return sys_.stats().max_al_iterations; }
  std::vector<std::vector<std::array<double, 5>>> limitImpacts() const override {
    return stops_ ? stops_->impacts() : std::vector<std::vector<std::array<double, 5>>>{};
  }
  std::vector<Margins::Latch> latches() const override { return latches_; }

 private:
  const Model& m_;
  std::string why_;
  System sys_;
  TimedEvents timed_;
  CrossingEvents crossings_;
  std::optional<StopMonitor> stops_;
  double atol_ = 0.0;
  CrossingEvents::Hit hit_;
  std::vector<Margins::Latch> latches_;
  std::optional<StopEvent> stop_;
  double last_stop_time_ = -1.0;
  int same_time_stops_ = 0;
};

}  // namespace

std::unique_ptr<Dynamics> makeConstrainedDynamics(const Model& model, const std::string& why_not_tree) {
  return std::make_unique<ConstrainedDynamics>(model, why_not_tree);
}

}  // namespace fc::mbs
