// The integrators on problems with exact solutions:
// - Dormand-Prince on y' = A y (a rotation plus decay): global error follows
//   the tolerance (tolerance proportionality), the dense output is accurate
//   between steps, and the step lands exactly on the requested limit;
// - TR-BDF2 on the stiff Prothero-Robinson problem y' = L (y - g(t)) + g'(t),
//   g = sin t, L = -1e6: exact y = sin t. An explicit method would need
//   ~1e6 steps for stability; TR-BDF2 takes a few hundred.
#include <gtest/gtest.h>

#include <cmath>

#include "mbs-run/integrators/integrator.h"

namespace fc::mbs {
namespace {

using Eigen::VectorXd;

void oscillator(double, const VectorXd& y, VectorXd& d) {
  d.resize(2);
  d << -0.1 * y[0] + 2.0 * y[1], -2.0 * y[0] - 0.1 * y[1];
}
VectorXd exactOscillator(double t) {
  VectorXd y(2);
  y << std::exp(-0.1 * t) * std::cos(2 * t), -std::exp(-0.1 * t) * std::sin(2 * t);
  return y;
}

double runDopri(double rtol, double* dense_err, long* steps) {
  Tolerances tol;
  tol.rtol = rtol;
  tol.atol = rtol;
  auto I = makeDormandPrince(oscillator, tol);
  I->reset(0.0, exactOscillator(0.0));
  double worst = 0, worst_dense = 0;
  while (I->t() < 10.0) {
    EXPECT_TRUE(I->step(10.0));
    worst = std::max(worst, (I->y() - exactOscillator(I->t())).norm());
    const double tm = 0.5 * (I->tPrevious() + I->t());
    worst_dense = std::max(worst_dense, (I->interpolate(tm) - exactOscillator(tm)).norm());
  }
  EXPECT_EQ(I->t(), 10.0);
  *dense_err = worst_dense;
  *steps = I->steps;
  return worst;
}

TEST(DormandPrince, ErrorFollowsTolerance) {
  double dense6, dense9;
  long s6, s9;
  const double e6 = runDopri(1e-6, &dense6, &s6), e9 = runDopri(1e-9, &dense9, &s9);
  std::printf("[   info   ] dopri5: rtol 1e-6 -> error %.2e (dense %.2e, %ld steps); 1e-9 -> %.2e (dense %.2e, %ld steps)\n",
              e6, dense6, s6, e9, dense9, s9);
  // Global error within a small multiple of the tolerance over 3 periods,
  // and shrinking with it by about the tolerance ratio (1e3).
  EXPECT_LT(e6, 1e-5);
  EXPECT_LT(e9, 1e-8);
  EXPECT_GT(e6 / e9, 100.0);
  // Fifth order: 1000x tighter tolerance costs about 1000^(1/5) ~ 4x the steps.
  EXPECT_NEAR(double(s9) / s6, std::pow(1000.0, 0.2), 1.5);
  // The continuous extension is 4th order: as accurate as the steps themselves.
  EXPECT_LT(dense6, 1e-5);
  EXPECT_LT(dense9, 1e-8);
}

// Hairer's stiffness test: on Prothero-Robinson with L = -1e4 the
// explicit steps settle at the real stability boundary of DOPRI5 (|h L| ~
// 3.3), so the eigenvalue implied by the step, 3.25 / h, is L to within the
// controller's wandering about the boundary; on the mildly damped oscillator
// (|lambda| = 2, accuracy-bound steps) nothing is reported.
TEST(DormandPrince, ReportsTheStiffnessThatHoldsItsSteps) {
  constexpr double L = -1e4;
  Rhs pr = [](double t, const VectorXd& y, VectorXd& d) {
    d.resize(1);
    d[0] = L * (y[0] - std::sin(t)) + std::cos(t);
  };
  Tolerances tol;
  tol.rtol = tol.atol = 1e-6;
  auto I = makeDormandPrince(pr, tol);
  I->reset(0.0, VectorXd::Zero(1));
  while (I->t() < 0.05) ASSERT_TRUE(I->step(0.05));
  std::printf("[   info   ] stiff: %ld steps, reported |lambda| %.3g (exact 1e4)\n", I->steps, I->stiffness());
  EXPECT_GT(I->stiffness(), 0.5e4);
  EXPECT_LT(I->stiffness(), 2e4);

  auto J = makeDormandPrince(oscillator, tol);
  J->reset(0.0, exactOscillator(0.0));
  while (J->t() < 10.0) ASSERT_TRUE(J->step(10.0));
  EXPECT_EQ(J->stiffness(), 0.0);
}

TEST(TrBdf2, StiffProtheroRobinson) {
  const double L = -1e6;
  Rhs f = [L](double t, const VectorXd& y, VectorXd& d) {
    d.resize(1);
    d[0] = L * (y[0] - std::sin(t)) + std::cos(t);
  };
  Tolerances tol;
  tol.rtol = 1e-6;
  tol.atol = 1e-8;
  auto I = makeTrBdf2(f, tol);
  VectorXd y0(1);
  y0[0] = 0.0;
  I->reset(0.0, y0);
  double worst = 0;
  while (I->t() < 5.0) {
    ASSERT_TRUE(I->step(5.0));
    worst = std::max(worst, std::abs(I->y()[0] - std::sin(I->t())));
  }
  std::printf("[   info   ] trbdf2 on Prothero-Robinson (L = -1e6): error %.2e in %ld steps (%ld rejected)\n", worst,
              I->steps, I->rejected);
  // L-stable: the stiff mode is damped at any step; the smooth solution is
  // followed to the tolerance with a step count set by accuracy alone.
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT(I->steps, 5000);
}

TEST(TrBdf2, SecondOrderOnTheOscillator) {
  auto run = [](double rtol) {
    Tolerances tol;
    tol.rtol = rtol;
    tol.atol = rtol;
    auto I = makeTrBdf2(oscillator, tol);
    I->reset(0.0, exactOscillator(0.0));
    double worst = 0;
    while (I->t() < 10.0) {
      EXPECT_TRUE(I->step(10.0));
      worst = std::max(worst, (I->y() - exactOscillator(I->t())).norm());
    }
    return std::make_pair(worst, I->steps);
  };
  const auto [e4, s4] = run(1e-4);
  const auto [e6, s6] = run(1e-6);
  std::printf("[   info   ] trbdf2 oscillator: rtol 1e-4 -> %.2e (%ld steps), 1e-6 -> %.2e (%ld steps)\n", e4, s4, e6, s6);
  // Error per step is controlled, so the global error is bounded by the sum
  // of local errors, steps x rtol (|y| <= 1); it shrinks like rtol^(2/3) for
  // a second-order method (100^(2/3) ~ 22).
  EXPECT_LT(e6, s6 * 1e-6);
  EXPECT_LT(e4, s4 * 1e-4);
  EXPECT_GT(e4 / e6, 10.0);
  // Error per step ~ h^3: 100x tighter tolerance costs ~100^(1/3) ~ 4.6x the steps.
  EXPECT_NEAR(double(s6) / s4, std::pow(100.0, 1.0 / 3.0), 1.5);
}

}  // namespace
}  // namespace fc::mbs
