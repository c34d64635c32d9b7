#pragma once
// The one interface the run loop (simulation.cpp) integrates, as Drake's
// Simulator steps any System: a formulation turns the Model into a state vector
// y, its time derivative, output rows and energies, and owns what happens at
// its events. Two implement it:
//   - ConstrainedDynamics (constrained_dynamics.h): body coordinates with the
//     augmented-Lagrangian constraints; timed events, angle crossings, stops;
//   - TreeDynamics (tree_dynamics.h): joint coordinates of an open tree of
//     rigid bodies; no events (the tree is only chosen for scenes without).
// The loop itself reads as MuJoCo's mj_step: start, step, locate events, write
// rows, accept, apply the event.
#include <Eigen/Dense>

#include <array>
#include <string>
#include <vector>

#include "mbs-run/integrators/integrator.h"
#include "mbs-run/run/margins.h"
#include "mbs-run/run/sampling.h"

namespace fc::mbs {

class Dynamics {
 public:
  virtual ~Dynamics() = default;

  // "tree", or "constrained (why the tree was not possible)".
  virtual std::string formulation() const = 0;
  // The consistent initial state (the stops' initial contacts logged).
  virtual Eigen::VectorXd start(double atol, std::vector<std::string>& event_log) = 0;
  // Length of y (known before start(): the integrators are made first).
  virtual int size() const = 0;
  // f(t, y), and what went non-finite when it is not finite ("" if unknown).
  virtual void derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) = 0;
  virtual std::string nonFiniteCause(double, const Eigen::VectorXd&) { return ""; }
  // The stiff linear modal part for the IMEX method; empty when there is none.
  virtual StiffPart stiffPart() { return StiffPart(); }
  // The output row, and the total energy T + V + D - W the balance follows.
  virtual Sample sample(double t, const Eigen::VectorXd& y) = 0;
  virtual double energy(double t, const Eigen::VectorXd& y) = 0;

  // Events. Applies one event due at or before t (timed events); false when none is.
  virtual bool applyDueEvent(double, Eigen::VectorXd&, std::vector<std::string>&) { return false; }
  // The step may not pass the next timed event.
  virtual double stepLimit(double t_end) const { return t_end; }
  // After a step from (t, y): the time of the earliest event inside it, or
  // the step's end when there is none (eventLocated() says which).
  virtual double locateEvent(Integrator& integ, double, const Eigen::VectorXd&) { return integ.t(); }
  virtual bool eventLocated() const { return false; }
  // The accepted state (t, y): angle unwrapping references, drift projection
  // (always at an event). True if y was projected.
  virtual bool accept(double t, Eigen::VectorXd& y, bool at_event) = 0;
  // Applies the located event at (t, y); step is the length of the step it
  // was found in. True when it starts a new energy-balance segment.
  virtual bool applyLocatedEvent(double, Eigen::VectorXd&, double, std::vector<std::string>&) { return false; }
  // A timed event is due at t (it starts a new energy-balance segment).
  virtual bool timedEventDue(double) const { return false; }

  // Counts for the summary.
  virtual long evaluations() const = 0;
  virtual int maxAlIterations() const { return 0; }
  // Impacts on the stops, per joint (joint_limits.h).
  virtual std::vector<std::vector<std::array<double, 5>>> limitImpacts() const { return {}; }
  // Each latch's arrival (time, rate) before its lock acted (margins.h).
  virtual std::vector<Margins::Latch> latches() const { return {}; }
};

}  // namespace fc::mbs
