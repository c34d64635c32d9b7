// The node form of the second-order inertia terms (nodal_inertia.h) against
// the invariant form it replaces: the same sums in another order, so the mass
// matrix, the quadratic velocity vector, the arrow rows and the kinetic energy
// agree to rounding; and against the brute-force nodal kinetic energy and
// Lagrange equations, which neither form shares.
#include <gtest/gtest.h>

#include "common/rotations.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/mechanics/flexible/nodal_inertia.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

struct State {
  Matrix3d A;
  VectorXd w, wd;
  Vector3d om;
};

State randomState(int nm, unsigned seed) {
  std::srand(seed);
  State s;
  s.A = fc::expRotation(Vector3d::Random() * 2.0);
  s.w = 0.3 * VectorXd::Random(nm);  // large deformations: the second-order terms matter
  s.wd = VectorXd::Random(nm);
  s.om = 3.0 * Vector3d::Random();
  return s;
}

// Both forms on one body and state. Tolerance: the entries are sums of
// ~n nm products of O(1) numbers (n <= 30 nodes, nm <= 40 modes) taken in
// another order: rounding of ~1e-16 per term relative to the largest term,
// so 1e-12 of the norm leaves a hundredfold margin, while a missing or
// mis-indexed term is O(1) of it.
void expectSame(const fc::FlexBody& body, int nm, unsigned seed) {
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body, nm);
  const fc::mbs::NodalInertia ni = fc::mbs::nodalInertia(body, nm);
  const State s = randomState(nm, seed);
  const auto a = fc::mbs::flexibleInertia(inv, s.A, s.w, s.wd, s.om);
  const auto b = fc::mbs::flexibleInertia(inv, s.A, s.w, s.wd, s.om, &ni);
  EXPECT_LT((a.M - b.M).norm(), 1e-12 * a.M.norm()) << "seed " << seed;
  EXPECT_LT((a.Qv - b.Qv).norm(), 1e-12 * a.Qv.norm()) << "seed " << seed;
  const auto ra = fc::mbs::flexibleInertiaRows(inv, s.A, s.w, s.wd, s.om);
  const auto rb = fc::mbs::flexibleInertiaRows(inv, s.A, s.w, s.wd, s.om, &ni);
  EXPECT_LT((ra.top - rb.top).norm(), 1e-12 * ra.top.norm());
  EXPECT_LT((ra.Qv - rb.Qv).norm(), 1e-12 * ra.Qv.norm());
  VectorXd v(6 + nm);
  v << Vector3d::Random(), s.om, s.wd;
  const double Ta = fc::mbs::kineticEnergy(inv, s.A, s.w, v), Tb = fc::mbs::kineticEnergy(inv, s.A, s.w, v, &ni);
  EXPECT_NEAR(Ta, Tb, 1e-12 * Ta);
  // And the node form alone against the brute-force kinetic energy of the nodes.
  const fc::testing::BruteForce bf{body, nm};
  EXPECT_NEAR(Tb, bf.kinetic(s.A, s.w, v), 1e-12 * Tb);
}

TEST(NodalInertia, SameAsTheInvariantsOnABodyMovingAlongEveryAxis) {
  for (unsigned seed : {1u, 2u, 3u}) expectSame(fc::testing::randomBody(9, 14, seed), 14, 40 + seed);
  // Fewer modes kept than the file holds: only the leading columns count.
  expectSame(fc::testing::randomBody(12, 20, 7), 11, 50);
}

TEST(NodalInertia, SameAsTheInvariantsWhenRowsVanish) {
  // A planar body (every mode in the x-y plane) with massless and fixed
  // nodes: the node form drops those rows, the invariants hold zeros there.
  fc::FlexBody body = fc::testing::randomBody(30, 40, 9);
  for (long k = 0; k < body.nodeCount(); ++k) body.shapes.row(6 * k + 2).setZero();
  body.shapes.middleRows(6 * 4, 6).setZero();
  body.nodal_mass(7, 0) = 0.0;
  const fc::mbs::NodalInertia ni = fc::mbs::nodalInertia(body, 40);
  EXPECT_EQ(ni.shapes[2].cols(), 0);
  EXPECT_EQ(ni.shapes[0].cols(), 28);  // 30 nodes less the fixed and the massless one
  EXPECT_EQ(ni.rows(), 56);
  expectSame(body, 40, 60);
}

TEST(NodalInertia, CostRuleKeepsTheInvariantsForFewModesOnBigMeshes) {
  // A shell panel (thousands of nodes, tens of modes) keeps the nm x nm
  // invariants; a beam with more modes than nodal rows takes the node form.
  EXPECT_FALSE(fc::mbs::nodalFormCheaper(3 * 2000, 30));
  EXPECT_FALSE(fc::mbs::nodalFormCheaper(101, 4));
  EXPECT_FALSE(fc::mbs::nodalFormCheaper(20, 16));  // in cache: the invariants are as fast
  EXPECT_TRUE(fc::mbs::nodalFormCheaper(101, 200));
  EXPECT_FALSE(fc::mbs::nodalFormCheaper(0, 0));  // a rigid body has no second-order terms
}

TEST(NodalInertia, RefusesABodyWithoutNodalShapes) {
  fc::FlexBody body = fc::testing::randomBody(5, 3, 4);
  body.shapes.resize(0, 0);  // as readFlexBody(..., FlexBodyParts::Dynamics) leaves it
  EXPECT_THROW(fc::mbs::nodalInertia(body, 3), std::invalid_argument);
}

}  // namespace
