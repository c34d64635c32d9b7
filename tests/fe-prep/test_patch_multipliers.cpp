// Held distributing patches kept by Lagrange multipliers (the default,
// reference_conditions.h) against their elimination: the constrained problem
// is the same, so the body must be the same to the solvers' rounding, for the
// free reduction (shift-invert on the saddle-point pencil, with and without a
// rigid motion left free), its static correction, and Craig-Bampton's
// constraint and fixed-interface modes. And the multipliers must leave no
// spurious mode: same count, no zero or infinite eigenvalue among the kept.
#include <gtest/gtest.h>

#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "fe-prep/build_body.h"
#include "feprep_test_support.h"

namespace fc::feprep::test {
namespace {

std::string panel(const std::string& reference, const std::string& extra) {
  return R"(
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  name: panel
  shell: {rectangle: {length: 1.0, width: 0.65}, material: cfrp_iso, thickness: 0.002, mesh: {size: 0.04}}
  interfaces:
    H1: {point: [-0.4, -0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}
    H2: {point: [-0.4, 0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}
    T: {point: [0.4, 0.0, 0.0], coupling: distributing, nodes: {within: 0.08}}
  reference: )" + reference + "\n" + extra;
}

BuildResult build(const std::string& yaml, PatchHold hold) {
  const BodySpec spec = parseBodySpec(InputNode::loadString(yaml, "<test>"));
  BuildOptions opt;
  opt.quiet = true;
  opt.patch_hold = hold;
  return buildFlexBody(PETSC_COMM_WORLD, spec, opt);
}

struct Difference {
  double eigenvalue = 0.0;  // largest relative difference
  double shape = 0.0;       // largest entry difference over the shape's largest entry (sign aligned)
  double interface = 0.0;   // the same for the interface shapes
};

Difference compare(const FlexBody& a, const FlexBody& b) {
  Difference d;
  for (long j = 0; j < a.eigenvalues.size(); ++j) {
    d.eigenvalue = std::max(d.eigenvalue, std::abs(a.eigenvalues(j) - b.eigenvalues(j)) / std::abs(b.eigenvalues(j)));
    const double s = a.shapes.col(j).dot(b.shapes.col(j)) < 0 ? -1.0 : 1.0;
    d.shape = std::max(d.shape, (s * a.shapes.col(j) - b.shapes.col(j)).cwiseAbs().maxCoeff() /
                                    b.shapes.col(j).cwiseAbs().maxCoeff());
    for (std::size_t k = 0; k < a.interfaces.size(); ++k) {
      const Eigen::VectorXd ia = a.interfaces[k].shapes.row(j), ib = b.interfaces[k].shapes.row(j);
      d.interface = std::max(d.interface, (s * ia - ib).cwiseAbs().maxCoeff() / b.shapes.col(j).cwiseAbs().maxCoeff());
    }
  }
  return d;
}

// Each path converges every eigenpair to SLEPc's 1e-10 relative residual
// (BuildOptions) on its own factorisation, so they agree to about that, not to
// machine rounding: measured eigenvalues 8e-13..1.8e-10 (the shifted pencil
// with a rigid turn the largest), shapes 2e-12..1.3e-10 of their largest entry
// (printed). 1e-8 is the figure the body must meet between runs (as between
// serial and mpirun, test_cli.cpp); a patch not held or a multiplier with mass
// moves the first frequency by percent.
void expectSame(const std::string& what, const BuildResult& mult, const BuildResult& elim) {
  ASSERT_EQ(mult.body.eigenvalues.size(), elim.body.eigenvalues.size()) << what;
  EXPECT_EQ(mult.reduced_dofs, elim.reduced_dofs) << what;
  EXPECT_EQ(mult.rigid_removed, elim.rigid_removed) << what;
  const Difference d = compare(mult.body, elim.body);
  std::printf("%s: eigenvalues %.2e, shapes %.2e, interface shapes %.2e; first %.6f Hz\n", what.c_str(),
              d.eigenvalue, d.shape, d.interface, mult.body.frequencies_hz(0));
  EXPECT_LT(d.eigenvalue, 1e-8) << what;
  EXPECT_LT(d.shape, 1e-6) << what;
  EXPECT_LT(d.interface, 1e-6) << what;
  // No spurious mode from the multipliers: every kept eigenvalue is finite and
  // positive (the held panel has no rigid motion left, or it was removed).
  EXPECT_GT(mult.body.eigenvalues.minCoeff(), 1.0) << what;
  EXPECT_TRUE(mult.body.eigenvalues.allFinite()) << what;
}

TEST(PatchMultipliers, FreeModesEqualTheElimination) {
  const std::string y = panel("{pin: [H1, H2, T]}", "  modes: 8\n");
  expectSame("pinned H1 H2 T, 8 free modes", build(y, PatchHold::Multipliers), build(y, PatchHold::Eliminate));
}

TEST(PatchMultipliers, ARigidMotionLeftFreeShiftsThePencil) {
  // Two pins leave the turn about their line: the shift sigma < 0 factorises
  // K - sigma M with the multiplier rows, and the rigid mode is removed.
  const std::string y = panel("{pin: [H1, H2]}", "  modes: 6\n");
  const BuildResult m = build(y, PatchHold::Multipliers), e = build(y, PatchHold::Eliminate);
  EXPECT_EQ(m.rigid_removed, 1);
  expectSame("pinned H1 H2 (one rigid turn), 6 free modes", m, e);
  EXPECT_LT(m.rigid_eigenvalues.cwiseAbs().maxCoeff(), 1e-6 * m.body.eigenvalues(0));
}

TEST(PatchMultipliers, StaticCorrectionEqualsTheElimination) {
  const std::string y = panel("{clamp: [H1], pin: [H2]}", "  modes: {count: 4, static_correction: [T]}\n");
  expectSame("clamped H1, pinned H2, 4 modes + correction at T", build(y, PatchHold::Multipliers),
             build(y, PatchHold::Eliminate));
}

TEST(PatchMultipliers, CraigBamptonEqualsTheElimination) {
  const std::string y = panel("{pin: [H1, H2], clamp: [T]}", "  reduction: craig_bampton\n  modes: 6\n");
  const BuildResult m = build(y, PatchHold::Multipliers), e = build(y, PatchHold::Eliminate);
  EXPECT_EQ(m.constraint_modes, 12);
  expectSame("Craig-Bampton, pinned H1 H2, clamped T, 6 fixed-interface modes", m, e);
  const double fic = (m.body.fixed_interface_coordinates.cwiseAbs() - e.body.fixed_interface_coordinates.cwiseAbs())
                         .cwiseAbs()
                         .maxCoeff();
  EXPECT_LT(fic, 1e-6);
}

}  // namespace
}  // namespace fc::feprep::test
