// The augmented Lagrangian solve against the exact constrained solution from a
// dense KKT system, [M Phi^T; Phi 0] [x; lambda] = [Q; -s], for well-posed,
// redundant (repeated and linearly dependent rows) and badly scaled cases.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "beam_body.h"
#include "common/rotations.h"
#include "mbs-run/constrained/augmented_lagrangian.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"

namespace fc::mbs {
namespace {

struct Case {
  Eigen::MatrixXd M, Phi;
  Eigen::VectorXd Q, s;
};

Case makeCase(int n, int m, bool redundant, double mass_spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Case c;
  Eigen::MatrixXd B(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) B(i, j) = u(rng);
  // SPD mass matrix with eigenvalues spread over `mass_spread` decades.
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(B);
  const Eigen::MatrixXd Qm = qr.householderQ();
  Eigen::VectorXd ev(n);
  for (int i = 0; i < n; ++i) ev[i] = std::pow(10.0, -mass_spread * i / (n - 1));
  c.M = Qm * ev.asDiagonal() * Qm.transpose();
  c.Phi.resize(m, n);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) c.Phi(i, j) = u(rng);
  c.Q.resize(n);
  c.s.resize(m);
  for (int i = 0; i < n; ++i) c.Q[i] = u(rng);
  for (int i = 0; i < m; ++i) c.s[i] = u(rng);
  if (redundant) {
    // Row m-1 repeats row 0 and row m-2 is a combination of rows 1 and 2; the
    // right-hand sides are made consistent.
    c.Phi.row(m - 1) = c.Phi.row(0);
    c.s[m - 1] = c.s[0];
    c.Phi.row(m - 2) = 0.3 * c.Phi.row(1) - 2.0 * c.Phi.row(2);
    c.s[m - 2] = 0.3 * c.s[1] - 2.0 * c.s[2];
  }
  return c;
}

// Exact solution on the independent rows (rank-revealing QR of Phi^T picks them).
Eigen::VectorXd exactSolution(const Case& c) {
  const int n = c.M.rows();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(c.Phi.transpose());
  const int r = qr.rank();
  Eigen::MatrixXd P(r, n);
  Eigen::VectorXd s(r);
  for (int k = 0; k < r; ++k) {
    P.row(k) = c.Phi.row(qr.colsPermutation().indices()[k]);
    s[k] = c.s[qr.colsPermutation().indices()[k]];
  }
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + r, n + r);
  K.topLeftCorner(n, n) = c.M;
  K.topRightCorner(n, r) = P.transpose();
  K.bottomLeftCorner(r, n) = P;
  Eigen::VectorXd b(n + r);
  b << c.Q, -s;
  return K.fullPivLu().solve(b).head(n);
}

void check(const Case& c, double penalty, const char* label, AlMethod method) {
  const SparseMatrixd M = c.M.sparseView(), Phi = c.Phi.sparseView();
  AlSolver solver;
  solver.setMethod(method);
  solver.factorize(M, Phi, penalty);
  ASSERT_TRUE(solver.ok());
  ASSERT_EQ(solver.methodUsed(), method);
  const AlResult r = solver.accelerations(c.Q, c.s, 1e-12, 50);
  const Eigen::VectorXd x = exactSolution(c);
  const double err = (r.vdot - x).norm() / x.norm();
  std::printf("[   info   ] %s: relative error %.2e after %d iterations, residual %.2e\n", label, err,
              r.iterations, r.residual);
  // The iteration stops at the rounding level of the factorised matrix; 1e-9
  // leaves room for its conditioning (penalty x mass spread ~1e9 here).
  EXPECT_LT(err, 1e-9);
  EXPECT_LT(r.residual, 1e-10);
  // The multipliers reproduce the applied-minus-inertia force: M x = Q - Phi^T lambda.
  // lambda carries the rounding of Phi x + s amplified by the penalty, so the
  // bound is (a few hundred) eps * penalty * |Phi|^2 * |x|: inherent to any
  // penalty-based multiplier, and why reactions are reported, not iterated on.
  const double force_res = (c.M * r.vdot - c.Q + c.Phi.transpose() * r.lambda).norm();
  const double bound = 300 * 2.2e-16 * penalty * c.Phi.squaredNorm() * r.vdot.lpNorm<Eigen::Infinity>();
  std::printf("[   info   ] %s: force residual %.2e (bound %.2e)\n", label, force_res, bound);
  EXPECT_LT(force_res, bound);
}

// Both ways of applying (M + a Phi^T Phi)^-1 (block Schur complement and
// sparse LDL^T) must give the same constrained solution.
class AugmentedLagrangian : public ::testing::TestWithParam<AlMethod> {};

TEST_P(AugmentedLagrangian, MatchesKktSolution) {
  check(makeCase(12, 5, false, 1.0, 1), 1e6, "independent rows", GetParam());
}
TEST_P(AugmentedLagrangian, RedundantRowsDoNotMatter) {
  check(makeCase(12, 7, true, 1.0, 2), 1e6, "redundant rows", GetParam());
}
TEST_P(AugmentedLagrangian, BadlyScaledMasses) {
  // Six decades between the heaviest and lightest directions, like a panel
  // and the axial inertia of a thin truss.
  check(makeCase(12, 7, true, 6.0, 3), 1e6, "mass spread 1e6", GetParam());
}

// A body-ordered block-diagonal M (three bodies of 6, 8 and 4 coordinates)
// with constraint rows each touching one or two bodies, as the engine builds
// it: the Schur path works block by block and must still match the KKT
// solution, redundant rows and a wide mass spread included.
TEST_P(AugmentedLagrangian, BlockDiagonalMassAsBodiesGiveIt) {
  Case c = makeCase(18, 9, true, 5.0, 7);
  const int off[4] = {0, 6, 14, 18};
  Eigen::MatrixXd Mb = Eigen::MatrixXd::Zero(18, 18);
  for (int b = 0; b < 3; ++b) {
    const int n = off[b + 1] - off[b];
    Mb.block(off[b], off[b], n, n) = c.M.block(off[b], off[b], n, n);
  }
  c.M = Mb;  // principal blocks of an SPD matrix are SPD
  for (int i = 0; i < c.Phi.rows(); ++i) {
    const int keep = i % 3;  // rows touch bodies {keep, keep+1 mod 3}
    for (int b = 0; b < 3; ++b)
      if (b != keep && b != (keep + 1) % 3) c.Phi.block(i, off[b], 1, off[b + 1] - off[b]).setZero();
  }
  c.Phi.row(c.Phi.rows() - 1) = c.Phi.row(0);  // keep one exact duplicate
  c.s[c.Phi.rows() - 1] = c.s[0];
  c.Phi.row(c.Phi.rows() - 2).setZero();
  c.s[c.Phi.rows() - 2] = 0.0;
  const BlockDiagonal D = BlockDiagonal::fromSparse(c.M.sparseView());
  ASSERT_EQ(D.block.size(), 3u);
  EXPECT_EQ(D.offset[1], 6);
  EXPECT_EQ(D.offset[2], 14);
  check(c, 1e6, "block-diagonal M", GetParam());
}

INSTANTIATE_TEST_SUITE_P(Methods, AugmentedLagrangian,
                         ::testing::Values(AlMethod::BlockSchur, AlMethod::SparseSchur, AlMethod::SparseLdlt),
                         [](const ::testing::TestParamInfo<AlMethod>& i) {
                           return i.param == AlMethod::BlockSchur    ? "BlockSchur"
                                  : i.param == AlMethod::SparseSchur ? "SparseSchur"
                                                                     : "SparseLdlt";
                         });

// A body whose own mass block is singular (a point mass carried by
// rotational coordinates it does not have) still gives a definite K when the
// constraints hold the missing directions: the Schur path cannot invert that
// block, so the automatic choice must fall back to the sparse LDL^T.
TEST(AugmentedLagrangianFallback, SingularBodyBlockFallsBackToSparse) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(4, 4);
  M(3, 3) = 0.0;  // no inertia in coordinate 3
  Eigen::MatrixXd Phi(1, 4);
  Phi << 0, 0, 1, 1;  // coordinate 3 tied to coordinate 2
  AlSolver solver;
  solver.factorize(SparseMatrixd(M.sparseView()), SparseMatrixd(Phi.sparseView()), 1e6);
  ASSERT_TRUE(solver.ok());
  EXPECT_EQ(solver.methodUsed(), AlMethod::SparseLdlt);
  Eigen::VectorXd Q(4), s(1);
  Q << 1, 2, 3, 0;
  s << 0.0;
  const AlResult r = solver.accelerations(Q, s, 1e-12, 50);
  // Exact: x2 = Q2 - lambda and 0 * x3 = Q3 - lambda give lambda = 0, so
  // x2 = 3 and, from x2 + x3 = 0, x3 = -3. 1e-6: the massless coordinate is
  // fixed by the penalty alone, to about |x| / a per multiplier pass.
  EXPECT_NEAR(r.vdot[0], 1.0, 1e-9);
  EXPECT_NEAR(r.vdot[1], 2.0, 1e-9);
  EXPECT_NEAR(r.vdot[2], 3.0, 1e-6);
  EXPECT_NEAR(r.vdot[3], -3.0, 1e-6);
}

// The automatic choice: block Schur with a dense S up to kMaxDenseSchurRows
// rows, with a sparse S above (a dense m x m factorisation costs m^3/3
// whatever the sparsity).
TEST(AugmentedLagrangianFallback, ManyRowsUseTheSparseFactorisation) {
  for (int m : {AlSolver::kMaxDenseSchurRows, AlSolver::kMaxDenseSchurRows + 1}) {
    const int n = 2 * m;
    const SparseMatrixd M = Eigen::MatrixXd::Identity(n, n).sparseView();
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(m, n);
    for (int i = 0; i < m; ++i) {
      P(i, 2 * i) = 1.0;
      P(i, 2 * i + 1) = -1.0;
    }
    AlSolver solver;
    solver.factorize(M, SparseMatrixd(P.sparseView()), 1e6);
    ASSERT_TRUE(solver.ok());
    EXPECT_EQ(solver.methodUsed(), m <= AlSolver::kMaxDenseSchurRows ? AlMethod::BlockSchur : AlMethod::SparseSchur);
    // x_{2i} - x_{2i+1} = 0 under Q = e_{2i}: both move at 1/2.
    const AlResult r = solver.accelerations(Eigen::VectorXd::Unit(n, 0), Eigen::VectorXd::Zero(m), 1e-12, 50);
    EXPECT_NEAR(r.vdot[0], 0.5, 1e-12);
    EXPECT_NEAR(r.vdot[1], 0.5, 1e-12);
  }
}

TEST(AugmentedLagrangianProjection, VelocityProjectionIsMassOrthogonal) {
  const Case c = makeCase(10, 4, true, 2.0, 4);
  const SparseMatrixd M = c.M.sparseView(), Phi = c.Phi.sparseView();
  AlSolver solver;
  solver.factorize(M, Phi, 1e6);
  Eigen::VectorXd v0 = c.Q;
  const Eigen::VectorXd phit = Eigen::VectorXd::Zero(c.Phi.rows());
  const Eigen::VectorXd v = solver.projectVelocities(v0, phit, 1e-13, 50);
  EXPECT_LT((c.Phi * v).norm(), 1e-11);
  // Mass-orthogonality: M (v - v0) lies in the range of Phi^T, so it is
  // M-orthogonal to every admissible velocity (null space of Phi).
  Eigen::FullPivLU<Eigen::MatrixXd> lu(c.Phi);
  const Eigen::MatrixXd N = lu.kernel();
  EXPECT_LT((N.transpose() * c.M * (v - v0)).norm(), 1e-10 * v0.norm());
}

}  // namespace
}  // namespace fc::mbs

namespace fc::mbs {
namespace {

// a floating-frame flexible body with mass-normalised modes has an
// arrow mass block (six rigid rows, a diagonal modal block), which the solver
// factorises in O(modes) by a Schur complement on the rigid 6 x 6 block
// (BlockFactor). On a random state of a 60-mode beam with a rigid body
// beside it and joint-like rows coupling them, the arrow path must give the
// accelerations and multipliers of the dense block (an ordinary Cholesky of
// the whole (6 + nm)^2 block) and of the KKT system to rounding.
TEST(AugmentedLagrangianArrow, FlexibleBodyArrowBlockMatchesDenseBlock) {
  test::BeamSpec spec;
  spec.elements = 40;
  spec.modes = 60;
  spec.pinned_root = true;
  const test::BeamModel bm = test::cantileverBeam(spec);
  const InertiaInvariants inv = computeInertiaInvariants(bm.body, spec.modes);
  const int nm = spec.modes, nf = 6 + nm, n = nf + 6, m = 9;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random = [&](int k, double scale) {
    Eigen::VectorXd v(k);
    for (int i = 0; i < k; ++i) v[i] = scale * u(rng);
    return v;
  };
  const Eigen::Vector4d p = Eigen::Vector4d(random(4, 1.0)).normalized();
  const Eigen::Matrix3d A = fc::rotationMatrix(p);
  // Deflections of a few cm and rates of order 1: the w-dependent terms of
  // the coupling rows are then far above rounding.
  const Eigen::VectorXd w = random(nm, 0.02), wd = random(nm, 1.0);
  const Eigen::Vector3d om = random(3, 2.0);
  const FlexibleInertia dense = flexibleInertia(inv, A, w, wd, om);
  const FlexibleInertiaRows rows = flexibleInertiaRows(inv, A, w, wd, om);
  const Eigen::MatrixXd Mff = inv.modalMass();
  Eigen::MatrixXd off = Mff;
  off.diagonal().setZero();
  ASSERT_LT(off.cwiseAbs().maxCoeff(), 1e-12);  // mass-normalised modes: the arrow form applies
  ASSERT_LT((rows.top - dense.M.topRows(6)).cwiseAbs().maxCoeff(), 1e-14 * dense.M.cwiseAbs().maxCoeff());
  ASSERT_LT((rows.Qv - dense.Qv).cwiseAbs().maxCoeff(), 1e-14 * (1 + dense.Qv.cwiseAbs().maxCoeff()));

  Eigen::MatrixXd rigid = Eigen::MatrixXd::Identity(6, 6);
  rigid.bottomRightCorner(3, 3) << 0.2, 0.01, 0, 0.01, 0.3, 0, 0, 0, 0.1;
  BlockDiagonal Md, Ma;
  Md.size = Ma.size = n;
  Md.offset = Ma.offset = {0, nf};
  Md.block = {dense.M, rigid};
  Md.diagonal = {Eigen::VectorXd(), Eigen::VectorXd()};
  Ma.block = {rows.top, rigid};
  Ma.diagonal = {Mff.diagonal(), Eigen::VectorXd()};
  ASSERT_LT((Ma.dense(0) - dense.M).cwiseAbs().maxCoeff(), 1e-14);
  // Rows as joints make them: each touches the rigid coordinates of both
  // bodies and the flexible body's modal columns (interface shapes).
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(m, n);
  for (int i = 0; i < m; ++i) {
    Phi.row(i).head(6) = random(6, 1.0).transpose();
    Phi.row(i).segment(6, nm) = random(nm, 0.3).transpose();
    Phi.row(i).tail(6) = random(6, 1.0).transpose();
  }
  const Eigen::VectorXd Q = random(n, 5.0), stab = random(m, 1.0);
  const SparseMatrixd Phis = Phi.sparseView();
  AlSolver sd, sa;
  sd.setMethod(AlMethod::BlockSchur);
  sa.setMethod(AlMethod::BlockSchur);
  sd.factorize(Md, Phis, 1e6);
  sa.factorize(Ma, Phis, 1e6);
  ASSERT_TRUE(sd.ok() && sa.ok());
  const AlResult rd = sd.accelerations(Q, stab, 1e-12, 50), ra = sa.accelerations(Q, stab, 1e-12, 50);
  Case c{Eigen::MatrixXd(), Phi, Q, stab};
  c.M = Eigen::MatrixXd::Zero(n, n);
  c.M.topLeftCorner(nf, nf) = dense.M;
  c.M.bottomRightCorner(6, 6) = rigid;
  const Eigen::VectorXd x = exactSolution(c);
  const double e_dense = (ra.vdot - rd.vdot).norm() / rd.vdot.norm();
  const double e_kkt = (ra.vdot - x).norm() / x.norm();
  const double e_lambda = (ra.lambda - rd.lambda).norm() / rd.lambda.norm();
  std::printf("[   info   ] arrow vs dense block: accelerations %.2e, multipliers %.2e; vs KKT %.2e\n", e_dense,
              e_lambda, e_kkt);
  // Both paths converge the multiplier iteration to rounding (correction
  // below 1e-13 relative); what is left is the rounding of two different
  // factorisations of the same matrix, amplified by its conditioning
  // (modal masses 1, rigid inertias 0.1, penalty 1e6): well below 1e-10.
  EXPECT_LT(e_dense, 1e-10);
  EXPECT_LT(e_lambda, 1e-10);
  EXPECT_LT(e_kkt, 1e-9);  // as check() above
  // The structured product M x equals the dense one.
  Eigen::VectorXd yd, ya;
  Md.multiply(x, yd);
  Ma.multiply(x, ya);
  EXPECT_LT((ya - yd).norm(), 1e-13 * yd.norm());
  // And the sparse form carries the whole block (less the modal block's
  // off-diagonal rounding, below 1e-12 as asserted above).
  EXPECT_LT((Eigen::MatrixXd(Ma.toSparse()) - c.M).cwiseAbs().maxCoeff(), 1e-12);
}

// A modal mass block that is constant but not diagonal (modes orthonormal only
// to the eigensolver's precision: fe-prep's 64-mode steel bar has 2.3e-10
// off the diagonal; here 5e-2, far above rounding, so a dropped or misplaced
// entry would show) is kept in the arrow form with that block factorised
// once (ConstantBlock). Same checks as above: the accelerations and
// multipliers of the dense block's Cholesky, and the KKT solution.
TEST(AugmentedLagrangianArrow, ConstantDenseModalBlockMatchesDenseBlock) {
  const int nm = 24, nf = 6 + nm, n = nf + 6, m = 9;
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random = [&](int k, double scale) {
    Eigen::VectorXd v(k);
    for (int i = 0; i < k; ++i) v[i] = scale * u(rng);
    return v;
  };
  // A rigid-like 6 x 6 leading block, coupling rows of order 0.3, and
  // D = I + 0.05 (R + R^T) / 2: symmetric, definite, dense.
  Eigen::MatrixXd R(nm, nm);
  for (int j = 0; j < nm; ++j) R.col(j) = random(nm, 0.05);
  const Eigen::MatrixXd D = Eigen::MatrixXd::Identity(nm, nm) + 0.5 * (R + R.transpose());
  Eigen::MatrixXd top = Eigen::MatrixXd::Zero(6, nf);
  top.leftCols(6) = Eigen::MatrixXd::Identity(6, 6) * 2.0;
  top.block(3, 3, 3, 3) << 0.4, 0.02, 0, 0.02, 0.5, 0.01, 0, 0.01, 0.3;
  for (int j = 6; j < nf; ++j) top.col(j) = random(6, 0.1);
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(nf, nf);
  full.topRows(6) = top;
  full.bottomLeftCorner(nm, 6) = top.rightCols(nm).transpose();
  full.bottomRightCorner(nm, nm) = D;
  ASSERT_EQ(Eigen::LLT<Eigen::MatrixXd>(full).info(), Eigen::Success);
  Eigen::MatrixXd rigid = Eigen::MatrixXd::Identity(6, 6);
  rigid.bottomRightCorner(3, 3) << 0.2, 0.01, 0, 0.01, 0.3, 0, 0, 0, 0.1;
  BlockDiagonal Md, Ma;
  Md.size = Ma.size = n;
  Md.offset = Ma.offset = {0, nf};
  Md.block = {full, rigid};
  Md.diagonal = {Eigen::VectorXd(), Eigen::VectorXd()};
  Ma.block = {top, rigid};
  Ma.diagonal = {Eigen::VectorXd(), Eigen::VectorXd()};
  Ma.constant = {std::make_shared<const ConstantBlock>(D), nullptr};
  ASSERT_TRUE(Ma.arrow(0) && !Ma.arrow(1));
  ASSERT_LT((Ma.dense(0) - full).cwiseAbs().maxCoeff(), 1e-15);
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(m, n);
  for (int i = 0; i < m; ++i) {
    Phi.row(i).head(6) = random(6, 1.0).transpose();
    Phi.row(i).segment(6, nm) = random(nm, 0.3).transpose();
    Phi.row(i).tail(6) = random(6, 1.0).transpose();
  }
  const Eigen::VectorXd Q = random(n, 5.0), stab = random(m, 1.0);
  const SparseMatrixd Phis = Phi.sparseView();
  AlSolver sd, sa;
  sd.setMethod(AlMethod::BlockSchur);
  sa.setMethod(AlMethod::BlockSchur);
  sd.factorize(Md, Phis, 1e6);
  sa.factorize(Ma, Phis, 1e6);
  ASSERT_TRUE(sd.ok() && sa.ok());
  const AlResult rd = sd.accelerations(Q, stab, 1e-12, 50), ra = sa.accelerations(Q, stab, 1e-12, 50);
  Case c{Eigen::MatrixXd(), Phi, Q, stab};
  c.M = Eigen::MatrixXd::Zero(n, n);
  c.M.topLeftCorner(nf, nf) = full;
  c.M.bottomRightCorner(6, 6) = rigid;
  const Eigen::VectorXd x = exactSolution(c);
  const double e_dense = (ra.vdot - rd.vdot).norm() / rd.vdot.norm();
  const double e_kkt = (ra.vdot - x).norm() / x.norm();
  const double e_lambda = (ra.lambda - rd.lambda).norm() / rd.lambda.norm();
  std::printf("[   info   ] constant-block arrow vs dense block: accelerations %.2e, multipliers %.2e; vs KKT %.2e\n",
              e_dense, e_lambda, e_kkt);
  // The same bounds as the diagonal arrow's above: two factorisations of one
  // well-conditioned matrix agree to rounding times its conditioning.
  EXPECT_LT(e_dense, 1e-10);
  EXPECT_LT(e_lambda, 1e-10);
  EXPECT_LT(e_kkt, 1e-9);
  Eigen::VectorXd yd, ya;
  Md.multiply(x, yd);
  Ma.multiply(x, ya);
  EXPECT_LT((ya - yd).norm(), 1e-13 * yd.norm());
  EXPECT_LT((Eigen::MatrixXd(Ma.toSparse()) - c.M).cwiseAbs().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace fc::mbs
