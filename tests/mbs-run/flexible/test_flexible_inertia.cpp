// The invariant-based mass matrix and quadratic velocity vector against the
// brute-force sums over the lumped nodes they replace, and against the rigid body.
#include <gtest/gtest.h>

#include "common/rotations.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

using fc::testing::BruteForce;
using fc::testing::randomBody;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

struct State {
  Matrix3d A;
  VectorXd w, v;  // v = [rdot, omega', wdot]
};

State randomState(int nm, unsigned seed) {
  std::srand(seed);
  State s;
  s.A = fc::expRotation(Vector3d::Random() * 2.0);
  s.w = 0.3 * VectorXd::Random(nm);  // deformations of ~30 % of the body size: the
                                     // formulas are exact polynomials in w, not linearised
  s.v = VectorXd::Random(6 + nm);
  s.v.segment<3>(3) *= 3.0;
  return s;
}

// Hessian of the brute-force kinetic energy in v by polarisation: exact for a
// quadratic form up to round-off.
MatrixXd bruteMassMatrix(const BruteForce& bf, const Matrix3d& A, const VectorXd& w) {
  const int n = 6 + bf.nm;
  MatrixXd M(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const VectorXd ei = VectorXd::Unit(n, i), ej = VectorXd::Unit(n, j);
      M(i, j) = bf.kinetic(A, w, ei + ej) - bf.kinetic(A, w, ei) - bf.kinetic(A, w, ej);
    }
  return M;
}

TEST(FlexibleInertia, MassMatrixIsTheHessianOfTheNodalKineticEnergy) {
  const int nm = 5;
  const fc::FlexBody body = randomBody(9, nm, 11);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const BruteForce bf{body, nm};
  for (unsigned trial = 0; trial < 5; ++trial) {
    const State s = randomState(nm, 100 + trial);
    const MatrixXd M = fc::mbs::flexibleMassMatrix(inv, s.A, s.w);
    const MatrixXd Mbf = bruteMassMatrix(bf, s.A, s.w);
    // Same sums in another order: agreement to round-off (entries ~10, eps ~1e-16,
    // ~100 terms) -> 1e-12 relative.
    EXPECT_LT((M - Mbf).norm(), 1e-12 * Mbf.norm()) << "trial " << trial;
    EXPECT_NEAR(0.5 * s.v.dot(M * s.v), bf.kinetic(s.A, s.w, s.v), 1e-12 * bf.kinetic(s.A, s.w, s.v));
    EXPECT_LT((M - M.transpose()).norm(), 1e-14 * M.norm());
  }
}

TEST(FlexibleInertia, MassMatrixIsPositiveDefiniteAtLargeDeformation) {
  // All terms come from one lumped mass, so v^T M v = 2 T is a sum of squares: M
  // stays positive definite whatever w (here deformations of the body's own size).
  const int nm = 6;
  const fc::FlexBody body = randomBody(10, nm, 19);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  for (unsigned trial = 0; trial < 5; ++trial) {
    const State s = randomState(nm, 300 + trial);
    const Eigen::SelfAdjointEigenSolver<MatrixXd> es(fc::mbs::flexibleMassMatrix(inv, s.A, 3.0 * s.w));
    EXPECT_GT(es.eigenvalues().minCoeff(), 0.0) << "trial " << trial;
  }
}

TEST(FlexibleInertia, ModalMassIsIdentityForMassNormalisedModes) {
  const int nm = 4;
  const fc::FlexBody body = randomBody(7, nm, 3);
  const MatrixXd M = fc::mbs::flexibleMassMatrix(fc::computeInertiaInvariants(body),
                                                 Matrix3d::Identity(), VectorXd::Zero(nm));
  EXPECT_LT((M.bottomRightCorner(nm, nm) - MatrixXd::Identity(nm, nm)).norm(), 1e-12);
}

// Q_v from the Lagrange equations in the quasi-velocities v = [rdot, omega', wdot]
// (Boltzmann-Hamel / Kirchhoff form), with p = dT/dv taken from the brute-force T:
//   rdot:   Q = -dp_r/dt
//   omega': Q = -(dp_w/dt + omega' x p_w - dT/dpi)   (pi: body-frame virtual rotation)
//   wdot:   Q = -(dp_f/dt - dT/dw)
// with the time derivatives along the motion at vdot = 0 (A' = A omega'~, w' = wdot),
// all by central differences.
VectorXd lagrangianQv(const BruteForce& bf, const State& s) {
  const int nm = bf.nm;
  const Vector3d om = s.v.segment<3>(3);
  const VectorXd wd = s.v.tail(nm);
  auto momenta = [&](const Matrix3d& A, const VectorXd& w) { return VectorXd(bruteMassMatrix(bf, A, w) * s.v); };
  const double h = 1e-4;
  const VectorXd dp = (momenta(s.A * fc::expRotation(h * om), s.w + h * wd) -
                       momenta(s.A * fc::expRotation(-h * om), s.w - h * wd)) / (2 * h);
  const VectorXd p = momenta(s.A, s.w);
  Vector3d dTdpi;
  for (int i = 0; i < 3; ++i)
    dTdpi(i) = (bf.kinetic(s.A * fc::expRotation(h * Vector3d::Unit(i)), s.w, s.v) -
                bf.kinetic(s.A * fc::expRotation(-h * Vector3d::Unit(i)), s.w, s.v)) / (2 * h);
  VectorXd dTdw(nm);
  for (int j = 0; j < nm; ++j)
    dTdw(j) = (bf.kinetic(s.A, s.w + h * VectorXd::Unit(nm, j), s.v) -
               bf.kinetic(s.A, s.w - h * VectorXd::Unit(nm, j), s.v)) / (2 * h);
  VectorXd Q(6 + nm);
  Q.head<3>() = -dp.head<3>();
  Q.segment<3>(3) = -(dp.segment<3>(3) + om.cross(Vector3d(p.segment<3>(3))) - dTdpi);
  Q.tail(nm) = -(dp.tail(nm) - dTdw);
  return Q;
}

TEST(FlexibleInertia, QuadraticVelocityVectorMatchesTheLagrangeEquations) {
  const int nm = 4;
  const fc::FlexBody body = randomBody(8, nm, 5);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const BruteForce bf{body, nm};
  for (unsigned trial = 0; trial < 4; ++trial) {
    const State s = randomState(nm, 200 + trial);
    const auto in = fc::mbs::flexibleInertia(inv, s.A, s.w, s.v.tail(nm), s.v.segment<3>(3));
    const VectorXd ref = lagrangianQv(bf, s);
    // Central differences with h = 1e-4: truncation h^2/6 |d3p/dt3| ~ 1e-8 |Q| for
    // rates of order 1-3 1/s, round-off eps |p| / h ~ 1e-12; 1e-6 relative is a
    // hundredfold margin, while any missing or mis-signed term is O(1).
    EXPECT_LT((in.Qv - ref).norm(), 1e-6 * ref.norm()) << "trial " << trial << "\n"
                                                         << in.Qv.transpose() << "\n"
                                                         << ref.transpose();
  }
}

TEST(FlexibleInertia, QuadraticVelocityDoesNoWorkBeyondTheMassMatrixRate) {
  // Energy balance of the Lagrange equations: v^T Q_v + 1/2 v^T (dM/dt) v = 0
  // (what makes the free body conserve energy), dM/dt along the motion by differences.
  const int nm = 3;
  const fc::FlexBody body = randomBody(6, nm, 8);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const State s = randomState(nm, 9);
  const Vector3d om = s.v.segment<3>(3);
  const VectorXd wd = s.v.tail(nm);
  const double h = 1e-5;
  const MatrixXd dM = (fc::mbs::flexibleMassMatrix(inv, s.A * fc::expRotation(h * om), s.w + h * wd) -
                       fc::mbs::flexibleMassMatrix(inv, s.A * fc::expRotation(-h * om), s.w - h * wd)) /
                      (2 * h);
  const auto in = fc::mbs::flexibleInertia(inv, s.A, s.w, wd, om);
  const double power = s.v.dot(in.Qv), scale = std::abs(s.v.dot(in.Qv.cwiseAbs()));
  EXPECT_NEAR(power + 0.5 * s.v.dot(dM * s.v), 0.0, 1e-7 * scale);
}

TEST(FlexibleInertia, WithoutModesIsExactlyTheRigidBody) {
  // Rigid body with its frame origin off the centre of mass (Shabana, Dynamics of
  // Multibody Systems, sec. 3.7; Nikravesh 1988 ch. 11): J_o = J_c - m c~ c~,
  //   M = [[m I, -m A c~], [m c~ A^T, J_o]],  Q_v = [-m A w~ w~ c, -w~ J_o w].
  const double m = 7.5;
  const Vector3d c(0.3, -0.2, 0.45);
  Matrix3d Jc;
  Jc << 2.0, 0.1, -0.2, 0.1, 3.0, 0.05, -0.2, 0.05, 4.0;
  const fc::InertiaInvariants inv = fc::rigidInvariants(m, c, Jc);
  const Matrix3d A = fc::expRotation(Vector3d(0.4, -1.1, 0.7));
  const Vector3d om(1.5, -0.7, 2.2);
  const Matrix3d ct = fc::skew(c), wt = fc::skew(om);
  const Matrix3d Jo = Jc - m * ct * ct;
  MatrixXd Mref(6, 6);
  Mref << m * Matrix3d::Identity(), -m * A * ct, m * ct * A.transpose(), Jo;
  VectorXd Qref(6);
  Qref << -m * A * wt * wt * c, -wt * Jo * om;
  const auto in = fc::mbs::flexibleInertia(inv, A, VectorXd(), VectorXd(), om);
  EXPECT_LT((in.M - Mref).norm(), 1e-14 * Mref.norm());
  EXPECT_LT((in.Qv - Qref).norm(), 1e-14 * Qref.norm());
}

TEST(FlexibleInertia, ZeroModesOfAFlexibleBodyGiveItsRigidInertia) {
  // Truncating a body file's invariants to no modes must give the rigid body of the
  // same mass, centre of mass and inertia (the contract's `modes: 0`).
  const fc::FlexBody body = randomBody(10, 4, 21);
  const fc::InertiaInvariants inv0 = fc::computeInertiaInvariants(body).truncated(0);
  const Vector3d c = body.center_of_mass;
  const Matrix3d Jc = body.inertia_tensor + body.mass * fc::skew(c) * fc::skew(c);
  const fc::InertiaInvariants rigid = fc::rigidInvariants(body.mass, c, Jc);
  const Matrix3d A = fc::expRotation(Vector3d(-0.3, 0.8, 0.2));
  const Vector3d om(-0.4, 1.9, 0.6);
  const auto a = fc::mbs::flexibleInertia(inv0, A, VectorXd(), VectorXd(), om);
  const auto b = fc::mbs::flexibleInertia(rigid, A, VectorXd(), VectorXd(), om);
  EXPECT_LT((a.M - b.M).norm(), 1e-12 * b.M.norm());
  EXPECT_LT((a.Qv - b.Qv).norm(), 1e-12 * b.Qv.norm());
}

TEST(FlexibleInertia, MomentaMatchTheNodalSums) {
  const int nm = 3;
  const fc::FlexBody body = randomBody(6, nm, 4);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const BruteForce bf{body, nm};
  const State s = randomState(nm, 77);
  const Vector3d r(1.0, -2.0, 0.5);
  const Vector3d L = bf.linearMomentum(s.A, s.w, s.v), H = bf.angularMomentum(r, s.A, s.w, s.v);
  EXPECT_LT((fc::mbs::linearMomentum(inv, s.A, s.w, s.v) - L).norm(), 1e-12 * L.norm());
  EXPECT_LT((fc::mbs::angularMomentum(inv, r, s.A, s.w, s.v) - H).norm(), 1e-12 * H.norm());
}

TEST(FlexibleInertia, RejectsModalCoordinatesOfTheWrongSize) {
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(randomBody(5, 3, 1));
  EXPECT_THROW(fc::mbs::flexibleMassMatrix(inv, Matrix3d::Identity(), VectorXd::Zero(2)),
               std::invalid_argument);
}

}  // namespace
