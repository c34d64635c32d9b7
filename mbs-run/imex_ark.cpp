// IMEX ARK3(2)4L[2]SA, see integrator.h for the source and the split.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "mbs-run/integrator.h"

namespace fc::mbs {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Kennedy & Carpenter (2003), Table 5 (ARK3(2)4L[2]SA): explicit ERK and
// implicit ESDIRK share c and b; bh is the embedded second-order solution.
// tests/mbs-run/test_imex_ark.cpp checks the order conditions.
constexpr double kG = 1767732205903.0 / 4055673282236.0;  // ESDIRK diagonal gamma
constexpr double kAE[4][4] = {
    {0, 0, 0, 0},
    {1767732205903.0 / 2027836641118.0, 0, 0, 0},
    {5535828885825.0 / 10492691773637.0, 788022342437.0 / 10882634858940.0, 0, 0},
    {6485989280629.0 / 16251701735622.0, -4246266847089.0 / 9704473918619.0, 10755448449292.0 / 10357097424841.0, 0}};
constexpr double kB[4] = {1471266399579.0 / 7840856788654.0, -4482444167858.0 / 7529755066697.0,
                          11266239266428.0 / 11593286722821.0, 1767732205903.0 / 4055673282236.0};
constexpr double kAI[4][4] = {{0, 0, 0, 0},
                              {kG, kG, 0, 0},
                              {2746238789719.0 / 10658868560708.0, -640167445237.0 / 6845629431997.0, kG, 0},
                              {kB[0], kB[1], kB[2], kG}};
constexpr double kBh[4] = {2756255671327.0 / 12835298489170.0, -10771552573575.0 / 22201958757719.0,
                           9247589265047.0 / 10645013368117.0, 2193209047091.0 / 5459859503100.0};
constexpr double kC[4] = {0.0, 2.0 * kG, 3.0 / 5.0, 1.0};
// Steps after which the linear part is renewed (it is also renewed after a
// rejected step): L only has to keep the explicit remainder f - L non-stiff.
constexpr int kSplitAge = 25;

class ImexArk3 final : public Integrator {
 public:
  ImexArk3(Rhs f, StiffPart stiff, const Tolerances& tol) : f_(std::move(f)), stiff_(std::move(stiff)), tol_(tol) {}

  void reset(double t, const VectorXd& y) override {
    t_ = t_old_ = t;
    y_ = y;
    y_old_ = y;
    if (tol_.mask.size() != y.size()) tol_.mask = VectorXd::Ones(y.size());
    f_(t_, y_, fn_);
    fn_old_ = fn_;
    split_age_ = kSplitAge;  // renew L
    if (h_ <= 0.0) {
      const double fn = weightedRmsNorm(fn_, y_, y_, tol_);
      h_ = fn > 1e-10 ? 0.01 / fn : 1e-4;
      if (tol_.max_step > 0) h_ = std::min(h_, tol_.max_step);
    }
    have_dense_ = false;
  }

  bool step(double t_limit) override {
    const double span = t_limit - t_;
    if (span <= 0.0) return false;
    for (;;) {
      const double h = nextStepSize(h_, t_, span, tol_);
      if (h <= 0.0) return false;
      if (split_age_ >= kSplitAge) renewSplit();
      if (h != h_lu_) factorize(h);
      // Stages: z_i = y + h sum_{j<i} (aE_ij fE_j + aI_ij fS_j) + gamma h L z_i,
      // fS_j = L z_j, fE_j = f(z_j) - L z_j.
      VectorXd z[4], fz[4], lz[4];
      z[0] = y_;
      fz[0] = fn_;
      lz[0] = applyL(z[0]);
      bool finite = true;
      for (int i = 1; i < 4 && finite; ++i) {
        VectorXd r = y_;
        for (int j = 0; j < i; ++j) r += h * (kAE[i][j] * (fz[j] - lz[j]) + kAI[i][j] * lz[j]);
        z[i] = solve(r);
        fz[i].resize(y_.size());
        f_(t_ + kC[i] * h, z[i], fz[i]);
        lz[i] = applyL(z[i]);
        finite = fz[i].allFinite();
      }
      double err = std::numeric_limits<double>::infinity();
      VectorXd y1;
      if (finite) {
        y1 = y_;
        VectorXd e = VectorXd::Zero(y_.size());
        for (int j = 0; j < 4; ++j) {
          y1 += h * kB[j] * fz[j];
          e += h * (kB[j] - kBh[j]) * fz[j];
        }
        // Filtered as TR-BDF2's (Shampine): (I - gamma h L)^-1 damps the
        // estimate in the stiff modal components the ESDIRK damps anyway.
        err = weightedRmsNorm(solve(e), y_, y1, tol_);
      }
      const double fac = stepFactor3(err);
      if (err <= 1.0) {
        VectorXd f1(y_.size());
        f_(t_ + h, y1, f1);
        t_old_ = t_;
        y_old_ = y_;
        fn_old_ = fn_;
        h_last_ = h;
        t_ = (h == span) ? t_limit : t_ + h;
        y_ = y1;
        fn_ = f1;
        have_dense_ = true;
        ++split_age_;
        h_ = stepAfterAccept(h, fac, last_rejected_);
        last_rejected_ = false;
        ++steps;
        return true;
      }
      ++rejected;
      last_rejected_ = true;
      // A stale L leaves stiff terms in the explicit part: renew it first.
      if (split_age_ > 0) split_age_ = kSplitAge;
      h_ = stepAfterReject(h, fac);
    }
  }

  double t() const override { return t_; }
  double tPrevious() const override { return t_old_; }
  const VectorXd& y() const override { return y_; }
  // Cubic Hermite from the end values and slopes (third order, as the method).
  VectorXd interpolate(double t) const override {
    if (!have_dense_ || h_last_ <= 0.0) return y_;
    return cubicHermite(t, t_old_, h_last_, y_old_, fn_old_, y_, fn_);
  }
  std::string name() const override { return "imex"; }

 private:
  void renewSplit() {
    S_ = stiff_(t_, y_);
    const int nm = S_.modes();
    Pm_.resize(nm, nm);
    for (int j = 0; j < nm; ++j) Pm_.row(j) = S_.response.row(S_.v_index[j] - S_.v_offset);
    split_age_ = 0;
    h_lu_ = -1.0;
  }

  // L z (see StiffModalPart).
  VectorXd applyL(const VectorXd& z) const {
    VectorXd out = VectorXd::Zero(z.size());
    const int nm = S_.modes();
    if (nm == 0) return out;
    VectorXd force(nm);
    for (int j = 0; j < nm; ++j) {
      out[S_.q_index[j]] = z[S_.v_index[j]];
      force[j] = S_.stiffness[j] * z[S_.q_index[j]] + S_.damping[j] * z[S_.v_index[j]];
    }
    out.segment(S_.v_offset, S_.response.rows()) -= S_.response * force;
    return out;
  }

  // (I - gamma h L) = I + P_m G on the modal rates a, G = gamma h (gamma h
  // Lambda + D): see solve().
  void factorize(double h) {
    const int nm = S_.modes();
    gh_ = kG * h;
    if (nm > 0) {
      G_ = gh_ * (gh_ * S_.stiffness + S_.damping);
      MatrixXd A = Pm_ * G_.asDiagonal();
      A.diagonal().array() += 1.0;
      lu_.compute(A);
    }
    h_lu_ = h;
  }

  // z = (I - gamma h L)^-1 r. With a the modal rates of z:
  //   z[q_j] = r[q_j] + gamma h a_j,
  //   z_v    = r_v - P (gamma h Lambda r_q + G a),
  // whose modal rows give (I + P_m G) a = r_vm - gamma h P_m Lambda r_q.
  VectorXd solve(const VectorXd& r) const {
    const int nm = S_.modes();
    if (nm == 0) return r;
    VectorXd rq(nm), rvm(nm);
    for (int j = 0; j < nm; ++j) {
      rq[j] = r[S_.q_index[j]];
      rvm[j] = r[S_.v_index[j]];
    }
    const VectorXd lr = gh_ * S_.stiffness.cwiseProduct(rq);
    const VectorXd a = lu_.solve(rvm - Pm_ * lr);
    VectorXd z = r;
    z.segment(S_.v_offset, S_.response.rows()) -= S_.response * (lr + G_.cwiseProduct(a));
    for (int j = 0; j < nm; ++j) {
      z[S_.q_index[j]] = rq[j] + gh_ * a[j];
      z[S_.v_index[j]] = a[j];
    }
    return z;
  }

  Rhs f_;
  StiffPart stiff_;
  Tolerances tol_;
  StiffModalPart S_;
  MatrixXd Pm_;
  VectorXd G_;
  Eigen::PartialPivLU<MatrixXd> lu_;
  double gh_ = 0.0, h_lu_ = -1.0;
  int split_age_ = kSplitAge;
  double t_ = 0, t_old_ = 0, h_ = 0, h_last_ = 0;
  VectorXd y_, y_old_, fn_, fn_old_;
  bool have_dense_ = false, last_rejected_ = false;
};

}  // namespace

std::unique_ptr<Integrator> makeImexArk3(Rhs f, StiffPart stiff, const Tolerances& tol) {
  return std::make_unique<ImexArk3>(std::move(f), std::move(stiff), tol);
}

}  // namespace fc::mbs
