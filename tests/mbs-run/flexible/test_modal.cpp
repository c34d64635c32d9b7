// Modal stiffness and damping, and gravity on a flexible body.
#include <gtest/gtest.h>

#include <cmath>

#include "common/rotations.h"
#include "mbs-run/mechanics/flexible/modal.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

TEST(Modal, DampingIsTwoZetaOmega) {
  VectorXd ev(2);
  ev << std::pow(2 * M_PI * 3.0, 2), std::pow(2 * M_PI * 50.0, 2);
  const auto p = fc::mbs::modalProperties(ev, 0.02);
  EXPECT_NEAR(p.damping(0), 2 * 0.02 * 2 * M_PI * 3.0, 1e-12);
  EXPECT_NEAR(p.damping(1), 2 * 0.02 * 2 * M_PI * 50.0, 1e-12);
  VectorXd w(2), wd(2);
  w << 0.1, -0.2;
  wd << 1.0, 2.0;
  EXPECT_NEAR(fc::mbs::strainEnergy(p, w), 0.5 * (ev(0) * 0.01 + ev(1) * 0.04), 1e-9);
  EXPECT_NEAR(fc::mbs::dissipatedPower(p, wd), p.damping(0) + 4 * p.damping(1), 1e-12);
  ev(0) = -1.0;
  EXPECT_THROW(fc::mbs::modalProperties(ev, 0.0), std::invalid_argument);
}

TEST(Modal, SingleModeFreeDecayMatchesTheDampedOscillator) {
  // A body held still with one mode: wddot + 2 zeta omega wdot + omega^2 w = 0, whose
  // solution is exp(-zeta omega t) (cos omega_d t + zeta omega / omega_d sin omega_d t).
  // Integrated with RK4 (h omega = 0.02 -> global error ~ 1e-8).
  VectorXd ev(1);
  const double omega = 2 * M_PI * 2.0, zeta = 0.05;
  ev << omega * omega;
  const auto p = fc::mbs::modalProperties(ev, zeta);
  double w = 1.0, wd = 0.0;
  const double h = 0.02 / omega;
  const int steps = static_cast<int>(std::lround(1.0 / h));
  auto acc = [&](double a, double b) {
    return -fc::mbs::elasticForces(p, VectorXd::Constant(1, a), VectorXd::Constant(1, b))(0);
  };
  for (int i = 0; i < steps; ++i) {
    const double k1w = wd, k1v = acc(w, wd);
    const double k2w = wd + 0.5 * h * k1v, k2v = acc(w + 0.5 * h * k1w, wd + 0.5 * h * k1v);
    const double k3w = wd + 0.5 * h * k2v, k3v = acc(w + 0.5 * h * k2w, wd + 0.5 * h * k2v);
    const double k4w = wd + h * k3v, k4v = acc(w + h * k3w, wd + h * k3v);
    w += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
    wd += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  const double t = steps * h, wdmp = omega * std::sqrt(1 - zeta * zeta);
  const double exact = std::exp(-zeta * omega * t) * (std::cos(wdmp * t) + zeta * omega / wdmp * std::sin(wdmp * t));
  EXPECT_NEAR(w, exact, 1e-7);
}

TEST(Modal, GravityForcesAreTheGradientOfTheGravityPotential) {
  // Q_g . v = -dV/dt along any motion (central differences, h = 1e-5: error ~1e-10).
  const int nm = 3;
  const fc::FlexBody body = fc::testing::randomBody(7, nm, 12);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const Vector3d g(0.0, -3.0, -9.81), r(1.0, 2.0, 3.0);
  const Matrix3d A = fc::expRotation(Vector3d(0.5, 0.1, -0.4));
  std::srand(3);
  const VectorXd w = 0.2 * VectorXd::Random(nm), v = VectorXd::Random(6 + nm);
  auto V = [&](double t) {
    return fc::mbs::gravityPotential(inv, r + t * v.head<3>(),
                                     A * fc::expRotation(t * Vector3d(v.segment<3>(3))),
                                     w + t * v.tail(nm), g);
  };
  const double h = 1e-5;
  const double dVdt = (V(h) - V(-h)) / (2 * h);
  const VectorXd Q = fc::mbs::gravityForces(inv, A, w, g);
  EXPECT_NEAR(Q.dot(v), -dVdt, 1e-7 * Q.norm() * v.norm());
  // and the brute-force sum of m_k g over the nodes for the translational rows.
  EXPECT_LT((Q.head<3>() - body.mass * g).norm(), 1e-12 * body.mass * g.norm());
}

}  // namespace
