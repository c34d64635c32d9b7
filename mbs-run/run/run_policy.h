#pragma once
// The run policy: which integrator a run starts with, whether `auto` may hand
// a stiff segment to an implicit method, and the error control. The scene's
// `simulation:` keys and mbs-run's command line only record what was asked
// for (Settings, model/model.h: `integrator: auto` stays Auto there);
// runPolicy() decides once, at the start of the run, what that means for this
// model, and the loop (simulation.cpp) and its stages consult nothing else.
// How the switch itself is tried and judged: integrator_switching.h and
// switch_trial.h.
#include <optional>
#include <string>
#include <vector>

#include "mbs-run/integrators/integrator.h"
#include "mbs-run/model/model.h"

namespace fc::mbs {

struct RunPolicy {
  // The method the run starts with and that a named choice keeps throughout;
  // never Auto.
  IntegratorKind integrator = IntegratorKind::DormandPrince;
  // Set when `integrator: auto` chose dopri5: the run switches to an implicit
  // method for the rest of an event-free segment once Dormand-Prince's
  // stiffness test (Hairer's) finds it held at its stability boundary with
  // steps below 3.25 / stiff_frequency (1.6 ms), and a trial shows the
  // implicit method cheaper and as accurate (measurements in docs/mbs-run.md,
  // "Cost").
  bool switch_when_stiff = false;
  double stiff_frequency = 2000.0;  // [rad/s]
  // The error control: rtol, atol (the scene's, or 1e-3 rtol when it gives
  // none), and the longest step (the scene's max_step, or ten output
  // intervals, so that a joint-angle event cannot hide two crossings inside
  // one long step of a slow motion).
  double rtol = 1e-6, atol = 1e-9, max_step = 0.0;

  // The tolerances over a state of `size` entries whose last two are the
  // energy quadratures (diagnostics, not controlled). Both formulations
  // integrate with them.
  Tolerances tolerances(int size) const;
};

// The policy of a run of this model, its Settings as the scene and the
// command line left them.
RunPolicy runPolicy(const Model& model);

// The absolute tolerance a run uses: `atol`, or 1e-3 rtol when the scene
// gives none (the one place this default is written).
double absoluteTolerance(const Settings& st);

// Which integrator IntegratorKind::Auto means for this model: TR-BDF2 when a
// force element's natural frequency would force an explicit method to steps
// far below the output step, Dormand-Prince otherwise.
IntegratorKind chooseIntegrator(const Model& model);

// The integrator a name asks for (`auto`, `dopri5`, `trbdf2`, `imex`: the
// scene's simulation.integrator and mbs-run's --integrator), none if unknown;
// and the names, in that order, for the messages and the command line's
// choices.
std::optional<IntegratorKind> integratorNamed(const std::string& name);
const std::vector<std::string>& integratorNames();

}  // namespace fc::mbs
