// TR-BDF2, see integrator.h for the sources.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "mbs-run/integrators/integrator.h"

namespace fc::mbs {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

const double kGamma = 2.0 - std::sqrt(2.0);
const double kD = kGamma / 2.0;          // diagonal coefficient of both stages
const double kW = (1.0 - kD) / 2.0;      // = sqrt(2)/4
// Third-order quadrature on the nodes 0, gamma, 1 (exact for quadratics): the
// embedded solution whose difference from the TR-BDF2 result estimates the error.
const double kB2 = 1.0 / (6.0 * kGamma * (1.0 - kGamma));
const double kB3 = 0.5 - kB2 * kGamma;
const double kB1 = 1.0 - kB2 - kB3;
// Newton contraction rate above which the Jacobian is renewed after the step.
constexpr double kThetaRenew = 0.1;

class TrBdf2 final : public Integrator {
 public:
  // Newton stops at kappa times the error tolerance, kappa as RADAU5's FNEWT
  // (Hairer & Wanner, sec. IV.8): max(10 eps / rtol, min(0.03, sqrt(rtol))).
  // The Newton error is systematic, so it accumulates step after step: with
  // a fixed 0.05 (and stage slopes from the stage relation, see newton()) a
  // flexible pendulum gained 1e-2 J in 1 000 steps at rtol 1e-4, against
  // 3e-9 J with 0.01.
  TrBdf2(Rhs f, const Tolerances& tol)
      : f_(std::move(f)),
        tol_(tol),
        kappa_(std::max(10 * std::numeric_limits<double>::epsilon() / tol.rtol, std::min(0.03, std::sqrt(tol.rtol)))) {}

  void reset(double t, const VectorXd& y) override {
    t_ = t_old_ = t;
    y_ = y;
    y_old_ = y;
    if (tol_.mask.size() != y.size()) tol_.mask = VectorXd::Ones(y.size());
    f_(t_, y_, fn_);
    fn_old_ = fn_;
    if (h_ <= 0.0) {
      const double fn = scaledNorm(fn_, y_);
      h_ = startingStep(fn > 1e-10 ? 0.01 / fn : 1e-4, t_);
      h_ = std::min(h_, tol_.max_step > 0 ? tol_.max_step : h_);
    }
    have_dense_ = false;
  }

  bool step(double t_limit) override {
    const double span = t_limit - t_;
    if (span <= 0.0) return false;
    for (;;) {
      const double h = nextStepSize(h_, t_, span, tol_);
      if (h <= 0.0) return false;
      if (!jac_valid_) computeJacobian();
      if (h_lu_ <= 0.0 || h > 1.3 * h_lu_ || h < h_lu_ / 1.3) {
        lu_.compute(MatrixXd::Identity(y_.size(), y_.size()) - kD * h * J_);
        h_lu_ = h;
      }
      theta_ = 0.0;
      // Stage 1: trapezoidal rule to t + gamma h.
      VectorXd z = y_ + kGamma * h * fn_;
      VectorXd fz;
      if (!newton(t_ + kGamma * h, y_ + kD * h * fn_, h, z, fz)) {
        if (!retry(h)) return false;
        continue;
      }
      // Stage 2: y1 = y + h (w fn + w fz + d f1).
      VectorXd y1 = y_ + h * (kW * fn_ + kW * fz + kD * fz);
      VectorXd f1;
      if (!newton(t_ + h, y_ + h * kW * (fn_ + fz), h, y1, f1)) {
        if (!retry(h)) return false;
        continue;
      }
      // The filter (I - d h' J)^-1 with the factorised h': within 30 % of h it
      // damps the stiff components as well.
      const VectorXd est = lu_.solve(h * ((kB1 - kW) * fn_ + (kB2 - kW) * fz + (kB3 - kD) * f1));
      const double err = errorNorm(est, y_, y1);
      const double fac = stepFactor3(err);
      if (err <= 1.0 && std::isfinite(err)) {
        t_old_ = t_;
        y_old_ = y_;
        fn_old_ = fn_;
        h_last_ = h;
        t_ = (h == span) ? t_limit : t_ + h;
        y_ = y1;
        fn_ = f1;
        have_dense_ = true;
        jac_fresh_ = false;  // J now belongs to an older state
        // A slow contraction means J no longer matches the state (the frame
        // of a flexible body turns, and with it every modal coupling): renew
        // it for the next step rather than wait for a Newton failure
        // (RADAU5 renews it above theta = 0.001; a Jacobian costs n
        // evaluations here, so the threshold is higher).
        if (theta_ > kThetaRenew) jac_valid_ = false;
        h_ = stepAfterAccept(h, fac, last_rejected_);
        last_rejected_ = false;
        ++steps;
        return true;
      }
      ++rejected;
      last_rejected_ = true;
      h_ = stepAfterReject(h, fac);
    }
  }

  double t() const override { return t_; }
  double tPrevious() const override { return t_old_; }
  const VectorXd& y() const override { return y_; }
  // Cubic Hermite interpolation from the end values and slopes (third order,
  // above the method's second).
  VectorXd interpolate(double t) const override {
    if (!have_dense_ || h_last_ <= 0.0) return y_;
    return cubicHermite(t, t_old_, h_last_, y_old_, fn_old_, y_, fn_);
  }
  std::string name() const override { return "trbdf2"; }

 private:
  // Solves x - d h f(t, x) = rhs by simplified Newton with the factorised
  // iteration matrix (I - d h' J, h' within 30 % of h); x holds the predictor.
  // Stops when the error left, estimated from the observed contraction rate
  // theta as theta / (1 - theta) |dx|, is below kappa times the error
  // tolerance, and gives up as soon as the iteration does not contract
  // (Hairer & Wanner, Solving ODEs II, sec. IV.8, as in RADAU5). On return
  // fx = f(t, x), evaluated at the converged stage. Not the cheaper stage
  // relation (x - rhs) / (d h): that slope is consistent with whatever x is,
  // so the Newton error enters the step amplified by 1 / (d h) and neither
  // the error estimate nor the next step sees it; it is a fixed linear map
  // of the predictor's error (simplified Newton stops after one or two
  // corrections), so it acts as a change of the method, not as noise. On a
  // clamped-root beam on a hinge that changed method was
  // unstable on the frame-mode motion at 1.3e4-1.8e4 rad/s: at rtol 1e-4 the
  // energy grew at that rate from the first millisecond (accepted steps,
  // error estimates below 1), at rtol 1e-6 after 0.47 s (tip 2.2 mm off a
  // 5.3 mm deflection, "completed"). With f(t, x) the slopes are the
  // stage's own, the estimate sees an unconverged stage, and both runs
  // stay on Dormand-Prince's reference (docs/mbs-run.md).
  bool newton(double t, const VectorXd& rhs, double h, VectorXd& x, VectorXd& fx) {
    const double kappa = kappa_;
    constexpr int kMaxIterations = 7;
    double prev = 0.0, theta = 0.0;
    fx.resize(x.size());
    for (int it = 0; it < kMaxIterations; ++it) {
      f_(t, x, fx);
      const VectorXd dx = lu_.solve(rhs + kD * h * fx - x);
      x += dx;
      const double nrm = scaledNorm(dx, x);
      if (!std::isfinite(nrm)) return false;
      if (it == 0) {
        // No contraction rate is known after one correction, and none may be
        // borrowed from an earlier solve: a stale Jacobian or a new
        // configuration changes it (a 16-mode pendulum ended
        // "completed" 9.9 m off).
        // One correction suffices only when it is already at rounding level.
        if (nrm < 1e-3 * kappa) {
          f_(t, x, fx);
          return true;
        }
        prev = nrm;
        continue;
      }
      theta = nrm / prev;
      if (theta >= 0.9) return false;  // diverging or too slow
      // Error left after this iteration (geometric series of the contraction),
      // and the give-up test of RADAU5: if even the remaining iterations at
      // this rate cannot reach kappa, stop now and retry with a new Jacobian.
      const double left = theta / (1.0 - theta) * nrm;
      if (left <= kappa) {
        theta_ = std::max(theta_, theta);
        f_(t, x, fx);
        return true;
      }
      if (std::pow(theta, kMaxIterations - 1 - it) / (1.0 - theta) * nrm > kappa) return false;
      prev = nrm;
    }
    return false;
  }

  bool retry(double h) {
    ++rejected;
    if (!jac_fresh_) {
      jac_valid_ = false;  // a stale Jacobian is the usual culprit
    } else {
      h_ = 0.5 * h;
    }
    h_lu_ = -1.0;
    return h > 1e-14;
  }

  void computeJacobian() {
    J_ = finiteDifferenceJacobian(f_, t_, y_, fn_, tol_);
    jac_valid_ = true;
    jac_fresh_ = true;
    h_lu_ = -1.0;
  }

  double scaledNorm(const VectorXd& e, const VectorXd& y) const { return weightedRmsNorm(e, y, y, tol_); }
  double errorNorm(const VectorXd& e, const VectorXd& y0, const VectorXd& y1) const {
    return weightedRmsNorm(e, y0, y1, tol_);
  }

  Rhs f_;
  Tolerances tol_;
  double kappa_;
  double t_ = 0, t_old_ = 0, h_ = 0, h_last_ = 0, h_lu_ = -1.0;
  VectorXd y_, y_old_, fn_, fn_old_;
  MatrixXd J_;
  Eigen::PartialPivLU<MatrixXd> lu_;
  double theta_ = 0.0;  // slowest contraction rate of the current step's Newton solves
  bool jac_valid_ = false, jac_fresh_ = false, have_dense_ = false;
  bool last_rejected_ = false;
};

}  // namespace

std::unique_ptr<Integrator> makeTrBdf2(Rhs f, const Tolerances& tol) {
  return std::make_unique<TrBdf2>(std::move(f), tol);
}

}  // namespace fc::mbs
