// Interface markers: their velocity Jacobians and acceleration bias terms are the
// time derivatives of their positions and orientations (central differences along
// a motion at constant velocities), and a marker at a node moves with that node.
#include <gtest/gtest.h>

#include "common/rotations.h"
#include "mbs-run/mechanics/flexible/marker.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

struct Motion {
  Vector3d r;
  Matrix3d A;
  VectorXd w, v;
  int nm;
  // Configuration at time t for constant v: r + t rdot, A exp(t omega'~), w + t wdot.
  Vector3d r_at(double t) const { return r + t * v.head<3>(); }
  Matrix3d A_at(double t) const { return A * fc::expRotation(t * Vector3d(v.segment<3>(3))); }
  VectorXd w_at(double t) const { return w + t * v.tail(nm); }
};

Motion motion(int nm, double w_scale) {
  std::srand(17);
  return {Vector3d(0.2, 0.4, -0.1), fc::expRotation(Vector3d(0.3, -0.9, 0.5)),
          w_scale * VectorXd::Random(nm), VectorXd::Random(6 + nm) * 2.0, nm};
}

TEST(Marker, TranslationJacobianAndBiasAreTheDerivativesOfThePosition) {
  const int nm = 4;
  const fc::FlexBody body = fc::testing::randomBody(6, nm, 2);
  const fc::mbs::Marker m = fc::mbs::markerFromInterface(body.interface("P3"), nm);
  const Motion mo = motion(nm, 0.2);
  auto x = [&](double t) { return fc::mbs::markerPosition(mo.r_at(t), mo.A_at(t), m, mo.w_at(t)); };
  const double h = 1e-4;
  const Vector3d vel = (x(h) - x(-h)) / (2 * h);
  const Vector3d acc = (x(h) - 2 * x(0) + x(-h)) / (h * h);
  const Vector3d J_v = fc::mbs::markerTranslationJacobian(mo.A, m, mo.w) * mo.v;
  const Vector3d bias =
      fc::mbs::markerAccelerationBias(mo.A, m, mo.w, mo.v.tail(nm), mo.v.segment<3>(3));
  // Central first difference: error h^2/6 |x'''| ~ 1e-8 |x'''|; second difference:
  // h^2/12 |x''''| plus round-off eps |x| / h^2 ~ 1e-8 (|x| ~ 1): tolerances 1e-6.
  EXPECT_LT((vel - J_v).norm(), 1e-6 * J_v.norm());
  EXPECT_LT((acc - bias).norm(), 1e-6 * bias.norm());
}

TEST(Marker, AtANodeMovesWithTheNode) {
  const int nm = 3;
  const fc::FlexBody body = fc::testing::randomBody(6, nm, 4);
  const fc::testing::BruteForce bf{body, nm};
  const Motion mo = motion(nm, 0.3);
  const fc::mbs::Marker m = fc::mbs::markerFromInterface(body.interface("P3"), nm);
  EXPECT_LT((fc::mbs::markerLocalPosition(m, mo.w) - bf.s(3, mo.w)).norm(), 1e-14);
  EXPECT_LT((fc::mbs::markerTranslationJacobian(mo.A, m, mo.w) * mo.v - bf.velocity(3, mo.A, mo.w, mo.v)).norm(),
            1e-13);
}

TEST(Marker, RotationJacobianIsTheFrameAngularVelocityAtZeroDeformation) {
  // At w = 0 the exponential map's tangent is the identity, so J_w v is the exact
  // angular velocity of A R(Theta w) A0; away from 0 it is first order in Theta w
  // (the shared convention), checked below with a bound of |Theta w|.
  const int nm = 3;
  const fc::FlexBody body = fc::testing::randomBody(6, nm, 6);
  const Matrix3d axes = fc::expRotation(Vector3d(0.1, 0.2, -0.3));
  const fc::mbs::Marker m = fc::mbs::markerFromInterface(body.interface("P0"), nm, axes);
  for (double scale : {0.0, 1e-3}) {
    const Motion mo = motion(nm, scale);
    auto frame = [&](double t) { return fc::mbs::markerOrientation(mo.A_at(t), m, mo.w_at(t)); };
    const double h = 1e-5;
    const Vector3d omega_fd = fc::rotationVector(frame(h) * frame(-h).transpose()) / (2 * h);
    const Vector3d omega = fc::mbs::markerRotationJacobian(mo.A, m) * mo.v;
    const double first_order = (m.Theta * mo.w).norm() * omega.norm();
    EXPECT_LT((omega_fd - omega).norm(), 1e-7 * omega.norm() + first_order) << "scale " << scale;
    if (scale == 0.0) {
      // Angular acceleration bias: d/dt (J_w v) at constant v.
      auto om_at = [&](double t) {
        return Vector3d(fc::mbs::markerRotationJacobian(mo.A_at(t), m) * mo.v);
      };
      const Vector3d alpha_fd = (om_at(h) - om_at(-h)) / (2 * h);
      const Vector3d bias = fc::mbs::markerAngularAccelerationBias(mo.A, m, mo.v.tail(nm), mo.v.segment<3>(3));
      EXPECT_LT((alpha_fd - bias).norm(), 1e-7 * (1 + bias.norm()));
    }
  }
}

TEST(Marker, GeneralizedForcesDoTheWorkOfTheForce) {
  // Virtual power: f . xdot = Q^T v and n . omega_m = Q^T v for any v.
  const int nm = 4;
  const fc::FlexBody body = fc::testing::randomBody(6, nm, 9);
  const fc::mbs::Marker m = fc::mbs::markerFromInterface(body.interface("P3"), nm);
  const Motion mo = motion(nm, 0.2);
  const Vector3d f(1.0, -2.0, 0.5), n(0.3, 0.7, -1.1);
  const Vector3d xdot = fc::mbs::markerTranslationJacobian(mo.A, m, mo.w) * mo.v;
  const Vector3d om = fc::mbs::markerRotationJacobian(mo.A, m) * mo.v;
  EXPECT_NEAR(fc::mbs::markerForce(mo.A, m, mo.w, f).dot(mo.v), f.dot(xdot), 1e-12 * f.norm() * xdot.norm());
  EXPECT_NEAR(fc::mbs::markerTorque(mo.A, m, n).dot(mo.v), n.dot(om), 1e-12 * n.norm() * om.norm());
}

TEST(Marker, RigidMarkerIgnoresTheModesAndBadSizesAreRejected) {
  const fc::mbs::Marker m = fc::mbs::rigidMarker(Vector3d(1, 2, 3), 2);
  EXPECT_EQ((fc::mbs::markerLocalPosition(m, VectorXd::Ones(2)) - Vector3d(1, 2, 3)).norm(), 0.0);
  const fc::FlexBody body = fc::testing::randomBody(5, 2, 1);
  EXPECT_THROW(fc::mbs::markerFromInterface(body.interface("P0"), 3), std::invalid_argument);
  EXPECT_THROW(body.interface("nope"), std::out_of_range);
}

}  // namespace
