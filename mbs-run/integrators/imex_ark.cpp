// IMEX additive Runge-Kutta pairs ARK3(2)4L[2]SA and ARK4(3)6L[2]SA, see
// integrator.h for the source and the split.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

#include "mbs-run/integrators/integrator.h"

namespace fc::mbs {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// An additive pair: explicit ERK (aE) and ESDIRK (aI, first stage explicit,
// constant diagonal gamma) sharing c and b; bh the embedded solution; `order`
// that of b (the controller's exponent is -1/order, bh being one lower).
// tests/mbs-run/integrators/test_integrator_correctness.cpp checks the orders (error
// ratios at fixed steps on a problem with an exact solution).
struct ArkTableau {
  int stages, order;
  double gamma;
  std::vector<std::vector<double>> aE, aI;
  std::vector<double> b, bh, c;
};

// Kennedy & Carpenter (2003), ARK3(2)4L[2]SA (their Table 5).
const ArkTableau& ark324() {
  static const ArkTableau t = [] {
    ArkTableau a;
    a.stages = 4;
    a.order = 3;
    const double g = 1767732205903.0 / 4055673282236.0;
    a.gamma = g;
    a.aE = {{0, 0, 0, 0},
            {1767732205903.0 / 2027836641118.0, 0, 0, 0},
            {5535828885825.0 / 10492691773637.0, 788022342437.0 / 10882634858940.0, 0, 0},
            {6485989280629.0 / 16251701735622.0, -4246266847089.0 / 9704473918619.0,
             10755448449292.0 / 10357097424841.0, 0}};
    a.b = {1471266399579.0 / 7840856788654.0, -4482444167858.0 / 7529755066697.0,
           11266239266428.0 / 11593286722821.0, g};
    a.aI = {{0, 0, 0, 0},
            {g, g, 0, 0},
            {2746238789719.0 / 10658868560708.0, -640167445237.0 / 6845629431997.0, g, 0},
            {a.b[0], a.b[1], a.b[2], g}};
    a.bh = {2756255671327.0 / 12835298489170.0, -10771552573575.0 / 22201958757719.0,
            9247589265047.0 / 10645013368117.0, 2193209047091.0 / 5459859503100.0};
    a.c = {0.0, 2.0 * g, 3.0 / 5.0, 1.0};
    return a;
  }();
  return t;
}

// Kennedy & Carpenter (2003), ARK4(3)6L[2]SA, gamma = 1/4, the coefficients
// as SUNDIALS ARKODE ships them (ARK436L2SA_ERK_6_3_4 / _DIRK_6_3_4).
const ArkTableau& ark436() {
  static const ArkTableau t = [] {
    ArkTableau a;
    a.stages = 6;
    a.order = 4;
    a.gamma = 0.25;
    a.aE = {{0, 0, 0, 0, 0, 0},
            {0.5, 0, 0, 0, 0, 0},
            {13861.0 / 62500.0, 6889.0 / 62500.0, 0, 0, 0, 0},
            {-116923316275.0 / 2393684061468.0, -2731218467317.0 / 15368042101831.0,
             9408046702089.0 / 11113171139209.0, 0, 0, 0},
            {-451086348788.0 / 2902428689909.0, -2682348792572.0 / 7519795681897.0,
             12662868775082.0 / 11960479115383.0, 3355817975965.0 / 11060851509271.0, 0, 0},
            {647845179188.0 / 3216320057751.0, 73281519250.0 / 8382639484533.0, 552539513391.0 / 3454668386233.0,
             3354512671639.0 / 8306763924573.0, 4040.0 / 17871.0, 0}};
    a.aI = {{0, 0, 0, 0, 0, 0},
            {0.25, 0.25, 0, 0, 0, 0},
            {8611.0 / 62500.0, -1743.0 / 31250.0, 0.25, 0, 0, 0},
            {5012029.0 / 34652500.0, -654441.0 / 2922500.0, 174375.0 / 388108.0, 0.25, 0, 0},
            {15267082809.0 / 155376265600.0, -71443401.0 / 120774400.0, 730878875.0 / 902184768.0,
             2285395.0 / 8070912.0, 0.25, 0},
            {82889.0 / 524892.0, 0, 15625.0 / 83664.0, 69875.0 / 102672.0, -2260.0 / 8211.0, 0.25}};
    a.b = {82889.0 / 524892.0, 0, 15625.0 / 83664.0, 69875.0 / 102672.0, -2260.0 / 8211.0, 0.25};
    a.bh = {4586570599.0 / 29645900160.0, 0, 178811875.0 / 945068544.0, 814220225.0 / 1159782912.0,
            -3700637.0 / 11593932.0, 61727.0 / 225920.0};
    a.c = {0.0, 0.5, 83.0 / 250.0, 31.0 / 50.0, 17.0 / 20.0, 1.0};
    return a;
  }();
  return t;
}
// Steps after which the linear part is renewed (it is also renewed after a
// rejected step): L only has to keep the explicit remainder f - L non-stiff.
constexpr int kSplitAge = 25;

class ImexArk final : public Integrator {
 public:
  ImexArk(const ArkTableau& tab, std::string name, Rhs f, StiffPart stiff, const Tolerances& tol)
      : T_(tab), name_(std::move(name)), f_(std::move(f)), stiff_(std::move(stiff)), tol_(tol) {}

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
      h_ = startingStep(fn > 1e-10 ? 0.01 / fn : 1e-4, t_);
      if (tol_.max_step > 0) h_ = std::min(h_, tol_.max_step);
    }
    have_dense_ = false;
  }

  // After a projection: the derivative is renewed; the split L, its
  // factorisation and the step control are kept (L only decides stability,
  // and renewing it is one constrained solve per mode, ~10x a step's
  // evaluations at 64 modes).
  void restart(double t, const VectorXd& y) override {
    t_ = t;
    y_ = y;
    f_(t_, y_, fn_);
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
      const int ns = T_.stages;
      z_.resize(ns);
      fz_.resize(ns);
      lz_.resize(ns);
      z_[0] = y_;
      fz_[0] = fn_;
      lz_[0] = applyL(z_[0]);
      bool finite = true;
      for (int i = 1; i < ns && finite; ++i) {
        VectorXd r = y_;
        for (int j = 0; j < i; ++j) r += h * (T_.aE[i][j] * (fz_[j] - lz_[j]) + T_.aI[i][j] * lz_[j]);
        z_[i] = solve(r);
        fz_[i].resize(y_.size());
        f_(t_ + T_.c[i] * h, z_[i], fz_[i]);
        lz_[i] = applyL(z_[i]);
        finite = fz_[i].allFinite();
      }
      double err = std::numeric_limits<double>::infinity();
      VectorXd y1;
      if (finite) {
        y1 = y_;
        VectorXd e = VectorXd::Zero(y_.size());
        for (int j = 0; j < ns; ++j) {
          y1 += h * T_.b[j] * fz_[j];
          e += h * (T_.b[j] - T_.bh[j]) * fz_[j];
        }
        // Filtered twice by (I - gamma h L)^-1 (docs/mbs-run.md, "The IMEX
        // error estimate, filtered twice"). Shampine's filter, as TR-BDF2's,
        // damps the estimate's stiff modal components, which the ESDIRK
        // damps over the next steps anyway; once, it damps them only by
        // 1 / |1 - gamma h lambda|, and where the steps sit (gamma h |lambda|
        // ~ 1 for the stiff modes of a constrained flexible body) those
        // components, absent from the global error, still set the step.
        err = weightedRmsNorm(solve(solve(e)), y_, y1, tol_);
      }
      // Safety 0.9, exponent -1/order (the embedded solution's local error
      // is O(h^order)), within [0.2, 5]; as stepFactor3 for order 3.
      const double fac = std::isfinite(err)
                             ? std::clamp(0.9 * std::pow(std::max(err, 1e-12), -1.0 / T_.order), 0.2, 5.0)
                             : 0.25;
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
  std::string name() const override { return name_; }

 private:
  void renewSplit() {
    S_ = stiff_(t_, y_);
    const int nm = S_.modes(), ne = S_.elements();
    // The rows of the stage system: the modal rates a, then the elements'
    // rates s_e = g_e^T z_v; its columns: the modal and element forces.
    Pm_.resize(nm + ne, nm + ne);
    for (int j = 0; j < nm; ++j) {
      Pm_.row(j).head(nm) = S_.response.row(S_.v_index[j] - S_.v_offset);
      if (ne) Pm_.row(j).tail(ne) = S_.element_response.row(S_.v_index[j] - S_.v_offset);
    }
    if (ne) {
      Pm_.bottomLeftCorner(ne, nm) = S_.element_gradient.transpose() * S_.response;
      Pm_.bottomRightCorner(ne, ne) = S_.element_gradient.transpose() * S_.element_response;
    }
    split_age_ = 0;
    h_lu_ = -1.0;
  }

  // L z (see StiffModalPart).
  VectorXd applyL(const VectorXd& z) const {
    VectorXd out = VectorXd::Zero(z.size());
    const int nm = S_.modes(), ne = S_.elements();
    if (nm == 0) return out;
    VectorXd force(nm), zq(nm);
    for (int j = 0; j < nm; ++j) {
      out[S_.q_index[j]] = z[S_.v_index[j]];
      zq[j] = z[S_.q_index[j]];
      force[j] = S_.stiffness[j] * zq[j] + S_.damping[j] * z[S_.v_index[j]];
    }
    auto v = out.segment(S_.v_offset, S_.response.rows());
    v -= S_.response * force;
    if (ne) {
      const VectorXd fe =
          S_.element_damping.cwiseProduct(S_.element_gradient.transpose() * z.segment(S_.v_offset, v.size())) +
          S_.element_stiffness.cwiseProduct(S_.element_modal_gradient.transpose() * zq);
      v -= S_.element_response * fe;
    }
    return out;
  }

  // (I - gamma h L) = I + gamma h P H on x = [a; s] (the modal rates and
  // the elements' rates), H the forces' dependence on x: see solve(). With
  // no elements, gamma h H = G = gamma h (gamma h Lambda + D), diagonal.
  void factorize(double h) {
    const int nm = S_.modes(), ne = S_.elements();
    gh_ = T_.gamma * h;
    if (nm > 0) {
      G_ = gh_ * (gh_ * S_.stiffness + S_.damping);
      MatrixXd A(nm + ne, nm + ne);
      A.leftCols(nm) = Pm_.leftCols(nm) * G_.asDiagonal();
      if (ne) {
        // Element force rows of gamma h H: gamma h (gamma h k_e g_qe^T a + c_e s_e).
        Ge_.resize(ne, nm);
        Ge_ = gh_ * gh_ * S_.element_stiffness.asDiagonal() * S_.element_modal_gradient.transpose();
        A.leftCols(nm) += Pm_.rightCols(ne) * Ge_;
        A.rightCols(ne) = Pm_.rightCols(ne) * (gh_ * S_.element_damping).asDiagonal();
      }
      A.diagonal().array() += 1.0;
      lu_.compute(A);
    }
    h_lu_ = h;
  }

  // z = (I - gamma h L)^-1 r. With a the modal rates of z and s the
  // elements' rates g_e^T z_v:
  //   z[q_j] = r[q_j] + gamma h a_j,
  //   z_v    = r_v - gamma h (P F_m + R F_e),
  //   F_m = Lambda z_q + D a,  F_e = k (g_q^T z_q) + c s,
  // whose modal and element rows give
  //   (I + gamma h P_x H) x = [r_vm; g^T r_v] - gamma h P_x F0,
  // F0 the forces at a = s = 0 (Lambda r_q, k g_q^T r_q).
  VectorXd solve(const VectorXd& r) const {
    const int nm = S_.modes(), ne = S_.elements();
    if (nm == 0) return r;
    VectorXd rq(nm), rx(nm + ne);
    for (int j = 0; j < nm; ++j) {
      rq[j] = r[S_.q_index[j]];
      rx[j] = r[S_.v_index[j]];
    }
    const VectorXd lr = gh_ * S_.stiffness.cwiseProduct(rq);
    VectorXd a, ue;  // ue: gamma h F_e
    VectorXd z = r;
    auto zv = z.segment(S_.v_offset, S_.response.rows());
    if (ne == 0) {
      a = lu_.solve(rx - Pm_ * lr);
    } else {
      rx.tail(ne) = S_.element_gradient.transpose() * r.segment(S_.v_offset, S_.response.rows());
      VectorXd uf0(nm + ne);
      uf0.head(nm) = lr;
      uf0.tail(ne) = gh_ * S_.element_stiffness.cwiseProduct(S_.element_modal_gradient.transpose() * rq);
      const VectorXd x = lu_.solve(rx - Pm_ * uf0);
      a = x.head(nm);
      ue = uf0.tail(ne) + Ge_ * a + gh_ * S_.element_damping.cwiseProduct(x.tail(ne));
      zv -= S_.element_response * ue;
    }
    zv -= S_.response * (lr + G_.cwiseProduct(a));
    for (int j = 0; j < nm; ++j) {
      z[S_.q_index[j]] = rq[j] + gh_ * a[j];
      z[S_.v_index[j]] = a[j];
    }
    return z;
  }

  const ArkTableau& T_;
  std::string name_;
  std::vector<VectorXd> z_, fz_, lz_;
  Rhs f_;
  StiffPart stiff_;
  Tolerances tol_;
  StiffModalPart S_;
  MatrixXd Pm_;
  VectorXd G_;
  MatrixXd Ge_;
  Eigen::PartialPivLU<MatrixXd> lu_;
  double gh_ = 0.0, h_lu_ = -1.0;
  int split_age_ = kSplitAge;
  double t_ = 0, t_old_ = 0, h_ = 0, h_last_ = 0;
  VectorXd y_, y_old_, fn_, fn_old_;
  bool have_dense_ = false, last_rejected_ = false;
};

}  // namespace

std::unique_ptr<Integrator> makeImexArk3(Rhs f, StiffPart stiff, const Tolerances& tol) {
  return std::make_unique<ImexArk>(ark324(), "imex", std::move(f), std::move(stiff), tol);
}

std::unique_ptr<Integrator> makeImexArk4(Rhs f, StiffPart stiff, const Tolerances& tol) {
  return std::make_unique<ImexArk>(ark436(), "imex", std::move(f), std::move(stiff), tol);
}

std::unique_ptr<Integrator> makeImex(Rhs f, StiffPart stiff, const Tolerances& tol) {
  return makeImexArk4(std::move(f), std::move(stiff), tol);
}

}  // namespace fc::mbs
