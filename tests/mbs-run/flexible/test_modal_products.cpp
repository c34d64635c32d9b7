// The invariants' S_ab over their non-zero entries (modal_products.h)
// against the dense S_ab they stand for: on a beam-like body (each mode
// moving along one axis, plus the orthogonality noise an eigen-solve leaves)
// the pattern keeps exactly the blocks the axes couple, and the mass matrix,
// the quadratic velocity vector, the arrow rows and the kinetic energy agree
// with the dense products to rounding.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "common/rotations.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/mechanics/flexible/modal_products.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

// Mode j moves its nodes along axis j % 3 only (rotations free), as a
// beam's axial and bending modes do, and every other nodal translation gets
// noise of `noise` relative (fe-prep's modes: 1e-14 to 1e-12 of the
// largest product entry, measured on the steel bar of
// tests/data/fe-prep/steel_bar_pendulum.yaml).
fc::FlexBody axisBody(int n, int nm, unsigned seed, double noise) {
  fc::FlexBody body = fc::testing::randomBody(n, nm, seed);
  std::mt19937 gen(seed + 100);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int j = 0; j < nm; ++j)
    for (long k = 0; k < body.nodeCount(); ++k)
      for (int a = 0; a < 3; ++a)
        if (a != j % 3) body.shapes(6 * k + a, j) = noise * u(gen);
  return body;
}

TEST(ModalProducts, KeepsTheBlocksTheAxesCoupleAndDropsTheNoise) {
  const int nm = 30;
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(axisBody(20, nm, 3, 1e-9), nm);
  const fc::mbs::SparseModalProducts s = fc::mbs::sparseModalProducts(inv);
  // With 1e-9 noise, S_ab keeps the entries where mode i moves along a or
  // mode j along b: the noise x shape terms (1e-9) are above rounding; only
  // the noise x noise terms (1e-18) fall below nm eps: (2 nm / 3)^2 of each.
  long expected = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      const auto& p = s.products[3 * a + b];
      for (int j = 0; j < nm; ++j)
        for (int q = p.start[j]; q < p.start[j + 1]; ++q) EXPECT_EQ(inv.modal_products[3 * a + b](p.row[q], j), p.value[q]);
      expected += nm * nm - (2 * nm / 3) * (2 * nm / 3);
    }
  EXPECT_EQ(s.entries(), expected);
  // With noise below rounding only the blocks the axes couple remain: (nm/3)^2 of each.
  const fc::InertiaInvariants clean = fc::computeInertiaInvariants(axisBody(20, nm, 3, 1e-17), nm);
  const fc::mbs::SparseModalProducts c = fc::mbs::sparseModalProducts(clean);
  EXPECT_EQ(c.entries(), 6L * (nm / 3) * (nm / 3));
  EXPECT_TRUE(fc::mbs::sparseFormCheaper(c));
  EXPECT_FALSE(fc::mbs::sparseFormCheaper(s));
  // A body whose modes move along every axis keeps everything: the dense form.
  const fc::InertiaInvariants full = fc::computeInertiaInvariants(fc::testing::randomBody(20, nm, 4), nm);
  EXPECT_FALSE(fc::mbs::sparseFormCheaper(fc::mbs::sparseModalProducts(full)));
}

// Tolerance: the dropped entries are each below nm eps of the largest entry,
// and the dense sums themselves are exact only to nm eps of their terms'
// magnitudes (modal_products.h): with O(1) entries and states the two
// differ by a few 1e-15 relative; 1e-13 leaves a margin of tens, while one
// missing block entry (1e-2 relative at least) is eleven orders above it.
TEST(ModalProducts, SameAsTheDenseProductsToRounding) {
  for (int nm : {12, 30, 60}) {
    const fc::InertiaInvariants inv = fc::computeInertiaInvariants(axisBody(25, nm, nm, 1e-17), nm);
    const fc::mbs::SparseModalProducts s = fc::mbs::sparseModalProducts(inv);
    ASSERT_LT(s.entries(), 6L * nm * nm / 4);  // the noise is dropped: the test compares the pattern
    std::srand(static_cast<unsigned>(nm));
    const Matrix3d A = fc::expRotation(Vector3d::Random() * 2.0);
    const VectorXd w = 0.3 * VectorXd::Random(nm), wd = VectorXd::Random(nm);
    const Vector3d om = 3.0 * Vector3d::Random();
    const auto a = fc::mbs::flexibleInertia(inv, A, w, wd, om);
    const auto b = fc::mbs::flexibleInertia(inv, A, w, wd, om, &s);
    EXPECT_LT((a.M - b.M).norm(), 1e-13 * a.M.norm()) << nm;
    EXPECT_LT((a.Qv - b.Qv).norm(), 1e-13 * a.Qv.norm()) << nm;
    const auto ra = fc::mbs::flexibleInertiaRows(inv, A, w, wd, om);
    const auto rb = fc::mbs::flexibleInertiaRows(inv, A, w, wd, om, &s);
    EXPECT_LT((ra.top - rb.top).norm(), 1e-13 * ra.top.norm()) << nm;
    EXPECT_LT((ra.Qv - rb.Qv).norm(), 1e-13 * ra.Qv.norm()) << nm;
    VectorXd v(6 + nm);
    v << Vector3d::Random(), om, wd;
    const double Ta = fc::mbs::kineticEnergy(inv, A, w, v), Tb = fc::mbs::kineticEnergy(inv, A, w, v, &s);
    EXPECT_NEAR(Ta, Tb, 1e-13 * Ta) << nm;
    // The second-order terms are what the pattern serves: they must matter
    // here, or the comparison above would not see a wrong pattern.
    const auto lin = fc::mbs::flexibleInertia(inv, A, 1e-3 * w, wd, om, &s);
    EXPECT_GT((lin.Qv - b.Qv).norm(), 1e-3 * b.Qv.norm()) << nm;
  }
}

TEST(ModalProducts, ARigidBodyHasNoProducts) {
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(fc::testing::randomBody(5, 3, 2), 0);
  const fc::mbs::SparseModalProducts s = fc::mbs::sparseModalProducts(inv);
  EXPECT_EQ(s.entries(), 0);
  EXPECT_FALSE(fc::mbs::sparseFormCheaper(s));
}

}  // namespace
