#pragma once
// Stops on revolute joints (scene `limits: {min, max, restitution}`):
// impacts located exactly in time on the integrator's dense output, Newton's
// restitution as an impulse of the constrained system, and a resting contact
// that is an active unilateral constraint whose reaction sign is monitored.
// Theory and validation: docs/mbs-run.md, section "Stops and impacts".
//
// Impact (Pfeiffer & Glocker, Multibody Dynamics with Unilateral Contacts,
// 1996, ch. 4; Newton's law on the contact's relative rate): with v- the
// velocities before and g = d(angle)/dv the angle's gradient, the velocities
// after solve the impulsive momentum balance with every joint active,
//   M (v+ - v-) = Phi_v^T mu + g^T P,
//   Phi_v v+ + Phi_t = 0,         g v+ = -e g v-,
// i.e. v+ is the mass-orthogonal projection of v- onto those constraints;
// P [N m s] is the stop's angular impulse and T(v-) - T(v+) >= 0 the energy
// the impact dissipates (zero for e = 1).
//
// Rest instead of a Zeno sequence: after an impact the joint would rise
// from the stop at v = e |rate-| against an acceleration a that pushes it
// back; with a constant a the bounces that follow form a geometric series
// that ends (accumulates) after t_Z = 2 v / ((1 - e) a), rising at most
// v^2 / (2 a). The joint rests (its angle held by one row, captureLock) when
// that remainder cannot be resolved: all of it fits inside the integrator's
// current step (t_Z <= h: the time-stepping view of Moreau and Jean, where a
// rebound that the contact's acceleration reverses within a step is a closed
// contact), or its apex is below the angle tolerance. It leaves when the
// row's torque turns from pushing into pulling (located on the dense output
// like an impact, with a hysteresis of a relative 1e-8 of the holding torque
// so that rounding cannot make it chatter).
#include <Eigen/Dense>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mbs-run/model/model.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs {

struct ImpactSolution {
  Eigen::VectorXd v_plus;
  double impulse = 0.0;  // multiplier of the g row: the stop's impulse along the angle
};

// The velocity jump of a constrained system (dense kernel): v+ minimising
// (v+ - v-)^T M (v+ - v-) subject to Phi v+ + phit = 0 and g v+ = target, by
// the Cholesky factor L of M and the pseudo-inverse of C M^-1 C^T, C = [Phi; g]
// (Phi may have redundant rows, as the SAR's hinge lines do; the g row's
// multiplier is unique as long as g is not a combination of Phi's rows).
ImpactSolution constrainedImpact(const Eigen::MatrixXd& M, const Eigen::MatrixXd& Phi, const Eigen::VectorXd& phit,
                                 const Eigen::RowVectorXd& g, const Eigen::VectorXd& v_minus, double target);

// Duration of the rest of a Zeno sequence: the bounces after a rebound at
// `rebound_rate` against a constant `accel_into_stop` (> 0), restitution e < 1,
// sum to 2 rebound / ((1 - e) accel) (a geometric series of flight times).
double zenoRemainder(double restitution, double rebound_rate, double accel_into_stop);

// Whether a joint leaving its stop at `rebound_rate` against `accel_into_stop`
// (both >= 0 toward the stop's side convention: rate away, acceleration back)
// rests: its remaining bounces all fit inside one integrator step `step`
// [s] (t_Z <= step), or it rises less than `angle_tol` before falling back.
bool shouldRest(double restitution, double rebound_rate, double accel_into_stop, double angle_tol,
                double step = 0.0);

// One stop event inside an accepted step.
struct StopEvent {
  enum Kind { Impact, Release } kind = Impact;
  int joint = -1;
  int side = 0;  // -1 min stop, +1 max stop
  double time = 0.0;
};

class StopMonitor {
 public:
  using Dense = std::function<Eigen::VectorXd(double)>;
  StopMonitor(const Model& model, double angle_tol);
  bool active() const { return !joints_.empty(); }
  // Joints that start on a stop and are pushed into it start resting.
  void start(System& sys, double t, Eigen::VectorXd& y, std::vector<std::string>& log);
  // The earliest stop event in (t0, t1]: a free joint's angle crossing one of
  // its bounds, or a resting joint's torque crossing into a pull; located by
  // bisection on the dense output to machine precision in time (the state
  // returned is on the admissible side of the stop).
  std::optional<StopEvent> locate(System& sys, const Dense& dense, double t0, const Eigen::VectorXd& y0, double t1,
                                  const Eigen::VectorXd& y1);
  // Applies an event at its time: impulse and energy loss (into y's
  // dissipated-energy quadrature), rest or release. `step` is the accepted
  // integrator step the event was located in (the time resolution of the
  // rest rule; 0 at the start). Returns the log line.
  std::string apply(System& sys, const StopEvent& ev, double t, Eigen::VectorXd& y, double step = 0.0);
  // Per joint (empty for joints without limits), per impact: time, angle
  // rate before and after [rad/s], impulse [N m s], energy lost [J]. The
  // resting state and torque are in each output row (sampling.h).
  const std::vector<std::vector<std::array<double, 5>>>& impacts() const { return impacts_; }

 private:
  double angleRate(System& sys, int j, const Eigen::VectorXd& y) const;
  double angleAccel(System& sys, int j, double t, const Eigen::VectorXd& y) const;
  // Torque of a resting stop pushing the joint away from it (>= 0 while the
  // contact holds), after evaluating the derivative at (t, y).
  double push(System& sys, int j, double t, const Eigen::VectorXd& y) const;
  // Rest if the joint is pushed into the stop, else leave it free; on rest
  // `accumulation` is the time the Zeno sequence would have ended (t + t_Z).
  bool restIfPushed(System& sys, int j, int side, double t, Eigen::VectorXd& y, double step, double& lost,
                    double& accumulation);

  const Model& model_;
  double angle_tol_;
  std::vector<int> joints_;  // joints with limits
  std::vector<std::vector<std::array<double, 5>>> impacts_;
  std::vector<double> release_tol_;  // per joint, set when it starts resting
};

}  // namespace fc::mbs
