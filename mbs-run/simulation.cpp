#include "mbs-run/simulation.h"

#include <ctime>
#include <optional>
#include <stdexcept>
#include <sstream>

#include "common/progress.h"
#include "mbs-run/crossings.h"
#include "mbs-run/events.h"
#include "mbs-run/integrator_switching.h"
#include "mbs-run/joint_limits.h"

namespace fc::mbs {

std::atomic<int> g_stop_signal{0};

using Eigen::VectorXd;

void History::append(const Sample& s) {
  const std::size_t nb = s.bodies.size(), nj = s.joints.size();
  if (position.size() != nb) {
    for (auto* v : {&position, &velocity, &angular_velocity}) v->resize(nb);
    orientation.resize(nb);
    modal.resize(nb);
    modal_rate.resize(nb);
  }
  if (reaction.size() != nj) {
    joint_angle.resize(nj);
    reaction.resize(nj);
    limit_state.resize(nj);
    limit_torque.resize(nj);
  }
  if (distances.size() != s.distances.size()) distances.resize(s.distances.size());
  for (std::size_t k = 0; k < s.distances.size(); ++k) distances[k].push_back(s.distances[k]);
  time.push_back(s.time);
  for (std::size_t k = 0; k < nb; ++k) {
    const BodySample& b = s.bodies[k];
    position[k].push_back(b.position);
    orientation[k].push_back(b.orientation);
    velocity[k].push_back(b.velocity);
    angular_velocity[k].push_back(b.angular_velocity);
    modal[k].push_back(b.modal);
    modal_rate[k].push_back(b.modal_rate);
  }
  for (std::size_t j = 0; j < nj; ++j) {
    reaction[j].push_back(s.joints[j].reaction_force);
    joint_angle[j].push_back(s.joints[j].angle);
    limit_state[j].push_back(s.joints[j].limit_state);
    limit_torque[j].push_back(s.joints[j].limit_torque);
  }
  kinetic.push_back(s.energy.kinetic);
  potential.push_back(s.energy.potential);
  strain.push_back(s.energy.strain);
  dissipated.push_back(s.energy.dissipated);
  applied_work.push_back(s.energy.applied_work);
  violation.push_back(s.violation);
}

namespace {

// Error control on positions and velocities (atol in m, rad, m/s, rad/s).
Tolerances tolerances(const Settings& st, int size) {
  Tolerances tol;
  tol.rtol = st.rtol;
  tol.atol = st.atol > 0 ? st.atol : 1e-3 * st.rtol;
  // Default step limit: ten output intervals, so that a joint-angle event cannot
  // hide two crossings inside one long step of a slow motion.
  tol.max_step = st.max_step > 0 ? st.max_step : 10.0 * st.output_step;
  tol.mask = VectorXd::Ones(size);
  tol.mask.tail(2).setZero();  // energy quadratures are diagnostics, not controlled
  return tol;
}

// Projects an accepted state onto the constraints when its drift is one the
// error control could see: below a tenth of atol (in m, rad, m/s, rad/s) the
// stabilised accelerations keep it bounded, and every projection costs two or
// three factorisations and, by changing y, the first stage the next step would
// reuse (FSAL). True if it projected.
bool projectDrift(System& sys, double t, VectorXd& y, double atol, bool always) {
  const System::Violations viol = sys.violations(t, y);
  const bool project = always || viol.position > 0.1 * atol || viol.velocity > 0.1 * atol;
  if (project) sys.project(t, y);
  return project;
}

// The message of a step-size underflow.
std::string stepFailure(double t, const Integrator& integ, const Settings& st, double atol) {
  std::ostringstream s;
  // The usual cause at tight tolerances: the error test (or TR-BDF2's Newton
  // iteration) asks for more digits than f(y) carries (the multiplier
  // iteration stops at a 1e-10 residual), so say what to change.
  s << "solver failure: step size too small at t = " << t << " (" << integ.name() << ", rtol " << st.rtol
    << ", atol " << atol << "): the error test cannot be met; at tight tolerances the right-hand side's"
    << " precision is the limit - loosen rtol or use dopri5";
  return s.str();
}

class SummarySink : public SampleSink {
 public:
  SummarySink(SampleSink& out, RunSummary& r) : out_(out), r_(r) {}
  void write(const Sample& s) override {
    r_.observe(s);
    out_.write(s);
  }

 private:
  SampleSink& out_;
  RunSummary& r_;
};

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

}  // namespace

RunSummary simulate(const Model& model, const RunOptions& options, SampleSink& output) {
  const std::clock_t cpu0 = std::clock();
  const Settings& st = model.settings;
  System sys(model);
  RunSummary R;
  SummarySink sink(output, R);

  VectorXd y = sys.initialState();
  // Capture held poses, make the initial state consistent, then measure the
  // revolute angle offsets in the consistent configuration.
  sys.initializeJoints(y);
  sys.project(0.0, y);
  sys.initializeJoints(y);

  const Tolerances tol = tolerances(st, sys.size());
  // Stops on revolute joints (joint_limits.h): the angle tolerance that
  // decides when a rebound is too small to resolve is atol [rad].
  StopMonitor stops(model, tol.atol);
  stops.start(sys, 0.0, y, R.event_log);
  if (stops.active()) sys.project(0.0, y);
  IntegratorSwitching methods(st, [&sys](double t, const VectorXd& yy, VectorXd& yd) { sys.derivative(t, yy, yd); },
                              tol);
  R.integrator = methods.label();
  methods.current().reset(0.0, y);

  TimedEvents timed(model);
  CrossingEvents crossings(model);
  OutputClock clock(st.output_step, st.t_end);
  sink.write(takeSample(sys, 0.0, y));
  clock.advance();
  EnergyBalance balance;
  balance.startSegment(sys.energies(0.0, y).total());

  fc::Progress progress("mbs-run", st.t_end, options.quiet);
  double t = 0.0;
  double last_stop_time = -1.0;
  int same_time_stops = 0;
  // Any failure inside the step (a kernel throwing, a singular factorisation
  // reported as an exception) ends the run with what was computed so far and
  // a status saying why, as the contract asks of solver failures.
  try {
    while (t < st.t_end) {
      if (g_stop_signal.load()) {
        R.status = "interrupted by signal " + std::to_string(g_stop_signal.load());
        break;
      }
      while (timed.dueAt(t)) {  // events at or before the current time (e.g. time 0) apply now
        R.event_log.push_back(timeLabel(t) + describeEvent(model, timed.applyNext(sys, y)));
        projectKeepingEnergy(sys, t, y);
        methods.restartAfterEvent(t, y, R.integrator_log);
        balance.startSegment(sys.energies(t, y).total());
      }
      Integrator& integ = methods.current();
      if (!integ.step(timed.limit(st.t_end))) {
        R.status = stepFailure(t, integ, st, tol.atol);
        break;
      }
      CrossingEvents::Hit hit = crossings.locate(sys, integ, t, y);
      double t_new = hit.event ? hit.time : integ.t();
      // Stops: the earliest impact or release in the step, if not after the
      // crossing (at equal times the stop acts first; the crossing is found
      // again on the step that follows).
      std::optional<StopEvent> stop;
      if (stops.active()) {
        stop = stops.locate(sys, [&integ](double tt) { return integ.interpolate(tt); }, t, y, t_new,
                            hit.event ? integ.interpolate(t_new) : integ.y());
        if (stop) {
          if (hit.event) crossings.rearm(hit.event);
          hit.event = nullptr;
          t_new = stop->time;
        }
      }
      const VectorXd y_new = hit.event || stop ? integ.interpolate(t_new) : integ.y();
      for (; clock.dueBy(t_new); clock.advance()) {
        const double to = std::min(clock.next(), t_new);
        sink.write(takeSample(sys, to, integ.interpolate(to)));
      }
      balance.check(sys.energies(t_new, y_new).total(), R);
      t = t_new;
      y = y_new;
      sys.updateAngleReferences(y);
      const bool projected = projectDrift(sys, t, y, tol.atol, hit.event != nullptr || stop);
      R.projections += projected;
      if (hit.event) {
        applyEvent(sys, *hit.event, y);
        R.event_log.push_back(timeLabel(t) + " joint " + model.joints[hit.event->joint].name + " crossed " +
                              std::to_string(hit.event->angle) + ";" + describeEvent(model, *hit.event));
        projectKeepingEnergy(sys, t, y);
        methods.restartAfterEvent(t, y, R.integrator_log);
      } else if (stop) {
        // Stop events that repeat without time advancing would be a Zeno
        // sequence the rest rule should have prevented: stop, saying so.
        same_time_stops = (t == last_stop_time) ? same_time_stops + 1 : 0;
        last_stop_time = t;
        if (same_time_stops > 20)
          throw std::runtime_error("joint " + model.joints[stop->joint].name +
                                   ": stop events repeat without time advancing (Zeno sequence)");
        R.event_log.push_back(stops.apply(sys, *stop, t, y));
        sys.project(t, y);
        methods.restartAfterEvent(t, y, R.integrator_log);
      } else if (methods.switchIfStiff(t, y, R.integrator_log)) {
        R.integrator = methods.label();
      } else if (projected) {
        integ.restart(t, y);
      }
      if (hit.event || timed.dueAt(t)) balance.startSegment(sys.energies(t, y).total());
      progress.update(t, "steps " + std::to_string(methods.current().steps));
    }
  } catch (const std::exception& e) {
    std::ostringstream msg;
    msg << "solver failure at t = " << t << ": " << e.what();
    R.status = msg.str();
  }
  progress.finish();
  R.t_reached = t;
  R.limit_impacts = stops.impacts();
  R.steps = methods.steps();
  R.rejected_steps = methods.rejected();
  R.evaluations = sys.stats().evaluations;
  R.max_al_iterations = sys.stats().max_al_iterations;
  R.cpu_seconds = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  return R;
}

namespace {
class HistorySink : public SampleSink {
 public:
  explicit HistorySink(History& h) : h_(h) {}
  void write(const Sample& s) override { h_.append(s); }

 private:
  History& h_;
};
}  // namespace

Results simulate(const Model& model, const RunOptions& options) {
  Results r;
  HistorySink sink(r);
  static_cast<RunSummary&>(r) = simulate(model, options, sink);
  return r;
}

}  // namespace fc::mbs
