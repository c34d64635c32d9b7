// Beam section resultants at the element midpoint (beamMidpointResultants),
// against closed forms: the displacement fields of pure extension, pure torsion
// and pure bending give N = EA u', T = GJ theta', M = EI kappa with no shear;
// a tip-loaded Timoshenko cantilever gives V = P, M = P (L - x); rigid motions
// give nothing; and a chain of elements with a fully coupled section under a
// general end load gives, in every element, the end load carried by statics.
// The element is exact in all of these (flexibility-based, beam_flexibility.h),
// so the tolerances are roundoff: the 6x6 tip flexibility of a slender element
// spans EA L^2 / EI ~ 1e4-1e6 in scale, and its inverse loses that much of
// double precision's 1e-16, hence 1e-9 relative to the largest resultant.
#include <gtest/gtest.h>

#include <cmath>

#include "fe-prep/elements/beam_element.h"

namespace fc::fe {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Isotropic solid circle (Cowper's shear factor), as test_beam_element.cpp.
struct Section {
  double E = 70e9, nu = 0.3, d = 0.02;
  double G() const { return E / (2 * (1 + nu)); }
  double A() const { return M_PI * d * d / 4; }
  double I() const { return M_PI * std::pow(d, 4) / 64; }
  double J() const { return 2 * I(); }
  double kappa() const { return 6 * (1 + nu) / (7 + 6 * nu); }
  Matrix6d K() const {
    Matrix6d k = Matrix6d::Zero();
    k.diagonal() << E * A(), kappa() * G() * A(), kappa() * G() * A(), G() * J(), E * I(), E * I();
    return k;
  }
};

// A general element direction and section x2 hint, so the rotation to section
// axes is exercised; e1, e2, e3 the section axes it implies.
const Eigen::Vector3d kA(0.2, -0.1, 0.3);
const Eigen::Vector3d kAxis = Eigen::Vector3d(1, 2, -0.5).normalized();
const Eigen::Vector3d kX2Hint(0.3, -0.1, 1.0);
struct Axes {
  Eigen::Vector3d e1, e2, e3;
  Axes() : e1(kAxis), e2((kX2Hint - kX2Hint.dot(kAxis) * kAxis).normalized()), e3(e1.cross(e2)) {}
};

// Nodal DOF (body frame) of a field given in section axes at both ends.
Eigen::Matrix<double, 12, 1> nodal(const Vector6d& at_a_local, const Vector6d& at_b_local) {
  const Axes ax;
  Eigen::Matrix3d Rt;  // local -> body
  Rt << ax.e1, ax.e2, ax.e3;
  Eigen::Matrix<double, 12, 1> q;
  q << Rt * at_a_local.head<3>(), Rt * at_a_local.tail<3>(), Rt * at_b_local.head<3>(), Rt * at_b_local.tail<3>();
  return q;
}

Vector6d midpoint(const Matrix6d& Ks, double L, const Eigen::Matrix<double, 12, 1>& q) {
  return beamMidpointResultants(kA, kA + L * kAxis, kX2Hint, Ks) * q;
}

void expectResultants(const Vector6d& got, const Vector6d& want) {
  const double scale = want.cwiseAbs().maxCoeff();
  for (int c = 0; c < 6; ++c) EXPECT_NEAR(got(c), want(c), 1e-9 * scale) << "component " << c << "\n" << got.transpose();
}

TEST(BeamResultants, PureExtensionTorsionAndBending) {
  const Section s;
  const double L = 0.4;
  // u1 = eps x: N = EA eps.
  const double eps = 2e-4;
  Vector6d a = Vector6d::Zero(), b = Vector6d::Zero(), want = Vector6d::Zero();
  b(0) = eps * L;
  want(0) = s.E * s.A() * eps;
  expectResultants(midpoint(s.K(), L, nodal(a, b)), want);
  // theta1 = phi' x: T = GJ phi'.
  const double twist = 0.05;  // rad/m
  b.setZero();
  b(3) = twist * L;
  want.setZero();
  want(3) = s.G() * s.J() * twist;
  expectResultants(midpoint(s.K(), L, nodal(a, b)), want);
  // Bending in the x1-x2 plane at constant curvature k: u2 = k x^2 / 2,
  // theta3 = k x (no shear strain u2' - theta3): M3 = EI k, V2 = 0.
  const double k = 0.3;  // 1/m
  b.setZero();
  b(1) = 0.5 * k * L * L;
  b(5) = k * L;
  want.setZero();
  want(5) = s.E * s.I() * k;
  expectResultants(midpoint(s.K(), L, nodal(a, b)), want);
  // In the x1-x3 plane: u3 = -k x^2 / 2, theta2 = k x (u3' + theta2 = 0): M2 = EI k.
  b.setZero();
  b(2) = -0.5 * k * L * L;
  b(4) = k * L;
  want.setZero();
  want(4) = s.E * s.I() * k;
  expectResultants(midpoint(s.K(), L, nodal(a, b)), want);
  // A rigid rotation and translation on top changes nothing.
  const Eigen::Vector3d u0(1e-3, -2e-3, 5e-4), th(0.01, -0.02, 0.015);
  Eigen::Matrix<double, 12, 1> rigid;
  rigid << u0, th, u0 + th.cross(L * kAxis), th;
  expectResultants(midpoint(s.K(), L, nodal(a, b) + rigid), want);
}

TEST(BeamResultants, RigidMotionGivesNothing) {
  const Section s;
  const double L = 0.4;
  const Eigen::Vector3d u0(1e-3, -2e-3, 5e-4), th(0.01, -0.02, 0.015);
  Eigen::Matrix<double, 12, 1> q;
  q << u0, th, u0 + th.cross(L * kAxis), th;
  const Vector6d r = midpoint(s.K(), L, q);
  // Scale: the resultants the same rotation would give as a curvature over L.
  const double scale = s.E * s.I() * th.norm() / L;
  EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-9 * scale) << r.transpose();
}

TEST(BeamResultants, TipLoadedTimoshenkoCantilever) {
  // Clamped at x = 0, force P along x2 at x = L: Timoshenko's tip deflection
  // P L^3 / 3EI + P L / kGA and slope P L^2 / 2EI (Gere & Timoshenko). At the
  // midpoint V2 = P and M3 = P (L - L/2) (statics).
  const Section s;
  const double L = 0.5, P = 120.0;
  Vector6d a = Vector6d::Zero(), b = Vector6d::Zero(), want = Vector6d::Zero();
  b(1) = P * L * L * L / (3 * s.E * s.I()) + P * L / (s.kappa() * s.G() * s.A());
  b(5) = P * L * L / (2 * s.E * s.I());
  want(1) = P;
  want(5) = P * 0.5 * L;
  expectResultants(midpoint(s.K(), L, nodal(a, b)), want);
}

TEST(BeamResultants, CoupledChainCarriesTheEndLoadByStatics) {
  // Five elements, a fully coupled section, clamped at node 0, a general end
  // load [F; M] (section axes) at the tip: every element's midpoint carries
  // N, V = F and M(x) = M + (L - x) e1 x F, i.e. M2 = M2 - (L-x) F3,
  // M3 = M3 + (L-x) F2, whatever the coupling (equilibrium alone).
  Matrix6d X;
  X << 1.0, 0.2, -0.1, 0.3, 0.05, -0.2, 0.0, 0.8, 0.1, -0.2, 0.1, 0.05, 0.1, 0.0, 0.9, 0.1, -0.1, 0.2, 0.0, 0.1,
      0.0, 0.5, 0.2, 0.1, 0.2, 0.0, 0.1, 0.0, 0.7, -0.1, 0.0, 0.1, 0.0, 0.1, 0.0, 0.6;
  const Matrix6d Ks = 1e3 * (X * X.transpose() + 0.1 * Matrix6d::Identity());
  const int n = 5;
  const double L = 0.9;
  const Axes ax;
  Eigen::Matrix3d R;
  R << ax.e1.transpose(), ax.e2.transpose(), ax.e3.transpose();
  const int N = 6 * (n + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  for (int e = 0; e < n; ++e)
    K.block<12, 12>(6 * e, 6 * e) += timoshenkoBeam(kA + e * L / n * kAxis, kA + (e + 1) * L / n * kAxis, kX2Hint, Ks,
                                                    Matrix6d::Identity()).K;
  Vector6d load;
  load << 30, -5, 7, 0.4, -0.3, 0.2;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(N - 6);
  f.segment<3>(N - 12) = R.transpose() * load.head<3>();
  f.tail<3>() = R.transpose() * load.tail<3>();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(N);
  u.tail(N - 6) = K.bottomRightCorner(N - 6, N - 6).ldlt().solve(f);
  for (int e = 0; e < n; ++e) {
    const double x = (e + 0.5) * L / n;
    Vector6d want = load;
    want(4) -= (L - x) * load(2);
    want(5) += (L - x) * load(1);
    const Vector6d got =
        beamMidpointResultants(kA + e * L / n * kAxis, kA + (e + 1) * L / n * kAxis, kX2Hint, Ks) * u.segment<12>(6 * e);
    SCOPED_TRACE("element " + std::to_string(e));
    expectResultants(got, want);
  }
}

}  // namespace
}  // namespace fc::fe
