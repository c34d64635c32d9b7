#pragma once
// Whether a finished run's own invariants say its answer is as accurate as
// its tolerances ask (no run may report `completed` with a wrong
// answer). Two checks a wrong integration cannot pass unnoticed:
// - the energy balance T + V + D - W over each event-free segment, which the
//   exact solution keeps constant;
// - the constraint violation at the output times, which the projections keep
//   below atol / 10.
// Limits: what the error control promises. Every accepted step's local error
// is at most rtol |y| + atol (weighted norm), so
// - energy: at most steps x (rtol x the largest energy term + atol x
//   sum |g_i|), g = dE/dy over the state (mechanics/energy_sensitivity.h): what
//   the local errors allowed per step can do to E, all adding up. The atol
//   part matters where E is still small but steep in the state: a 1 000-rod
//   chain just released (0.48 J) whose rod heights may each be off by atol,
//   1e-12 m x 0.98 N per rod and step. A run that loses accuracy
//   to something the error estimate does not see - an unconverged Newton
//   stage, a stale Jacobian, an instability - exceeds it by orders of
//   magnitude; and never more than kMaxRelativeEnergyError of the largest
//   energy term (a blown-up run's largest energy term is its blow-up);
// - violation: outputs are interpolated between projected steps, so their
//   drift is the interpolant's error, at most 10 (atol + rtol L), L the
//   largest body position of the run (1 m at least).
// Calibration on every scene of the mbs-run test suites: docs/mbs-run.md,
// "Run quality".
#include <string>

namespace fc::mbs {

struct RunSummary;

constexpr double kMaxRelativeEnergyError = 0.1;
constexpr double kEnergyFloor = 1e-12;  // [J]

struct QualityLimits {
  double energy = 0.0;     // [J]
  double violation = 0.0;  // [m, rad]
};

QualityLimits qualityLimits(const RunSummary& r, double rtol, double atol);

// The status a run that reached its end should report: "completed", or
// "inaccurate: ..." naming the check that failed, its value and its limit.
std::string qualityStatus(const RunSummary& r, double rtol, double atol);

// A run that advances but would never finish: steps far above the underflow
// limit that stay tiny (a time scale of 1e-12 s in a model of seconds: a
// nearly singular mass matrix, a spring of 1e12 N/m on a milligram) make an
// explicit integrator grind for years while the progress bar sits still.
// Every kWindow accepted steps the mean step of the window gives the steps
// still needed to reach t_end; beyond kMaxRemainingSteps (a day or more at
// microseconds per step), check() returns the status to stop with, naming
// the time scale and what to try. Legitimately long runs are far from it: the
// suite's longest, the 1000 s pendulum, needs 1e5 steps; a flexible SAR run
// at rtol 1e-8, 1e6.
class StallMonitor {
 public:
  static constexpr long kWindow = 20000;
  static constexpr double kMaxRemainingSteps = 1e10;
  explicit StallMonitor(double t_end) : t_end_(t_end) {}
  // After an accepted step that reached time t; "" while the run may go on.
  std::string check(double t, const std::string& integrator);

 private:
  double t_end_;
  long steps_ = 0;
  double t_window_ = 0.0;
};

// The status of a run whose step size underflowed at time t, with what to
// change (the one run loop, simulation.cpp, for both formulations).
std::string stepFailure(double t, const std::string& integrator, double rtol, double atol);

}  // namespace fc::mbs
