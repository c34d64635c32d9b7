#include "mbs-run/run/simulation.h"

#include <algorithm>
#include <ctime>
#include <optional>
#include <stdexcept>
#include <sstream>

#include "common/progress.h"
#include "common/termination.h"
#include "mbs-run/constrained/consistent_start.h"
#include "mbs-run/run/crossings.h"
#include "mbs-run/run/events.h"
#include "mbs-run/run/finite_guard.h"
#include "mbs-run/run/integrator_switching.h"
#include "mbs-run/run/joint_limits.h"
#include "mbs-run/run/run_quality.h"
#include "mbs-run/tree/tree_simulation.h"

namespace fc::mbs {

using Eigen::VectorXd;

void History::append(const Sample& s) {
  const std::size_t nb = s.bodies.size(), nj = s.joints.size();
  if (position.size() != nb) {
    for (auto* v : {&position, &velocity, &angular_velocity}) v->resize(nb);
    orientation.resize(nb);
    modal.resize(nb);
    modal_rate.resize(nb);
    stress.resize(nb);
  }
  if (reaction.size() != nj) {
    joint_angle.resize(nj);
    reaction.resize(nj);
    reaction_torque.resize(nj);
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
    stress[k].push_back(b.stress);
  }
  for (std::size_t j = 0; j < nj; ++j) {
    reaction[j].push_back(s.joints[j].reaction_force);
    reaction_torque[j].push_back(s.joints[j].reaction_torque);
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

Sample History::row(std::size_t i) const {
  Sample s;
  s.time = time[i];
  s.bodies.resize(position.size());
  for (std::size_t k = 0; k < position.size(); ++k) {
    BodySample& b = s.bodies[k];
    b.position = position[k][i];
    b.orientation = orientation[k][i];
    b.velocity = velocity[k][i];
    b.angular_velocity = angular_velocity[k][i];
    b.modal = modal[k][i];
    b.modal_rate = modal_rate[k][i];
    b.stress = stress[k][i];
  }
  s.joints.resize(reaction.size());
  for (std::size_t j = 0; j < reaction.size(); ++j) {
    s.joints[j].angle = joint_angle[j][i];
    s.joints[j].reaction_force = reaction[j][i];
    s.joints[j].reaction_torque = reaction_torque[j][i];
    s.joints[j].limit_state = limit_state[j][i];
    s.joints[j].limit_torque = limit_torque[j][i];
  }
  for (std::size_t k = 0; k < distances.size(); ++k) s.distances.push_back(distances[k][i]);
  s.energy.kinetic = kinetic[i];
  s.energy.potential = potential[i];
  s.energy.strain = strain[i];
  s.energy.dissipated = dissipated[i];
  s.energy.applied_work = applied_work[i];
  s.violation = violation[i];
  return s;
}

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

class SummarySink : public SampleSink {
 public:
  SummarySink(const Model& m, SampleSink& out, RunSummary& r) : m_(m), out_(out), r_(r) {}
  void write(const Sample& s) override {
    FiniteGuard::checkSample(m_, s);  // a file never holds NaN: the run stops first
    r_.observe(m_, s);
    out_.write(s);
  }

 private:
  const Model& m_;
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
  // An open tree of rigid bodies runs in joint coordinates (tree_simulation.h).
  const std::string not_tree = treeFormulationDeclined(model);
  if (not_tree.empty()) return simulateTree(model, options, output);
  const std::clock_t cpu0 = std::clock();
  const Settings& st = model.settings;
  System sys(model);
  RunSummary R;
  R.warnings = samplingWarnings(model);
  R.formulation = "constrained (" + not_tree + ")";
  if (st.formulation == Formulation::Tree)
    R.warnings.push_back("formulation: tree is not possible here (" + not_tree + "): the run is constrained");
  SummarySink sink(model, output, R);
  const Tolerances tol = tolerances(st, sys.size());
  // Stops on revolute joints (joint_limits.h): a rebound rests when its
  // remaining bounces fit in the step it was found in, or rise less than
  // atol [rad].
  StopMonitor stops(model, tol.atol);
  FiniteGuard guard(sys);
  IntegratorSwitching methods(st, guard.rhs(), [&sys](double t, const VectorXd& yy) { return sys.modalSplit(t, yy); },
                              tol);
  R.integrator = methods.label();
  TimedEvents timed(model);
  CrossingEvents crossings(model);
  OutputClock clock(st.output_step, st.t_end);
  StallMonitor stall(st.t_end);
  EnergyBalance balance;
  fc::Progress progress("mbs-run", st.t_end, options.quiet);
  double t = 0.0;
  double last_stop_time = -1.0;
  int same_time_stops = 0;
  // Any failure (a kernel throwing, a singular factorisation, a non-finite
  // state, contradicting joints, a signal) ends the run with what was
  // computed so far and a status saying why, as the contract asks.
  try {
    VectorXd y = consistentStart(sys, tol.atol);
    stops.start(sys, 0.0, y, R.event_log);
    if (stops.active()) sys.project(0.0, y);
    methods.current().reset(0.0, y);
    sink.write(takeSample(sys, 0.0, y));
    clock.advance();
    guard.watchSignals();
    balance.startSegment(sys.energies(0.0, y).total());

    while (t < st.t_end) {
      if (const int sig = fc::terminationSignal()) throw fc::Terminated(sig);
      while (timed.dueAt(t)) {  // events at or before the current time (e.g. time 0) apply now
        R.event_log.push_back(timeLabel(t) + describeEvent(model, timed.applyNext(sys, y)));
        projectKeepingEnergy(sys, t, y);
        requireSatisfiable(sys, t, y, tol.atol);
        methods.restartAfterEvent(t, y, R.integrator_log);
        balance.startSegment(sys.energies(t, y).total());
      }
      Integrator& integ = methods.current();
      if (!integ.step(timed.limit(st.t_end))) {
        R.status = stepFailure(t, integ.name(), st.rtol, tol.atol);
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
        requireSatisfiable(sys, t, y, tol.atol);
        methods.restartAfterEvent(t, y, R.integrator_log);
      } else if (stop) {
        // Stop events that repeat without time advancing would be a Zeno
        // sequence the rest rule should have prevented: stop, saying so.
        same_time_stops = (t == last_stop_time) ? same_time_stops + 1 : 0;
        last_stop_time = t;
        if (same_time_stops > 20)
          throw std::runtime_error("joint " + model.joints[stop->joint].name +
                                   ": stop events repeat without time advancing (Zeno sequence)");
        // The step the event was found in is the rest rule's time resolution.
        R.event_log.push_back(stops.apply(sys, *stop, t, y, integ.t() - integ.tPrevious()));
        sys.project(t, y);
        methods.restartAfterEvent(t, y, R.integrator_log);
      } else if (methods.switchIfStiff(t, y, R.integrator_log)) {
        R.integrator = methods.label();
      } else if (projected) {
        integ.restart(t, y);
      }
      if (hit.event || timed.dueAt(t)) balance.startSegment(sys.energies(t, y).total());
      progress.update(t, "steps " + std::to_string(methods.current().steps));
      if (std::string stalled = stall.check(t, methods.current().name()); !stalled.empty()) {
        R.status = std::move(stalled);
        break;
      }
    }
  } catch (const OutputError&) {
    throw;  // the results cannot be stored: an error, not a status
  } catch (const fc::Terminated& e) {
    R.status = "interrupted by " + fc::signalName(e.signal());
  } catch (const NonFiniteState& e) {
    R.status = e.what();
  } catch (const UnsatisfiableConstraints& e) {
    R.status = e.what();
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
  // A run that reached its end says whether its answer is within its
  // tolerances (run_quality.h): "completed" only then.
  if (R.status == "completed") R.status = qualityStatus(R, st.rtol, tol.atol);
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
