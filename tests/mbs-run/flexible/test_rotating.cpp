// A body spinning at a prescribed constant rate: a tip mass m on a radial spring k
// at radius R from a massive hub (one constrained mode: the tip's radial motion).
// Its damped modal equation settles at the closed-form stretch of the rotating
// spring-mass, u = m omega^2 R / (k - m omega^2) (the centrifugal force m omega^2
// (R + u) balances k u). The softening it shows is right for a radial spring; for
// a beam's bending modes the same linear-mode softening is the known error that
// geometric stiffening corrects (Kane's spin-up beam), outside this formulation.
#include <gtest/gtest.h>

#include <cmath>

#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/mechanics/flexible/modal.h"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

fc::FlexBody springMass(double hub_mass, double m, double R, double k) {
  fc::FlexBody b;
  b.name = "spring_mass";
  b.nodes.resize(2, 3);
  b.nodes << 0, 0, 0, R, 0, 0;
  b.nodal_mass.resize(2, 4);
  b.nodal_mass << hub_mass, 1, 1, 1, m, 0, 0, 0;
  b.shapes = Eigen::MatrixXd::Zero(12, 1);
  b.shapes(6, 0) = 1.0 / std::sqrt(m);  // unit modal mass
  b.eigenvalues = VectorXd::Constant(1, k / m);
  b.frequencies_hz = VectorXd::Constant(1, std::sqrt(k / m) / (2 * M_PI));
  return b;
}

TEST(RotatingBody, SpringMassSettlesAtTheCentrifugalStretch) {
  const double m = 2.0, R = 1.5, k = 800.0;
  const fc::FlexBody body = springMass(50.0, m, R, k);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const auto modal = fc::mbs::modalProperties(body.eigenvalues, 0.2);
  for (double omega : {2.0, 10.0, 18.0}) {  // m omega^2 / k = 0.01, 0.25, 0.81
    const Vector3d om(0, 0, omega);
    // Prescribed spin: rdot = 0, omega' constant, so the modal row reads
    // M_ff wddot = Q_f - Lambda w - D wdot; integrated to rest with RK4.
    auto acc = [&](double w, double wd) {
      const auto in = fc::mbs::flexibleInertia(inv, Matrix3d::Identity(), VectorXd::Constant(1, w),
                                               VectorXd::Constant(1, wd), om);
      const double f = in.Qv(6) - fc::mbs::elasticForces(modal, VectorXd::Constant(1, w), VectorXd::Constant(1, wd))(0);
      return f / in.M(6, 6);
    };
    double w = 0.0, wd = 0.0;
    const double h = 0.002;  // omega_n h = 0.04
    // Modal damping D = 2 zeta omega_n = 8 1/s whatever the spin: every case is
    // underdamped and its transient decays as exp(-4 t); 10 s leaves exp(-40).
    for (int i = 0; i < 5000; ++i) {
      const double k1w = wd, k1v = acc(w, wd);
      const double k2w = wd + 0.5 * h * k1v, k2v = acc(w + 0.5 * h * k1w, wd + 0.5 * h * k1v);
      const double k3w = wd + 0.5 * h * k2v, k3v = acc(w + 0.5 * h * k2w, wd + 0.5 * h * k2v);
      const double k4w = wd + h * k3v, k4v = acc(w + h * k3w, wd + h * k3v);
      w += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
      wd += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    const double u = w / std::sqrt(m);
    const double exact = m * omega * omega * R / (k - m * omega * omega);
    // At rest the RK4 fixed point is the exact equilibrium and the transient has
    // decayed by exp(-40): what is left is round-off (1e-12 relative); 1e-10 margin.
    EXPECT_NEAR(u, exact, 1e-10 * exact) << "omega " << omega;
  }
}

}  // namespace
