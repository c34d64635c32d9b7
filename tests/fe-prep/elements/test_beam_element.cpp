// Beam element against closed forms: Timoshenko cantilever statics (one element
// is exact), extension-twist coupling, multi-element exactness for a fully
// coupled section, Euler-Bernoulli cantilever and Timoshenko simply supported
// frequencies, rigid-body modes, and exact mass/inertia.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "closed_forms.h"
#include "fe-prep/elements/beam_element.h"

namespace fc::fe {
namespace {

// Solid circular section, diameter d, isotropic: kappa = 6(1+nu)/(7+6nu)
// (Cowper 1966). VABS order [ext, shear2, shear3, torsion, bend2, bend3].
struct Section {
  double E = 70e9, nu = 0.3, rho = 2700, d = 0.02;
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
  Matrix6d M() const {
    Matrix6d m = Matrix6d::Zero();
    m.diagonal() << rho * A(), rho * A(), rho * A(), rho * J(), rho * I(), rho * I();
    return m;
  }
};

// Body-frame direction of a general beam, so the transformation is exercised.
const Eigen::Vector3d kAxis = Eigen::Vector3d(1, 2, -0.5).normalized();
const Eigen::Vector3d kX2Hint(0.3, -0.1, 1.0);

void localFrame(Eigen::Vector3d& e1, Eigen::Vector3d& e2, Eigen::Vector3d& e3) {
  e1 = kAxis;
  e2 = (kX2Hint - kX2Hint.dot(e1) * e1).normalized();
  e3 = e1.cross(e2);
}

// Chain of n equal elements along kAxis, clamped at node 0, loaded at the tip
// by a local-frame force/moment; returns the tip displacement in local axes.
Eigen::Matrix<double, 6, 1> cantileverTip(const Matrix6d& Ks, double L, int n,
                                          const Eigen::Matrix<double, 6, 1>& load_local) {
  Eigen::Vector3d e1, e2, e3;
  localFrame(e1, e2, e3);
  Eigen::Matrix3d R;
  R << e1.transpose(), e2.transpose(), e3.transpose();
  const int N = 6 * (n + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
  for (int e = 0; e < n; ++e) {
    const BeamMatrices b = timoshenkoBeam(e * L / n * kAxis, (e + 1) * L / n * kAxis, kX2Hint,
                                          Ks, Matrix6d::Identity());
    K.block<12, 12>(6 * e, 6 * e) += b.K;
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(N - 6);
  f.tail<3>() = R.transpose() * load_local.tail<3>();
  f.segment<3>(N - 12) = R.transpose() * load_local.head<3>();
  const Eigen::VectorXd u = K.bottomRightCorner(N - 6, N - 6).ldlt().solve(f);
  Eigen::Matrix<double, 6, 1> tip;
  tip << R * u.segment<3>(N - 12), R * u.tail<3>();
  return tip;
}

TEST(BeamStatics, OneElementCantileverIsExactTimoshenko) {
  const Section s;
  const double L = 0.5, P = 100, T = 3, N = 1e4;
  Eigen::Matrix<double, 6, 1> load;
  load << N, P, 0, T, 0, 0;
  const auto tip = cantileverTip(s.K(), L, 1, load);
  // Timoshenko: v = P L^3 / 3EI + P L / kGA, slope P L^2 / 2EI; axial N L / EA;
  // twist T L / GJ (e.g. Gere & Timoshenko, Mechanics of Materials).
  const double v = P * L * L * L / (3 * s.E * s.I()) + P * L / (s.kappa() * s.G() * s.A());
  EXPECT_NEAR(tip(1), v, 1e-10 * v);
  EXPECT_NEAR(tip(5), P * L * L / (2 * s.E * s.I()), 1e-10 * std::abs(tip(5)));
  EXPECT_NEAR(tip(0), N * L / (s.E * s.A()), 1e-10 * tip(0));
  EXPECT_NEAR(tip(3), T * L / (s.G() * s.J()), 1e-10 * tip(3));
  EXPECT_NEAR(tip(2), 0.0, 1e-12 * v);
  EXPECT_NEAR(tip(4), 0.0, 1e-12 * v);
}

TEST(BeamStatics, ExtensionTwistCouplingMatchesAnalyticFlexibility) {
  // A uniform section with extension-twist coupling g (as in a helically wound
  // tube): under end loads the section forces are constant, so the strains are
  // the compliance times the loads and u1 = L C00 N + L C03 T, th1 = L C30 N + L C33 T.
  const Section s;
  Matrix6d Ks = s.K();
  const double g = 0.6 * std::sqrt(Ks(0, 0) * Ks(3, 3));
  Ks(0, 3) = Ks(3, 0) = g;
  const Matrix6d C = Ks.inverse();
  const double L = 1.24, N = 500, T = 2;
  Eigen::Matrix<double, 6, 1> load;
  load << N, 0, 0, T, 0, 0;
  const auto tip = cantileverTip(Ks, L, 1, load);
  EXPECT_NEAR(tip(0), L * (C(0, 0) * N + C(0, 3) * T), 1e-10 * std::abs(tip(0)));
  EXPECT_NEAR(tip(3), L * (C(3, 0) * N + C(3, 3) * T), 1e-10 * std::abs(tip(3)));
  // The coupling really acts: the twist under the axial load alone.
  load << N, 0, 0, 0, 0, 0;
  EXPECT_NEAR(cantileverTip(Ks, L, 1, load)(3), L * C(3, 0) * N, 1e-10 * std::abs(L * C(3, 0) * N));
  EXPECT_LT(C(3, 0) * N, 0.0);
}

TEST(BeamStatics, FullyCoupledSectionOneElementEqualsManyElements) {
  // A flexibility-based element is exact for a uniform beam under end loads
  // whatever the coupling, so 1 element and a chain of 7 must agree.
  Matrix6d X;
  X << 1.0, 0.2, -0.1, 0.3, 0.05, -0.2, 0.0, 0.8, 0.1, -0.2, 0.1, 0.05, 0.1, 0.0, 0.9, 0.1, -0.1,
      0.2, 0.0, 0.1, 0.0, 0.5, 0.2, 0.1, 0.2, 0.0, 0.1, 0.0, 0.7, -0.1, 0.0, 0.1, 0.0, 0.1, 0.0, 0.6;
  // Stiffnesses of comparable magnitude (N, N m^2 with L ~ 1 m) keep the chain's
  // condition number ~1e3, so roundoff stays far below the 1e-10 tolerance.
  const Eigen::Vector<double, 6> scale(2.0, 1.0, 1.2, 0.5, 0.7, 0.9);
  const Matrix6d Ks =
      1e3 * scale.asDiagonal() * (X * X.transpose() + 0.1 * Matrix6d::Identity()) * scale.asDiagonal();
  Eigen::Matrix<double, 6, 1> load;
  load << 30, -5, 7, 0.4, -0.3, 0.2;
  const auto one = cantileverTip(Ks, 0.9, 1, load);
  const auto many = cantileverTip(Ks, 0.9, 7, load);
  EXPECT_LT((one - many).norm(), 1e-10 * one.norm()) << one.transpose() << "\n" << many.transpose();
}

// Dense assembly of n elements on [0, L] along kAxis.
struct BeamModel {
  Eigen::MatrixXd K, M;
};
BeamModel beamModel(const Section& s, double L, int n, bool lumped) {
  const int N = 6 * (n + 1);
  BeamModel m{Eigen::MatrixXd::Zero(N, N), Eigen::MatrixXd::Zero(N, N)};
  for (int e = 0; e < n; ++e) {
    const BeamMatrices b =
        timoshenkoBeam(e * L / n * kAxis, (e + 1) * L / n * kAxis, kX2Hint, s.K(), s.M());
    m.K.block<12, 12>(6 * e, 6 * e) += b.K;
    if (lumped)
      m.M.block<12, 12>(6 * e, 6 * e) += Eigen::MatrixXd(b.lumped.asDiagonal());
    else
      m.M.block<12, 12>(6 * e, 6 * e) += b.M;
  }
  return m;
}

// Bending frequencies in the local (x1, x2) plane: project onto the local DOF
// u2 and theta3 of the kept nodes (isotropic: that plane decouples exactly).
std::vector<double> planarFrequencies(const BeamModel& m, int n, bool clamp_first,
                                      bool pin_both, int count) {
  Eigen::Vector3d e1, e2, e3;
  localFrame(e1, e2, e3);
  std::vector<Eigen::VectorXd> basis;
  for (int i = 0; i <= n; ++i) {
    const bool end = (i == 0 || i == n);
    const bool fix_u = (clamp_first && i == 0) || (pin_both && end);
    const bool fix_t = clamp_first && i == 0;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(m.K.rows());
    if (!fix_u) {
      v.segment<3>(6 * i) = e2;
      basis.push_back(v);
      v.setZero();
    }
    if (!fix_t) {
      v.segment<3>(6 * i + 3) = e3;
      basis.push_back(v);
    }
  }
  Eigen::MatrixXd P(m.K.rows(), basis.size());
  for (size_t c = 0; c < basis.size(); ++c) P.col(c) = basis[c];
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(P.transpose() * m.K * P,
                                                              P.transpose() * m.M * P,
                                                              Eigen::EigenvaluesOnly);
  std::vector<double> w;
  for (int i = 0; i < count; ++i) w.push_back(std::sqrt(es.eigenvalues()(i)));
  return w;
}

TEST(BeamModes, SlenderCantileverMatchesEulerBernoulli) {
  // L/d = 1000 (L/r = 4000): shear and rotary inertia lower mode 3 by only
  // ~(beta r)^2 (1 + E/kG) / 2 ~ 1e-5, below the tolerances used.
  Section s;
  s.d = 0.002;
  const double L = 2.0;
  const int n = 20;
  for (bool lumped : {false, true}) {
    const auto w = planarFrequencies(beamModel(s, L, n, lumped), n, true, false, 3);
    for (int k = 0; k < 3; ++k) {
      const double bl = test::cantileverRoot(k + 1);
      const double ref = bl * bl * std::sqrt(s.E * s.I() / (s.rho * s.A() * std::pow(L, 4)));
      // Consistent mass (the exact static shapes are the cubic Hermite functions
      // here): error O(l^4), < 2e-5 at 20 elements. Lumped: O((beta l)^2),
      // 0.75 % for mode 3 (beta L = 7.85, 20 elements).
      EXPECT_NEAR(w[k] / ref, 1.0, lumped ? 1e-2 : 1e-4) << "mode " << k << " lumped " << lumped;
    }
  }
}

TEST(BeamModes, StockySimplySupportedMatchesTimoshenko) {
  // L/d = 5: shear and rotary inertia lower the first frequency by ~5 % relative
  // to Euler-Bernoulli; the element must follow Timoshenko's closed form. With
  // the constant shear strain of a two-node element the frequency error is
  // O(l^2) (measured 4.7e-5, 5.8e-4, 2.2e-3 for modes 1-3 at 24 elements), so
  // check both the error and the observed order between 24 and 48 elements.
  Section s;
  s.d = 0.1;
  const double L = 0.5;
  const auto w24 = planarFrequencies(beamModel(s, L, 24, false), 24, false, true, 3);
  const auto w48 = planarFrequencies(beamModel(s, L, 48, false), 48, false, true, 3);
  for (int k = 0; k < 3; ++k) {
    const double ref = test::timoshenkoSimplySupportedOmega(
        s.E * s.I(), s.kappa() * s.G() * s.A(), s.rho * s.A(), s.rho * s.I(), L, k + 1);
    const double e24 = w24[k] / ref - 1, e48 = w48[k] / ref - 1;
    EXPECT_LT(std::abs(e48), 1e-3) << k;
    EXPECT_NEAR(std::log2(e24 / e48), 2.0, 0.2) << k;
    const double eb = std::pow((k + 1) * M_PI / L, 2) * std::sqrt(s.E * s.I() / (s.rho * s.A()));
    if (k == 0) {
      EXPECT_LT(w48[k] / eb, 0.97);  // the shear/rotary effect is really there
    }
  }
}

TEST(BeamElement, FreeElementHasSixRigidModesAndExactMass) {
  const Section s;
  const Eigen::Vector3d xa(0.1, -0.2, 0.3), xb = xa + 0.8 * kAxis;
  const BeamMatrices b = timoshenkoBeam(xa, xb, kX2Hint, s.K(), s.M());
  Eigen::SelfAdjointEigenSolver<Matrix12d> es(b.K, Eigen::EigenvaluesOnly);
  const auto& ev = es.eigenvalues();
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev(i)), 1e-12 * ev(11)) << i;
  EXPECT_GT(ev(6), 1e-9 * ev(11));

  // Rigid motions r: r^T M r must be the exact rigid-body mass matrix of the
  // bar: m = mu L, first moment about the origin m c, and inertia
  // J = mu int (|x|^2 I - x x^T) + L R^T diag(rho J, rho I, rho I) R.
  const double L = 0.8, mu = s.rho * s.A();
  Eigen::Matrix<double, 12, 6> R = Eigen::Matrix<double, 12, 6>::Zero();
  for (int n = 0; n < 2; ++n) {
    const Eigen::Vector3d x = n == 0 ? xa : xb;
    for (int d = 0; d < 3; ++d) {
      R(6 * n + d, d) = 1;
      R.block<3, 1>(6 * n, 3 + d) = Eigen::Vector3d::Unit(d).cross(x);
      R(6 * n + 3 + d, 3 + d) = 1;
    }
  }
  const Eigen::Matrix<double, 6, 6> MR = R.transpose() * b.M * R;
  // int_0^L x x^T with x = xa + t e1: L xa xa^T + L^2/2 (xa e1^T + e1 xa^T) + L^3/3 e1 e1^T.
  const Eigen::Matrix3d S = mu * (L * xa * xa.transpose() +
                                  L * L / 2 * (xa * kAxis.transpose() + kAxis * xa.transpose()) +
                                  L * L * L / 3 * kAxis * kAxis.transpose());
  Eigen::Vector3d e1, e2, e3;
  localFrame(e1, e2, e3);
  Eigen::Matrix3d Rl;
  Rl << e1.transpose(), e2.transpose(), e3.transpose();
  const Eigen::Matrix3d J = S.trace() * Eigen::Matrix3d::Identity() - S +
                            L * Rl.transpose() * s.M().block<3, 3>(3, 3) * Rl;
  const Eigen::Vector3d c = 0.5 * (xa + xb);
  Eigen::Matrix3d cx;
  cx << 0, -c(2), c(1), c(2), 0, -c(0), -c(1), c(0), 0;
  Eigen::Matrix<double, 6, 6> ref;
  ref << mu * L * Eigen::Matrix3d::Identity(), -mu * L * cx, mu * L * cx, J;
  EXPECT_LT((MR - ref).cwiseAbs().maxCoeff(), 1e-12 * ref.cwiseAbs().maxCoeff()) << MR << "\n\n"
                                                                                  << ref;
  // Lumped: half the mass at each node, section rotary inertia L/2 each.
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(b.lumped(d) + b.lumped(6 + d), mu * L, 1e-14 * mu * L);
    EXPECT_NEAR(b.lumped(3 + d) + b.lumped(9 + d), (L * Rl.transpose() * s.M().block<3, 3>(3, 3) * Rl)(d, d),
                1e-14 * mu * L);
  }
}

TEST(BeamInput, RejectsBadGeometryAndSections) {
  const Section s;
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0);
  EXPECT_THROW(timoshenkoBeam(a, a, kX2Hint, s.K(), s.M()), std::invalid_argument);
  EXPECT_THROW(timoshenkoBeam(a, b, Eigen::Vector3d(2, 0, 0), s.K(), s.M()), std::invalid_argument);
  Matrix6d bad = s.K();
  bad(1, 1) = -1;
  EXPECT_THROW(timoshenkoBeam(a, b, kX2Hint, bad, s.M()), std::invalid_argument);
}

}  // namespace
}  // namespace fc::fe
