// Element-level checks of the shell triangle: rigid-body modes, patch tests
// (constant membrane strain and constant curvature reproduced exactly), exact
// mass and inertia of the consistent and lumped mass, frame invariance.
#include <gtest/gtest.h>

#include <cmath>

#include "fe-prep/elements/shell_triangle.h"
#include "laminates.h"
#include "plate_model.h"

namespace fc::fe {
namespace {

using test::OrthoPly;

// An unsymmetric [0/45] laminate: B != 0 and anisotropic D and As, so every
// coupling term of the element is exercised.
LaminateStiffness coupledLaminate(double ply) {
  const double E2 = 10e9;
  return test::orthotropicLaminate({{15 * E2, E2, 0.5 * E2, 0.5 * E2, 0.35 * E2, 0.3, 1600, ply, 0},
                                    {15 * E2, E2, 0.5 * E2, 0.5 * E2, 0.35 * E2, 0.3, 1600, ply, 45}});
}

// A rotation taking the z = 0 plane to a general plane, so that the body-frame
// transformation is exercised.
Eigen::Matrix3d tilt() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
          Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// Six rigid motions of the nodes of `xyz` (rows), 6 DOF per node.
Eigen::Matrix<double, 18, 6> rigidModes(const Eigen::Matrix3d& xyz) {
  Eigen::Matrix<double, 18, 6> R = Eigen::Matrix<double, 18, 6>::Zero();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d x = xyz.row(i).transpose();
    for (int d = 0; d < 3; ++d) {
      R(6 * i + d, d) = 1.0;
      const Eigen::Vector3d a = Eigen::Vector3d::Unit(d);
      R.block<3, 1>(6 * i, 3 + d) = a.cross(x);
      R.block<3, 1>(6 * i + 3, 3 + d) = a;
    }
  }
  return R;
}

class ShellKinds : public ::testing::TestWithParam<ShellKind> {};

TEST_P(ShellKinds, FreeElementHasExactlySixRigidBodyModes) {
  Eigen::Matrix3d xy;
  xy << 0.0, 0.0, 0.0, 1.0, 0.2, 0.0, 0.3, 0.8, 0.0;
  const Eigen::Matrix3d xyz = xy * tilt().transpose();
  const LaminateStiffness lam = coupledLaminate(0.02);
  const ShellMatrices e = shellTriangle(xyz, lam, GetParam(), Eigen::Vector3d(1, 0.3, -0.2));
  const Eigen::Matrix<double, 18, 6> R = rigidModes(xyz);
  const double kmax = e.K.cwiseAbs().maxCoeff();
  // Rigid motions: zero strain energy up to roundoff of the 18x18 products.
  EXPECT_LT((e.K * R).cwiseAbs().maxCoeff(), 1e-11 * kmax);
  Eigen::SelfAdjointEigenSolver<Matrix18d> es(e.K);
  const auto& ev = es.eigenvalues();
  // Exactly six null modes; the smallest deformation mode (drilling, 1e-4 of a
  // bending stiffness that is itself ~(h/l)^2 = 4e-4 of the membrane) is far
  // above roundoff (1e-16 * kmax).
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev(i)), 1e-12 * ev(17)) << i;
  EXPECT_GT(ev(6), 1e-10 * ev(17));
}

// Patch of four triangles around an interior node, tilted in space. Boundary
// nodes get the exact values of a field of constant membrane strain and constant
// curvature; the interior node must reproduce the field exactly (Irons patch test;
// for DKT/DST Batoz, Bathe & Ho 1980, Batoz & Lardeur 1989).
void patchTest(ShellKind kind, const LaminateStiffness& lam, bool membrane, bool bending) {
  const Eigen::Matrix3d Q = tilt();
  std::vector<Eigen::Vector2d> p = {{0, 0}, {2.0, 0.1}, {2.2, 1.7}, {-0.1, 1.5}, {0.9, 0.7}};
  const std::vector<std::array<int, 3>> tri = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  // Local field: u = e.x (eps_x = 1e-3, eps_y = -4e-4, gamma_xy = 6e-4),
  // w = (kx x^2 + kxy x y + ky y^2)/2 with theta_x = w_,y, theta_y = -w_,x.
  const double ex = 1e-3, ey = -4e-4, gxy = 6e-4, kx = 0.02, ky = -0.013, kxy = 0.017;
  auto exact = [&](const Eigen::Vector2d& x) {
    Eigen::Matrix<double, 6, 1> l = Eigen::Matrix<double, 6, 1>::Zero();
    if (membrane) {
      l(0) = ex * x(0) + 0.5 * gxy * x(1);
      l(1) = ey * x(1) + 0.5 * gxy * x(0);
    }
    if (bending) {
      l(2) = 0.5 * (kx * x(0) * x(0) + kxy * x(0) * x(1) + ky * x(1) * x(1));
      l(3) = 0.5 * (kxy * x(0)) + ky * x(1);   // w_,y
      l(4) = -(kx * x(0) + 0.5 * kxy * x(1));  // -w_,x
    }
    Eigen::Matrix<double, 6, 1> b;
    b << Q * l.head<3>(), Q * l.tail<3>();
    return b;
  };
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(30, 30);
  for (const auto& t : tri) {
    Eigen::Matrix3d xyz;
    for (int i = 0; i < 3; ++i) xyz.row(i) = (Q * Eigen::Vector3d(p[t[i]](0), p[t[i]](1), 0)).transpose();
    const ShellMatrices e = shellTriangle(xyz, lam, kind, Q.col(0));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) K.block<6, 6>(6 * t[i], 6 * t[j]) += e.K.block<6, 6>(6 * i, 6 * j);
  }
  Eigen::VectorXd ub(24);
  for (int n = 0; n < 4; ++n) ub.segment<6>(6 * n) = exact(p[n]);
  const Eigen::Matrix<double, 6, 1> ui =
      K.block<6, 6>(24, 24).ldlt().solve(-K.block<6, 24>(24, 0) * ub);
  const Eigen::Matrix<double, 6, 1> ref = exact(p[4]);
  // The field is reproduced to roundoff: scale by its magnitude at the node.
  const double scale = std::max(ref.norm(), 1e-3);
  EXPECT_LT((ui - ref).norm(), 1e-9 * scale) << "computed " << ui.transpose() << "\nexact    "
                                             << ref.transpose();
}

// Both kinds with the fully coupled laminate (B != 0, anisotropic D and As),
// h/l ~ 0.01 (thin), and DST also with a thick one (h/l ~ 0.1) where its
// shear terms are large.
TEST_P(ShellKinds, PatchTestConstantMembraneStrain) {
  patchTest(GetParam(), coupledLaminate(0.005), true, false);
}
TEST_P(ShellKinds, PatchTestConstantCurvature) {
  patchTest(GetParam(), coupledLaminate(0.005), false, true);
}
TEST_P(ShellKinds, PatchTestCombinedWithCoupling) {
  patchTest(GetParam(), coupledLaminate(0.005), true, true);
}
TEST_P(ShellKinds, PatchTestThickCombinedWithCoupling) {
  patchTest(GetParam(), coupledLaminate(0.1), true, true);
}

INSTANTIATE_TEST_SUITE_P(Elements, ShellKinds, ::testing::Values(ShellKind::DKT, ShellKind::DST),
                         [](const auto& info) {
                           return info.param == ShellKind::DKT ? std::string("DKT")
                                                               : std::string("DST");
                         });

// Second moments of a triangle: int r r^T dA = A/12 (sum x_i x_i^T + s s^T),
// s = sum x_i (exact for linear fields; e.g. Zienkiewicz & Taylor vol. 1, app.).
Eigen::Matrix3d triangleSecondMoment(const Eigen::Matrix3d& xyz, double area) {
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d x = xyz.row(i).transpose();
    S += x * x.transpose();
    s += x;
  }
  return area / 12.0 * (S + s * s.transpose());
}

TEST(ShellMass, ConsistentMassGivesExactMassAndInertiaTensor) {
  Eigen::Matrix3d xyz;
  xyz << 0.3, -0.2, 0.5, 1.4, 0.1, 0.2, 0.2, 0.9, 1.1;
  const LaminateStiffness lam = test::isotropicPlate(70e9, 0.3, 2700, 0.01);
  const ShellMatrices e = shellTriangle(xyz, lam, ShellKind::DST, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d n =
      (xyz.row(1) - xyz.row(0)).cross(xyz.row(2) - xyz.row(0)).transpose().normalized();
  const double area =
      0.5 * (xyz.row(1) - xyz.row(0)).cross(xyz.row(2) - xyz.row(0)).norm();
  const double m = lam.mass_per_area * area;
  const Eigen::Matrix<double, 18, 6> R = rigidModes(xyz);
  const Eigen::Matrix<double, 6, 6> MR = R.transpose() * e.M * R;
  // Exact rigid-body mass matrix of the lamina (symmetric lay-up: I1 = 0):
  //   [m I, -m skew(c); m skew(c), J], J = I0 int (r.r I - r r^T) dA + I2 A (I - n n^T).
  const Eigen::Matrix3d S = triangleSecondMoment(xyz, area);
  const Eigen::Matrix3d J = lam.mass_per_area * (S.trace() * Eigen::Matrix3d::Identity() - S) +
                            lam.rotary_per_area * area * (Eigen::Matrix3d::Identity() - n * n.transpose());
  const Eigen::Vector3d c = xyz.colwise().mean().transpose();
  Eigen::Matrix3d cx;
  cx << 0, -c(2), c(1), c(2), 0, -c(0), -c(1), c(0), 0;
  Eigen::Matrix<double, 6, 6> ref;
  ref << m * Eigen::Matrix3d::Identity(), -m * cx, m * cx, J;
  EXPECT_LT((MR - ref).cwiseAbs().maxCoeff(), 1e-12 * ref.cwiseAbs().maxCoeff())
      << MR << "\n\n" << ref;
}

TEST(ShellMass, LumpedMassPreservesMassCentroidAndThicknessInertia) {
  Eigen::Matrix3d xyz;
  xyz << 0.3, -0.2, 0.5, 1.4, 0.1, 0.2, 0.2, 0.9, 1.1;
  const LaminateStiffness lam = coupledLaminate(0.004);
  const ShellMatrices e = shellTriangle(xyz, lam, ShellKind::DKT, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d nn =
      (xyz.row(1) - xyz.row(0)).cross(xyz.row(2) - xyz.row(0)).transpose();
  const double area = 0.5 * nn.norm();
  const Eigen::Vector3d n = nn.normalized();
  Eigen::Vector3d mass = Eigen::Vector3d::Zero(), rot = Eigen::Vector3d::Zero(),
                  first = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    mass += e.lumped.segment<3>(6 * i);
    rot += e.lumped.segment<3>(6 * i + 3);
    first += e.lumped(6 * i) * xyz.row(i).transpose();
  }
  const double m = lam.mass_per_area * area;
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(mass(d), m, 1e-14 * m);
    EXPECT_NEAR(rot(d), lam.rotary_per_area * area * (1 - n(d) * n(d)), 1e-14 * m);
  }
  EXPECT_LT((first - m * xyz.colwise().mean().transpose()).norm(), 1e-14 * m);
  EXPECT_TRUE((e.lumped.array() >= 0).all());
  // HRZ/row-sum equivalence: the translational row sums of the consistent mass
  // (same direction) equal the lumped nodal mass.
  for (int i = 0; i < 3; ++i)
    for (int d = 0; d < 3; ++d) {
      double row = 0;
      for (int j = 0; j < 3; ++j) row += e.M.block<3, 3>(6 * i, 6 * j).row(d).sum();
      EXPECT_NEAR(row, m / 3, 1e-13 * m);
    }
}

TEST(ShellFrame, StiffnessEigenvaluesDoNotDependOnPlacement) {
  Eigen::Matrix3d xy;
  xy << 0.0, 0.0, 0.0, 1.0, 0.2, 0.0, 0.3, 0.8, 0.0;
  const LaminateStiffness lam = coupledLaminate(0.01);
  const Eigen::Matrix3d Q = tilt();
  const ShellMatrices a = shellTriangle(xy, lam, ShellKind::DST, Eigen::Vector3d::UnitX());
  Eigen::Matrix3d moved = xy * Q.transpose();
  moved.rowwise() += Eigen::RowVector3d(5, -3, 2);
  const ShellMatrices b = shellTriangle(moved, lam, ShellKind::DST, Q.col(0));
  Eigen::SelfAdjointEigenSolver<Matrix18d> ea(a.K, Eigen::EigenvaluesOnly), eb(b.K, Eigen::EigenvaluesOnly);
  EXPECT_LT((ea.eigenvalues() - eb.eigenvalues()).cwiseAbs().maxCoeff(),
            1e-10 * ea.eigenvalues().maxCoeff());
}

// A flat mesh leaves the drilling rotations without physical stiffness; the
// drilling penalty must make the assembled free-free K singular only in the six
// rigid-body modes (paper, section 3.2), for both element kinds.
TEST(ShellAssembly, FlatFreeMeshHasOnlySixZeroEnergyModes) {
  const LaminateStiffness lam = coupledLaminate(0.01);
  const test::PlateMesh mesh = test::rectangleMesh(1.0, 0.7, 4, 3);
  for (ShellKind kind : {ShellKind::DKT, ShellKind::DST}) {
    const test::Assembled sys = test::assembleShell(mesh, lam, kind, true);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(sys.K, Eigen::EigenvaluesOnly);
    const Eigen::VectorXd& ev = es.eigenvalues();
    const double top = ev(ev.size() - 1);
    for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev(i)), 1e-11 * top) << i;
    // The softest deformation (a drilling mode, 1e-4 of a bending stiffness
    // that is ~(h/l)^2 ~ 1e-3 of the membrane one) is many decades above roundoff.
    EXPECT_GT(ev(6), 1e-10 * top);
  }
}

TEST(ShellInput, RejectsDegenerateTriangleAndNormalFibreDirection) {
  const LaminateStiffness lam = test::isotropicPlate(70e9, 0.3, 2700, 0.01);
  Eigen::Matrix3d line;
  line << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  EXPECT_THROW(shellTriangle(line, lam, ShellKind::DKT, Eigen::Vector3d::UnitX()),
               std::invalid_argument);
  Eigen::Matrix3d flat;
  flat << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  EXPECT_THROW(shellTriangle(flat, lam, ShellKind::DKT, Eigen::Vector3d::UnitZ()),
               std::invalid_argument);
  LaminateStiffness no_shear = lam;
  no_shear.As.setZero();
  EXPECT_THROW(shellTriangle(flat, no_shear, ShellKind::DST, Eigen::Vector3d::UnitX()),
               std::invalid_argument);
  EXPECT_NO_THROW(shellTriangle(flat, no_shear, ShellKind::DKT, Eigen::Vector3d::UnitX()));
}

}  // namespace
}  // namespace fc::fe
