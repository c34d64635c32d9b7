#pragma once
// Time integrators with error control behind one interface, so the simulation
// driver (events, output sampling, projections) does not care which is used.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fc::mbs {

using Rhs = std::function<void(double, const Eigen::VectorXd&, Eigen::VectorXd&)>;

// A state or right-hand side that went non-finite, naming what did: thrown by
// the run's guard (run/finite_guard.h) and by both formulations' starts.
class NonFiniteState : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Tolerances {
  double rtol = 1e-6;
  double atol = 1e-9;
  // Per-component weight of the error norm: 0 excludes a component (quadratures).
  Eigen::VectorXd mask;
  double max_step = 0.0;  // 0: unlimited
};

// Root-mean-square of e, each component scaled by atol + rtol max(|y0|, |y1|),
// over the components the mask keeps: the error norm both integrators control
// (Hairer, Norsett & Wanner, Solving ODEs I, eq. II.4.11).
double weightedRmsNorm(const Eigen::VectorXd& e, const Eigen::VectorXd& y0, const Eigen::VectorXd& y1,
                       const Tolerances& tol);

// Forward-difference Jacobian df/dy at (t, y), f0 = f(t, y). Column j uses
// the increment sqrt(eps) max(|y_j|, atol / rtol): relative where y_j is
// large, and otherwise at the scale below which the error norm does not look
// (atol / rtol ~ the size of a component whose absolute and relative
// tolerances weigh alike). An increment at y_j's own tiny size (1e-13 for a
// modal coordinate of 1e-5) lets the rounding of f, which the multiplier
// iteration leaves at ~1e-10 relative, swamp the column.
Eigen::MatrixXd finiteDifferenceJacobian(const Rhs& f, double t, const Eigen::VectorXd& y,
                                         const Eigen::VectorXd& f0, const Tolerances& tol);

class Integrator {
 public:
  virtual ~Integrator() = default;
  // (Re)starts at (t, y): after events the history is invalid.
  virtual void reset(double t, const Eigen::VectorXd& y) = 0;
  // Continues from (t, y), a state the caller nudged (a projection onto the
  // constraints) after the last accepted step: the derivative is renewed, the
  // step-size history kept, since the dynamics did not change.
  virtual void restart(double t, const Eigen::VectorXd& y) { reset(t, y); }
  // One accepted step, never past t_limit. False when the step size underflows.
  virtual bool step(double t_limit) = 0;
  virtual double t() const = 0;
  virtual double tPrevious() const = 0;
  virtual const Eigen::VectorXd& y() const = 0;
  // Continuous extension over the last accepted step [tPrevious, t].
  virtual Eigen::VectorXd interpolate(double t) const = 0;
  virtual std::string name() const = 0;
  // An estimate of the eigenvalue |lambda| (1/s) that holds the step at the
  // method's stability boundary, once that has persisted for several steps;
  // 0 otherwise (and for methods with no such boundary).
  virtual double stiffness() const { return 0.0; }
  long steps = 0, rejected = 0;
};

// The smallest step that still moves t by more than its rounding.
inline double minimumStep(double t) { return 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t)); }
// A starting step guess no smaller than 100 minimum steps: the guesses scale
// with |y| / |f|, which on a stiff model at rest (a milligram on a 1e12 N/m
// spring, its 1e15 m/s^2 against 1e-3 m) fall below the minimum step and
// would end the run at t = 0 as if no step could meet the error test; a
// guess too large is only rejected and shrunk.
inline double startingStep(double h_guess, double t) { return std::max(h_guess, 100.0 * minimumStep(t)); }

// The step to try from t towards t + span: the controller's h, capped by
// max_step and stretched to land exactly on the limit rather than leave a
// sliver; 0 when it falls below the round-off floor at t (the integrator gives up).
inline double nextStepSize(double h_controller, double t, double span, const Tolerances& tol) {
  const double hmin = minimumStep(t);
  double h = std::min(h_controller, span);
  if (tol.max_step > 0) h = std::min(h, tol.max_step);
  if (span - h < 0.01 * h) h = span;
  return h < hmin ? 0.0 : h;
}

// Step control shared by the third-order pairs with an embedded estimate
// (TR-BDF2, ARK3(2)4L[2]SA): the controller's factor from the error norm
// (safety 0.9, exponent -1/3, within [0.2, 5]; 0.25 when err is not finite).
inline double stepFactor3(double err) {
  return std::isfinite(err) ? std::clamp(0.9 * std::pow(std::max(err, 1e-12), -1.0 / 3.0), 0.2, 5.0) : 0.25;
}
// The step after an accepted step h. No growth right after a rejected error
// test (as DOPRI5 and RADAU5): otherwise the step oscillates about the
// accepted size, rejecting every few steps. And, as RADAU5, growth below
// 20 % is not worth a new factorisation of the iteration matrix (on the
// flexible SAR's phase 2, 650 -> 416 LU factorisations, each ~1 ms at 233
// states).
inline double stepAfterAccept(double h, double fac, bool after_rejection) {
  double next = after_rejection ? std::min(h, h * fac) : h * fac;
  if (next > h && next < 1.2 * h) next = h;
  return next;
}
// The step after a rejected step h: at most half of it.
inline double stepAfterReject(double h, double fac) { return h * std::min(fac, 0.5); }
// Cubic Hermite interpolation over [t0, t0 + h] from the end values and
// slopes (third order): the dense output of both.
inline Eigen::VectorXd cubicHermite(double t, double t0, double h, const Eigen::VectorXd& y0,
                                    const Eigen::VectorXd& f0, const Eigen::VectorXd& y1, const Eigen::VectorXd& f1) {
  const double s = (t - t0) / h, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * f0 + (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * h * f1;
}

// Dormand & Prince RK5(4)7M with Hairer's 4th-order dense output (Hairer,
// Norsett & Wanner, Solving ODEs I, sec. II.5-6, code DOPRI5), FSAL, PI step
// control (Gustafsson), explicit: for non-stiff scenes.
std::unique_ptr<Integrator> makeDormandPrince(Rhs f, const Tolerances& tol);
// TR-BDF2 (Bank et al. 1985, in the one-step form of Hosea & Shampine, Appl.
// Numer. Math. 20 (1996) 21-37): trapezoidal stage to t + gamma h then BDF2,
// gamma = 2 - sqrt(2), both with the same iteration matrix I - d h J; L-stable,
// order 2, embedded 3rd-order estimate filtered by (I - d h J)^-1 so that stiff
// components do not spoil the step control. Simplified Newton with a
// finite-difference Jacobian reused across steps. For stiff scenes. The
// iteration matrix is refactorised only when the step size has moved by more
// than 30 % since the last factorisation (or the Jacobian was renewed):
// simplified Newton still converges with a nearby h in the matrix.
std::unique_ptr<Integrator> makeTrBdf2(Rhs f, const Tolerances& tol);

// A linear part L of f in the structure of modal stiffness and damping
// (System::modalSplit): for each modal coordinate j, at state index q_j with
// its rate at v_j, (L z)[q_j] = z[v_j] and the velocity rows
// [v_offset, v_offset + response.rows()) receive
//   -sum_j response(:, j) (stiffness_j z[q_j] + damping_j z[v_j])
//   -sum_e element_response(:, e) (element_damping_e g_e^T z_v
//                                  + element_stiffness_e element_modal_gradient(:, e)^T z_q),
// the second sum over the linear force elements that act through modal
// coordinates (a rotary damper at a flexible interface): each applies
// -(k s + c s_dot) g_e along its coordinate s, s_dot = g_e^T v, and
// element_response(:, e) is the accelerations a unit generalised force g_e
// causes. Its damping is rank one over all the velocities it touches, frames
// and modes alike: the modal block c g_f g_f^T alone would leave the
// frame-mode coupling c g_r g_f^T explicit, with eigenvalues +-c sqrt(a b)
// (a, b the frame and modal shares of g^T M^-1 g), still stiff.
struct StiffModalPart {
  std::vector<int> q_index, v_index;
  int v_offset = 0;
  Eigen::VectorXd stiffness, damping;
  Eigen::MatrixXd response;
  Eigen::MatrixXd element_gradient;         // g_e over the velocity rows (response.rows() x ne)
  Eigen::MatrixXd element_modal_gradient;   // its modal entries in q_index order (modes() x ne)
  Eigen::MatrixXd element_response;         // (response.rows() x ne)
  Eigen::VectorXd element_stiffness, element_damping;  // k_e, c_e
  int modes() const { return int(q_index.size()); }
  int elements() const { return int(element_damping.size()); }
};
using StiffPart = std::function<StiffModalPart(double, const Eigen::VectorXd&)>;

// IMEX additive Runge-Kutta ARK3(2)4L[2]SA (Kennedy & Carpenter, Appl.
// Numer. Math. 44 (2003) 139-181): f = (f - L) + L with L the modal
// stiffness and damping and the linear force elements acting through them
// (StiffModalPart), L treated by the L-stable ESDIRK,
// the rest by the explicit tableau; order 3, embedded order 2. L is frozen
// over a step (and reused over many), so every stage is one structured
// linear solve (an (nm + ne) x (nm + ne) system, nm the modes, ne the
// force elements) and the split stays exact:
// accuracy never depends on how well L matches the Jacobian, only stability.
std::unique_ptr<Integrator> makeImexArk3(Rhs f, StiffPart stiff, const Tolerances& tol);
// The same split with Kennedy & Carpenter's ARK4(3)6L[2]SA (gamma = 1/4):
// order 4, embedded order 3, six stages (five evaluations and f at the end).
std::unique_ptr<Integrator> makeImexArk4(Rhs f, StiffPart stiff, const Tolerances& tol);
// `integrator: imex` (and `auto`'s implicit candidate on scenes with modes):
// ARK4(3)6L[2]SA at every tolerance. With the third-order pair at rtol 1e-4
// a latched flexible crank's 16 Hz ringing (12 steps a period) lost 0.3 % of
// its energy a period, 1.2e-3 of the run's largest energy, against 4.1e-5
// with the fourth-order pair at half the evaluations (docs/mbs-run.md, "Why
// order 4 for imex").
std::unique_ptr<Integrator> makeImex(Rhs f, StiffPart stiff, const Tolerances& tol);

}  // namespace fc::mbs
