#include "mbs-run/run/simulation.h"

#include <algorithm>
#include <ctime>
#include <memory>
#include <stdexcept>
#include <sstream>

#include "common/progress.h"
#include "common/termination.h"
#include "mbs-run/constrained/consistent_start.h"
#include "mbs-run/run/constrained_dynamics.h"
#include "mbs-run/run/finite_guard.h"
#include "mbs-run/run/integrator_switching.h"
#include "mbs-run/run/run_policy.h"
#include "mbs-run/run/run_quality.h"
#include "mbs-run/run/tree_dynamics.h"

namespace fc::mbs {

using Eigen::VectorXd;

namespace {

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

// An open tree of rigid bodies runs in joint coordinates (tree_dynamics.h),
// everything else constrained (constrained_dynamics.h).
std::unique_ptr<Dynamics> chooseFormulation(const Model& model, RunSummary& R) {
  const std::string not_tree = treeFormulationDeclined(model);
  if (not_tree.empty()) return makeTreeDynamics(model);
  if (model.settings.formulation == Formulation::Tree)
    R.warnings.push_back("formulation: tree is not possible here (" + not_tree + "): the run is constrained");
  return makeConstrainedDynamics(model, not_tree);
}

// Why a run ended early, as the status the contract asks for; an output
// error is not a status (the results cannot be stored) and propagates.
std::string failureStatus(double t) {
  try {
    throw;
  } catch (const OutputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    // Out of memory: writing what was computed needs memory too, and a results
    // file from a run that could not go on is no result; the run ends with the
    // error and no output (common/memory.h).
    throw;
  } catch (const fc::Terminated& e) {
    return "interrupted by " + fc::signalName(e.signal());
  } catch (const NonFiniteState& e) {
    return e.what();
  } catch (const UnsatisfiableConstraints& e) {
    return e.what();
  } catch (const std::exception& e) {
    std::ostringstream msg;
    msg << "solver failure at t = " << t << ": " << e.what();
    return msg.str();
  }
}

}  // namespace

// The stages of a run, as MuJoCo's mj_step: start; then per step: apply the
// events due, step, locate the earliest event in the step, write the output
// rows it passed, accept the state (unwrap, project), apply the located event
// or let auto switch methods; last, the counts and the quality verdict.
RunSummary simulate(const Model& model, const RunOptions& options, SampleSink& output) {
  const std::clock_t cpu0 = std::clock();
  const Settings& st = model.settings;
  const RunPolicy policy = runPolicy(model);
  RunSummary R;
  R.warnings = samplingWarnings(model);
  std::unique_ptr<Dynamics> dyn = chooseFormulation(model, R);
  R.formulation = dyn->formulation();
  SummarySink sink(model, output, R);
  FiniteGuard guard([&dyn](double t, const VectorXd& y, VectorXd& yd) { dyn->derivative(t, y, yd); },
                    [&dyn](double t, const VectorXd& y) { return dyn->nonFiniteCause(t, y); });
  IntegratorSwitching methods(policy, guard.rhs(), dyn->stiffPart(), dyn->size());
  R.integrator = methods.label();
  OutputClock clock(st.output_step, st.t_end);
  StallMonitor stall(st.t_end);
  EnergyBalance balance;
  fc::Progress progress("mbs-run", st.t_end, options.quiet);
  const double atol = policy.atol;
  double t = 0.0;
  // Any failure (a kernel throwing, a singular factorisation, a non-finite
  // state, contradicting joints, a signal) ends the run with what was
  // computed so far and a status saying why, as the contract asks.
  try {
    VectorXd y = dyn->start(atol, R.event_log);
    methods.current().reset(0.0, y);
    sink.write(dyn->sample(0.0, y));
    clock.advance();
    guard.watchSignals();
    balance.startSegment(dyn->energy(0.0, y));

    while (t < st.t_end) {
      if (const int sig = fc::terminationSignal()) throw fc::Terminated(sig);
      while (dyn->applyDueEvent(t, y, R.event_log)) {  // events at or before t (e.g. time 0) apply now
        methods.restartAfterEvent(t, y, R.integrator_log);
        balance.startSegment(dyn->energy(t, y));
      }
      Integrator& integ = methods.current();
      if (!integ.step(dyn->stepLimit(st.t_end))) {
        R.status = stepFailure(t, integ.name(), policy.rtol, atol);
        break;
      }
      const double t_new = dyn->locateEvent(integ, t, y);
      const bool event = dyn->eventLocated();
      const VectorXd y_new = event ? integ.interpolate(t_new) : integ.y();
      for (; clock.dueBy(t_new); clock.advance()) {
        const double to = std::min(clock.next(), t_new);
        sink.write(dyn->sample(to, integ.interpolate(to)));
      }
      balance.check(dyn->energy(t_new, y_new), R);
      t = t_new;
      y = y_new;
      const bool projected = dyn->accept(t, y, event);
      R.projections += projected;
      bool new_segment = false;
      if (event) {
        new_segment = dyn->applyLocatedEvent(t, y, integ.t() - integ.tPrevious(), R.event_log);
        methods.restartAfterEvent(t, y, R.integrator_log);
      } else if (methods.switchIfStiff(t, y, R.integrator_log)) {
        R.integrator = methods.label();
      } else if (projected) {
        integ.restart(t, y);
      }
      if (new_segment || dyn->timedEventDue(t)) balance.startSegment(dyn->energy(t, y));
      progress.update(t, "steps " + std::to_string(methods.current().steps));
      if (std::string stalled = stall.check(t, methods.current().name()); !stalled.empty()) {
        R.status = std::move(stalled);
        break;
      }
    }
  } catch (...) {
    R.status = failureStatus(t);
  }
  progress.finish();
  R.t_reached = t;
  R.limit_impacts = dyn->limitImpacts();
  R.margins.latches = dyn->latches();
  R.steps = methods.steps();
  R.rejected_steps = methods.rejected();
  R.evaluations = dyn->evaluations();
  R.max_al_iterations = dyn->maxAlIterations();
  R.cpu_seconds = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  // A run that reached its end says whether its answer is within its
  // tolerances (run_quality.h): "completed" only then.
  if (R.status == "completed") R.status = qualityStatus(R, policy.rtol, atol);
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
