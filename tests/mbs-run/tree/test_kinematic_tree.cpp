// the joint-coordinate path (mbs-run/tree/kinematic_tree.h, Featherstone's
// ABA; run/tree_dynamics.h) against references nobody here wrote:
//  - the planar N-link chain in absolute angles (chain_reference.h, d'Alembert
//    on the link centres, dense mass matrix): the accelerations to rounding;
//  - the constrained path (Cartesian coordinates, augmented Lagrangian) on a
//    3D tree with branches, non-planar axes, offset centres of mass, full
//    inertias, a joint whose bodies are listed child first with antiparallel
//    axes, a prismatic joint, springs, a damper and a constant torque: the
//    same motion to integration tolerance, the same reactions;
//  - energy conservation (T + V + D - W constant);
//  - the single compound pendulum's closed-form period and pivot force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "chain_reference.h"
#include "common/rotations.h"
#include "helpers.h"
#include "mbs-run/tree/kinematic_tree.h"
#include "mbs-run/mechanics/force_elements.h"
#include "mbs-run/run/constrained_dynamics.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/run/tree_dynamics.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs::test {
namespace {

constexpr double kL = 0.1, kM = 0.1, kG = 9.81;

std::string planarChain(int n, const std::string& simulation) { return thinLinkChainScene(n, kL, kM, simulation); }

// The consistent initial poses of a scene, as both paths start from them.
std::vector<BodyPose> startPoses(const Model& m) {
  System sys(m);
  Eigen::VectorXd y = sys.initialState();
  sys.initializeJoints(y);
  sys.project(0.0, y);
  std::vector<BodyPose> P;
  sys.poses(y, P);
  return P;
}

// The ABA's joint accelerations against the minimal-coordinate chain's at
// arbitrary states. Link k's relative angle q_k turns it about +y, which
// takes +x towards -z: the absolute angle (from +x towards +z) of link k is
// phi_k = -(q_0 + ... + q_k). Both sides are exact up to rounding (the
// reference solves its dense N x N system by Cholesky, condition ~1e3-1e5
// for these chains): 1e-10 relative to the largest acceleration leaves
// 3-4 decades above what was measured (listed in the output).
TEST(KinematicTree, AccelerationsEqualMinimalCoordinateChain) {
  for (int n : {1, 2, 10, 50}) {
    const Model m = sceneFromText(planarChain(n, "{t_end: 1}"));
    const KinematicTree tree = buildKinematicTree(m, startPoses(m));
    ASSERT_EQ(tree.size(), n);
    const MinimalChain ref(n, kL, kM, kM * kL * kL / 12, kG);
    double worst = 0.0;
    for (int trial = 0; trial < 5; ++trial) {
      std::srand(17 + trial);
      const Eigen::VectorXd q = Eigen::VectorXd::Random(n) * 1.5, qd = Eigen::VectorXd::Random(n) * 3.0;
      std::vector<BodyPose> P;
      treePoses(tree, q, qd, P);
      TreeWorkspace ws;
      Eigen::VectorXd qdd;
      treeAccelerations(m, tree, P, qd, Eigen::VectorXd(), ws, qdd);
      Eigen::VectorXd y(2 * n);
      double sq = 0.0, sqd = 0.0;
      for (int k = 0; k < n; ++k) {
        sq += q[k];
        sqd += qd[k];
        y[k] = -sq;
        y[n + k] = -sqd;
      }
      const Eigen::VectorXd phidd = ref.f(y).tail(n);
      Eigen::VectorXd expect(n);
      for (int k = 0; k < n; ++k) expect[k] = -(phidd[k] - (k ? phidd[k - 1] : 0.0));
      worst = std::max(worst, (qdd - expect).lpNorm<Eigen::Infinity>() / expect.lpNorm<Eigen::Infinity>());
      // The poses the tree implies: the reference's link centres.
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector2d c = ref.centre(y, k);
        EXPECT_LT(std::hypot(P[k + 1].r.x() - c.x(), P[k + 1].r.z() - c.y()) + std::abs(P[k + 1].r.y()), 1e-13 * n);
      }
    }
    std::printf("[   info   ] N = %d: ABA vs minimal-coordinate accelerations %.2e relative\n", n, worst);
    EXPECT_LT(worst, 1e-10);
  }
}

// A whole run of the tree path (auto picks it for this scene) against the
// reference integrated by RK4, as test_chain_reference.cpp does for the
// constrained path: Dormand-Prince at rtol 1e-11 (atol 1e-14) on angles of
// order 1 over 0.4 s; measured 4e-13 m, the reference's own RK4 error
// included (400 substeps per output). 1e-10 m is the bound.
TEST(KinematicTree, RunMatchesMinimalCoordinateChain) {
  const int n = 10;
  const Results r = simulate(sceneFromText(planarChain(n, "{t_end: 0.4, output_step: 0.04, rtol: 1e-11, atol: 1e-14}")),
                             {true});
  ASSERT_EQ(r.status, "completed");
  ASSERT_EQ(r.formulation, "tree");
  const MinimalChain c(n, kL, kM, kM * kL * kL / 12, kG);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  double t = 0, worst = 0;
  for (std::size_t k = 1; k < r.time.size(); ++k) {
    y = rk4([&](double, const Eigen::VectorXd& z) { return c.f(z); }, y, t, r.time[k], 400);
    t = r.time[k];
    for (int b = 0; b < n; ++b) {
      const Eigen::Vector2d ref = c.centre(y, b);
      const Eigen::Vector3d& p = r.position[b + 1][k];
      worst = std::max(worst, std::hypot(p.x() - ref.x(), p.z() - ref.y()) + std::abs(p.y()));
    }
  }
  std::printf("[   info   ] N = %d, 0.4 s: worst rod-centre error %.2e m, %ld steps, %ld evaluations\n", n, worst,
              r.steps, r.evaluations);
  ASSERT_GT(-r.position[n].back().z(), 0.1);  // a large motion
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(r.max_violation, 1e-12);  // the Cartesian poses of a joint-coordinate state satisfy every joint
}

// The 3D tree: ground - A (revolute about a tilted axis) - B (revolute, the
// joint listing B first, axes antiparallel) and - C (revolute about a third
// axis; a branch) - D (prismatic along C's x, held by a spring to the
// ground), a rotational spring-damper on A-C, a constant torque on B.
std::string spatialTree(const std::string& formulation, double rtol, bool damped) {
  // Consistent initial poses (the projection only has to fix the velocities):
  // every body starts with the ground's orientation qg, B turned by 60 deg
  // about its x axis more.
  const Eigen::Vector4d qg = fc::eulerParametersFromAxisAngle(Eigen::Vector3d::UnitY(), M_PI / 4);
  const Eigen::Vector4d qb = fc::quatProduct(qg, fc::eulerParametersFromAxisAngle(Eigen::Vector3d::UnitX(), M_PI / 3));
  const Eigen::Matrix3d Rg = fc::rotationMatrix(qg);
  const Eigen::Vector3d pa(0.1, -0.2, 0.3), pb = pa + Rg * Eigen::Vector3d(0.6, 0, 0),
      pc = pa + Rg * Eigen::Vector3d(0.4, 0.1, 0), pd = pc + Rg * Eigen::Vector3d(0.25, 0, 0.1);
  auto q4 = [](const Eigen::Vector4d& q) {
    char b[128];
    std::snprintf(b, sizeof b, "[%.17g, %.17g, %.17g, %.17g]", q[0], q[1], q[2], q[3]);
    return std::string(b);
  };
  std::string y =
      "bodies:\n"
      "  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true, position: " +
      yamlVector(pa) + ", orientation: " + q4(qg) +
      "}\n"
      "  - {name: A, rigid: {mass: 2.0, center_of_mass: [0.3, 0.05, -0.02],"
      " inertia: [[0.05, 0.004, -0.002], [0.004, 0.04, 0.003], [-0.002, 0.003, 0.03]]}, position: " +
      yamlVector(pa) + ", orientation: " + q4(qg) +
      ", angular_velocity: [0.3, 0.0, 0.9]}\n"
      "  - {name: B, rigid: {mass: 0.7, center_of_mass: [0.0, 0.2, 0.01],"
      " inertia: [[0.02, -0.001, 0.0], [-0.001, 0.005, 0.002], [0.0, 0.002, 0.018]]}, position: " +
      yamlVector(pb) + ", orientation: " + q4(qb) +
      "}\n"
      "  - {name: C, rigid: {mass: 1.1, center_of_mass: [0.1, 0.0, 0.15],"
      " inertia: [[0.01, 0.0, 0.001], [0.0, 0.012, 0.0], [0.001, 0.0, 0.006]]}, position: " +
      yamlVector(pc) + ", orientation: " + q4(qg) +
      "}\n"
      "  - {name: D, rigid: {mass: 0.4, inertia: [[0.001, 0, 0], [0, 0.002, 0], [0, 0, 0.002]]}, position: " +
      yamlVector(pd) + ", orientation: " + q4(qg) + "}\n";
  char s[2000];
  std::snprintf(
      s, sizeof s,
      "joints:\n"
      "  - {name: JA, type: revolute, bodies: [ground, A], points: [[0, 0, 0], [0, 0, 0]],"
      " axes: [[0.6, 0, 0.8], [0.6, 0, 0.8]]}\n"
      // B first: the link runs from A to B about A's axis; B's axis, as B's
      // orientation turns it, points the other way.
      "  - {name: JB, type: revolute, bodies: [B, A], points: [[0, 0, 0], [0.6, 0, 0]],"
      " axes: [[0, -0.8660254037844387, 0.5], [0, 0.8660254037844387, 0.5]]}\n"
      "  - {name: JC, type: revolute, bodies: [A, C], points: [[0.4, 0.1, 0], [0, 0, 0]],"
      " axes: [[0, 1, 1], [0, 1, 1]], initial_angle: 0.3}\n"
      "  - {name: JD, type: prismatic, bodies: [C, D], points: [[0.2, 0, 0.1], [0, 0, 0]],"
      " axes: [[1, 0, 0], [1, 0, 0]]}\n"
      "forces:\n"
      "  - {type: gravity, g: [0, 0, -9.81]}\n"
      "  - {type: rotational_spring_damper, joint: JC, damping: %g,"
      " torque: {angle: [-1, 1], value: [-3, 3]}}\n"
      "  - {type: translational_spring_damper, bodies: [ground, D], points: [[0.6, 0.1, 0.1], [0, 0, 0]],"
      " stiffness: 200, damping: %g, free_length: 0.05}\n"
      "  - {type: torque, body: B, torque: [0.0, 0.2, 0.1]}\n"
      "simulation: {t_end: 1.0, output_step: 0.05, rtol: %g, integrator: dopri5, formulation: %s}\n",
      damped ? 0.05 : 0.0, damped ? 0.5 : 0.0, rtol, formulation.c_str());
  return y + s;
}

// Tree against constrained: both integrate the same equations in different
// coordinates with Dormand-Prince at rtol 1e-10 (atol 1e-13) over 1 s.
// Measured: positions 1.4e-12 m, Euler parameters 2.3e-11, velocities
// 1.7e-10 m/s + rad/s, angles 4.5e-11 rad, reactions 2e-11 relative, energy
// 1.8e-11 J. The bounds are 10 rtol on quantities of order 1 (velocities
// 100 rtol: they carry the motion's ~10 rad/s); a wrong sign of a joint's
// angle or a wrong inertia term gives errors of order 1e-2.
TEST(KinematicTree, SpatialTreeMatchesConstrainedPath) {
  const Results tr = simulate(sceneFromText(spatialTree("tree", 1e-10, true)), {true});
  const Results cs = simulate(sceneFromText(spatialTree("constrained", 1e-10, true)), {true});
  ASSERT_EQ(tr.status, "completed");
  ASSERT_EQ(cs.status, "completed");
  EXPECT_EQ(tr.formulation, "tree");
  EXPECT_EQ(cs.formulation, "constrained (formulation: constrained)");
  ASSERT_EQ(tr.time.size(), cs.time.size());
  double pos = 0, ori = 0, vel = 0, ang = 0, rf = 0, rt = 0, fscale = 0, en = 0;
  for (std::size_t i = 0; i < tr.time.size(); ++i) {
    for (std::size_t b = 1; b < tr.position.size(); ++b) {
      pos = std::max(pos, (tr.position[b][i] - cs.position[b][i]).norm());
      ori = std::max(ori, (tr.orientation[b][i] - cs.orientation[b][i]).norm());
      vel = std::max(vel, (tr.velocity[b][i] - cs.velocity[b][i]).norm() +
                              (tr.angular_velocity[b][i] - cs.angular_velocity[b][i]).norm());
    }
    for (std::size_t j = 0; j < tr.reaction.size(); ++j) {
      ang = std::max(ang, std::abs(tr.joint_angle[j][i] - cs.joint_angle[j][i]));
      rf = std::max(rf, (tr.reaction[j][i] - cs.reaction[j][i]).norm());
      rt = std::max(rt, (tr.reaction_torque[j][i] - cs.reaction_torque[j][i]).norm());
      fscale = std::max(fscale, cs.reaction[j][i].norm());
    }
    en = std::max(en, std::abs(tr.kinetic[i] + tr.potential[i] + tr.dissipated[i] - tr.applied_work[i] -
                               (cs.kinetic[i] + cs.potential[i] + cs.dissipated[i] - cs.applied_work[i])));
  }
  const double moved = (cs.position[4].back() - cs.position[4].front()).norm();
  std::printf("[   info   ] tree vs constrained over 1 s: positions %.2e m, Euler parameters %.2e, velocities %.2e, "
              "joint angles %.2e rad, reactions %.2e N (of %.3g N) %.2e N m, energy %.2e J; D moved %.3f m; "
              "evaluations %ld vs %ld\n",
              pos, ori, vel, ang, rf, fscale, rt, en, moved, tr.evaluations, cs.evaluations);
  ASSERT_GT(moved, 0.02);  // the tree moves
  EXPECT_LT(pos, 1e-9);
  EXPECT_LT(ori, 1e-9);
  EXPECT_LT(vel, 1e-8);
  EXPECT_LT(ang, 1e-9);
  // Reactions: the tree's by the RNEA, the constrained path's from its
  // multipliers (converged to ~1e-10 relative), at states that differ by the
  // above.
  EXPECT_LT(rf, 1e-9 * fscale);
  EXPECT_LT(rt, 1e-9 * fscale);
  EXPECT_LT(en, 1e-9);
}

// Without dampers T + V - W is a first integral (the constant torque's work
// W enters through its power quadrature). At rtol 1e-10 over 1 s the
// balance drifts by the accumulated local errors, ~steps x rtol x energy.
TEST(KinematicTree, EnergyIsConserved) {
  const Results r = simulate(sceneFromText(spatialTree("auto", 1e-10, false)), {true});
  ASSERT_EQ(r.status, "completed");
  ASSERT_EQ(r.formulation, "tree");
  double scale = 0.0, drift = 0.0;
  const double e0 = r.kinetic[0] + r.potential[0] - r.applied_work[0];
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    scale = std::max({scale, std::abs(r.kinetic[i]), std::abs(r.potential[i])});
    drift = std::max(drift, std::abs(r.kinetic[i] + r.potential[i] - r.applied_work[i] - e0));
  }
  std::printf("[   info   ] energy drift %.2e J of %.3g J over 1 s (%ld steps); balance error %.2e J\n", drift, scale,
              r.steps, r.energy_balance_error);
  EXPECT_GT(std::abs(r.applied_work.back()), 1e-3);  // the torque works
  EXPECT_LT(drift, double(r.steps) * 1e-10 * scale);
  EXPECT_LT(r.energy_balance_error, double(r.steps) * 1e-10 * scale);
}

// Compound pendulum (rod of length l pivoted at one end) released at rest at
// theta0 from the bottom: period T = 4 sqrt(J / (m g d)) K(sin(theta0/2))
// (K the complete elliptic integral of the first kind; e.g. Landau &
// Lifshitz, Mechanics, sec. 11), J = m l^2/3, d = l/2. At T/4 it passes the
// bottom with theta_dot^2 = 2 m g d (1 - cos theta0) / J, where the pivot
// holds m (g + d theta_dot^2) (no tangential acceleration there).
TEST(KinematicTree, SinglePendulumClosedForm) {
  const double l = 0.8, m = 1.3, g = 9.81, th0 = 2.0;
  const double J = m * l * l / 3, d = l / 2;
  const double T = 4.0 * std::sqrt(J / (m * g * d)) * std::comp_ellint_1(std::sin(th0 / 2));
  // The rod hangs along -z at angle 0; it starts turned by th0 about +y
  // (which takes its free end from -z towards -x), centre at d (-sin, 0, -cos).
  char s[1200];
  std::snprintf(s, sizeof s,
                "bodies:\n"
                "  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n"
                "  - {name: rod, rigid: {mass: %.17g, inertia: [[%.17g,0,0],[0,%.17g,0],[0,0,1e-9]]},"
                " position: [%.17g, 0, %.17g], orientation: [%.17g, 0, %.17g, 0]}\n"
                "joints:\n"
                "  - {name: pivot, type: revolute, bodies: [ground, rod], points: [[0, 0, 0], [0, 0, %.17g]],"
                " axes: [[0, 1, 0], [0, 1, 0]], initial_angle: %.17g}\n"
                "forces:\n  - {type: gravity, g: [0, 0, %.17g]}\n"
                "simulation: {t_end: %.17g, output_step: %.17g, rtol: 1e-11, integrator: dopri5}\n",
                m, m * l * l / 12, m * l * l / 12, -d * std::sin(th0), -d * std::cos(th0), std::cos(th0 / 2),
                std::sin(th0 / 2), d, th0, -g, T, T / 4);
  const Results r = simulate(sceneFromText(s), {true});
  ASSERT_EQ(r.status, "completed");
  ASSERT_EQ(r.formulation, "tree");
  ASSERT_EQ(r.time.size(), 5u);
  const double expect[5] = {th0, 0.0, -th0, 0.0, th0};
  double worst = 0.0;
  for (int i = 0; i < 5; ++i) worst = std::max(worst, std::abs(r.joint_angle[0][i] - expect[i]));
  const double rate2 = 2 * m * g * d * (1 - std::cos(th0)) / J, pivot = m * (g + d * rate2);
  const double force_err = std::abs(r.reaction[0][1].norm() - pivot) / pivot;
  std::printf("[   info   ] period %.6f s: worst angle error at quarter periods %.2e rad; pivot force at the "
              "bottom %.8g N (closed form %.8g N)\n",
              T, worst, r.reaction[0][1].norm(), pivot);
  // rtol 1e-11 over ~250 steps: ~1e-9 rad; comp_ellint_1 is exact to rounding.
  EXPECT_LT(worst, 1e-8);
  // The reaction by the RNEA at the tree's state, whose own error is the
  // integration's (rtol 1e-11).
  EXPECT_LT(force_err, 1e-8);
}

// The RNEA reactions (treeReactions) against the constrained formulation's
// (System::reactions: the augmented-Lagrangian multipliers) at the same
// states: random joint angles and rates, the Cartesian state they imply
// given to System. Both are the exact constraint forces of one state, so
// they differ by the multiplier iteration's convergence (3 updates at
// penalty 1e6: ~1e-10 relative) and rounding. Scenes: the double pendulum
// (tests/data/mbs-run/double_pendulum_tiny_step.yaml: joints listed parent
// first) and the 3-D tree (tree_3d.yaml: non-parallel axes, a joint listed
// child first with the axis reversed, a prismatic joint, offset centres,
// springs, a damper and a torque acting, so f^ext is not gravity alone).
TEST(KinematicTree, ReactionsEqualConstrainedSolve) {
  for (const char* name : {"double_pendulum_tiny_step.yaml", "tree_3d.yaml"}) {
    const Model m = loadScene(std::string(FLEXCOMP_DATA_DIR) + "/mbs-run/" + name);
    ASSERT_EQ(treeUnsupported(m), "") << name;
    const KinematicTree tree = buildKinematicTree(m, startPoses(m));
    const int n = tree.size();
    System sys(m);
    Eigen::VectorXd y0 = sys.initialState();
    sys.initializeJoints(y0);
    double worst = 0.0, scale = 0.0, along = 0.0;
    for (int trial = 0; trial < 5; ++trial) {
      std::srand(31 + trial);
      const Eigen::VectorXd q = Eigen::VectorXd::Random(n), qd = 3.0 * Eigen::VectorXd::Random(n);
      std::vector<BodyPose> P;
      treePoses(tree, q, qd, P);
      Eigen::VectorXd qdd;
      ForceSums sums;
      sums.Q.setZero(m.nv);
      const std::vector<JointRuntime> rt = treeJointRuntimes(m, startPoses(m));
      for (int f : tree.other_forces) addForceElement(m, m.forces[f], P, rt, ForceQuantity::ForcesAndPowers, sums);
      TreeWorkspace ws;
      treeAccelerations(m, tree, P, qd, sums.Q, ws, qdd);
      const std::vector<JointReaction> tr = treeReactions(m, tree, P, qd, qdd, sums.Q);
      const std::vector<JointReaction> cs = sys.reactions(0.0, constrainedState(m, P, 0.0, 0.0));
      for (std::size_t j = 0; j < m.joints.size(); ++j) {
        worst = std::max({worst, (tr[j].force - cs[j].force).norm(), (tr[j].torque - cs[j].torque).norm()});
        scale = std::max({scale, cs[j].force.norm(), cs[j].torque.norm()});
        // A free joint transmits nothing along its own motion: no torque
        // about a revolute's axis, no force along a prismatic's.
        const Joint& jt = m.joints[j];
        const Eigen::Vector3d axis = P[jt.body_i].A * jt.axis_i.normalized();
        along = std::max(along, std::abs(axis.dot(jt.type == JointType::Revolute ? tr[j].torque : tr[j].force)));
      }
    }
    std::printf("[   info   ] %s: RNEA vs augmented-Lagrangian reactions %.2e relative (largest %.3g); "
                "along the joints' motion %.2e\n",
                name, worst / scale, scale, along / scale);
    EXPECT_GT(scale, 1.0);
    EXPECT_LT(worst, 1e-9 * scale);
    EXPECT_LT(along, 1e-12 * scale);  // rounding of the backward sums
  }
}

// A compound pendulum (rod of length l, mass m, pivoted at one end, centre
// at d = l/2, J = m l^2/3 about the pivot) in any state (theta, theta_dot):
// Newton-Euler for one body about a fixed axis gives J alpha = moment of
// gravity about the pivot, and the pin's force on the rod is
// F = m (a_c - g) with a_c = alpha x r_c + w x (w x r_c); along the rod
// towards the pivot m (g cos th + d thdot^2) (th from hanging down), across
// it m g sin th (1 - m d^2 / J). The joint lists the rod first, so the
// reaction on its first body is the force on the rod, the moment about the
// pin zero (a symmetric rod turning about a principal axis).
TEST(KinematicTree, PendulumPinReactionClosedForm) {
  const double l = 0.8, mass = 1.3, g = 9.81, d = l / 2, J = mass * l * l / 3;
  char s[900];
  std::snprintf(s, sizeof s,
                "bodies:\n"
                "  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n"
                "  - {name: rod, rigid: {mass: %.17g, inertia: [[1e-9,0,0],[0,%.17g,0],[0,0,%.17g]]},"
                " position: [%.17g, 0, 0]}\n"
                "joints:\n"
                "  - {name: pin, type: revolute, bodies: [rod, ground], points: [[%.17g, 0, 0], [0, 0, 0]],"
                " axes: [[0, 1, 0], [0, 1, 0]]}\n"
                "forces:\n  - {type: gravity, g: [0, 0, %.17g]}\n"
                "simulation: {t_end: 1}\n",
                mass, mass * l * l / 12, mass * l * l / 12, d, -d, -g);
  const Model m = sceneFromText(s);
  ASSERT_EQ(treeUnsupported(m), "");
  const KinematicTree tree = buildKinematicTree(m, startPoses(m));
  const Eigen::Vector3d gvec(0, 0, -g);
  double worst = 0.0, worst_radial = 0.0, worst_torque = 0.0;
  const std::pair<double, double> states[] = {{0.3, 0.0}, {-1.2, 2.5}, {2.9, -4.0}, {M_PI / 2, 1.0}};
  for (const auto& [q0, qd0] : states) {
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, q0), qd = Eigen::VectorXd::Constant(1, qd0);
    std::vector<BodyPose> P;
    treePoses(tree, q, qd, P);
    TreeWorkspace ws;
    Eigen::VectorXd qdd;
    treeAccelerations(m, tree, P, qd, Eigen::VectorXd(), ws, qdd);
    const JointReaction r = treeReactions(m, tree, P, qd, qdd, Eigen::VectorXd())[0];
    // The closed form from the pose alone.
    const Eigen::Vector3d rc = P[1].r, n = P[0].A * tree.links[0].axis, w = n * qd0;
    const Eigen::Vector3d alpha = n * (rc.cross(mass * gvec).dot(n) / J);
    const Eigen::Vector3d F = mass * (alpha.cross(rc) + w.cross(w.cross(rc)) - gvec);
    const Eigen::Vector3d e = rc / d;  // pivot -> centre
    const double radial = mass * (gvec.dot(e) + d * qd0 * qd0);  // towards the pivot
    const double across = mass * gvec.cross(e).norm() * (1.0 - mass * d * d / J);
    worst = std::max(worst, (r.force - F).norm() / F.norm());
    worst_radial = std::max({worst_radial, std::abs(-r.force.dot(e) - radial) / F.norm(),
                             std::abs((r.force - r.force.dot(e) * e).norm() - std::abs(across)) / F.norm()});
    worst_torque = std::max(worst_torque, r.torque.norm() / (F.norm() * l));
  }
  std::printf("[   info   ] pin force vs closed form %.2e relative (radial/tangential split %.2e), moment %.2e\n",
              worst, worst_radial, worst_torque);
  // Both sides are exact: rounding of a few operations on numbers of order 1-10.
  EXPECT_LT(worst, 1e-13);
  EXPECT_LT(worst_radial, 1e-13);
  EXPECT_LT(worst_torque, 1e-13);
}

// The tree's own start: the scene's placement and its velocities projected
// onto the tree's motions equal the constrained start (consistentStart: the
// assembly's mass-orthogonal velocity projection) on tree_3d.yaml, whose A
// is given an angular velocity off its joint's axis. The projection solves
// to 1e-13 relative (System::correctVelocities); the poses are as placed.
// A placement off by 1 micrometre declines with the joint named, and auto
// then runs constrained.
TEST(KinematicTree, StartsFromThePlacementAsTheConstrainedStart) {
  const Model m = loadScene(std::string(FLEXCOMP_DATA_DIR) + "/mbs-run/tree_3d.yaml");
  std::vector<std::string> log;
  const std::unique_ptr<Dynamics> tree = makeTreeDynamics(m);
  const Sample st = tree->sample(0.0, tree->start(1e-11, log));
  const std::unique_ptr<Dynamics> cons = makeConstrainedDynamics(m, "test");
  const Sample sc = cons->sample(0.0, cons->start(1e-11, log));
  double pos = 0.0, vel = 0.0, vscale = 0.0, reac = 0.0, rscale = 0.0;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    pos = std::max({pos, (st.bodies[b].position - sc.bodies[b].position).norm(),
                    (st.bodies[b].orientation - sc.bodies[b].orientation).norm()});
    vel = std::max({vel, (st.bodies[b].velocity - sc.bodies[b].velocity).norm(),
                    (st.bodies[b].angular_velocity - sc.bodies[b].angular_velocity).norm()});
    vscale = std::max(vscale, sc.bodies[b].angular_velocity.norm());
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    reac = std::max(reac, (st.joints[j].reaction_force - sc.joints[j].reaction_force).norm());
    rscale = std::max(rscale, sc.joints[j].reaction_force.norm());
    EXPECT_NEAR(st.joints[j].angle, sc.joints[j].angle, 1e-15) << m.joints[j].name;
  }
  std::printf("[   info   ] start: poses %.2e, velocities %.2e (of %.3g rad/s), reactions %.2e N (of %.3g N)\n", pos,
              vel, vscale, reac, rscale);
  EXPECT_LT(pos, 1e-15);
  EXPECT_GT((m.bodies[1].angular_velocity - sc.bodies[1].angular_velocity).norm(), 0.1);  // projected
  EXPECT_LT(vel, 1e-12 * vscale);
  EXPECT_LT(reac, 1e-9 * rscale);
  EXPECT_EQ(tree->formulation(), "tree");

  Model off = m;
  off.bodies[3].position.x() += 1e-6;  // C, 1 um off its joint JC on A
  const std::string why = treeUnsupported(off);
  EXPECT_EQ(why.rfind("joint JC does not hold as placed (misses by 1e-06 m or rad", 0), 0u) << why;
  off.settings.t_end = 0.01;
  const Results r = simulate(off, {true});
  EXPECT_EQ(r.formulation, "constrained (" + why + ")");
  EXPECT_EQ(r.status, "completed");
}

TEST(KinematicTree, DeclinesWhatItDoesNotSupport) {
  // A closed loop: the four-bar.
  Model m = sceneFromText(planarChain(3, "{t_end: 0.1}"));
  EXPECT_EQ(treeUnsupported(m), "");
  Joint loop = m.joints[0];
  loop.name = "close";
  loop.body_i = 3;
  loop.body_j = 0;
  m.joints.push_back(loop);
  const std::string why = treeUnsupported(m);  // which joint of the loop is met last depends on the search
  EXPECT_NE(why.find("closes a loop"), std::string::npos) << why;
  Model d = sceneFromText(planarChain(2, "{t_end: 0.1}"));
  d.joints[1].drive.active = true;
  EXPECT_EQ(treeUnsupported(d), "joint J1 is driven");
  Model f = sceneFromText(planarChain(2, "{t_end: 0.1}"));
  f.joints.pop_back();
  EXPECT_EQ(treeUnsupported(f), "body L1 is not joined to a fixed body (a floating base)");
  // formulation: tree on a scene it cannot run: constrained, with a warning.
  Model l = sceneFromText(planarChain(2, "{t_end: 0.05, formulation: tree}"));
  l.joints[1].limits.has_max = true;
  l.joints[1].limits.max = 3.0;
  const Results r = simulate(l, {true});
  EXPECT_EQ(r.formulation, "constrained (joint J1 has stops)");
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("formulation: tree is not possible here (joint J1 has stops)"), std::string::npos);
  // An unknown value is an input error naming the key and the choices.
  try {
    sceneFromText(planarChain(2, "{t_end: 0.1, formulation: minimal}"));
    ADD_FAILURE() << "formulation: minimal was accepted";
  } catch (const fc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected auto, tree or constrained, got 'minimal'"), std::string::npos)
        << e.what();
    EXPECT_NE(e.keyPath().find("formulation"), std::string::npos) << e.keyPath();
  }
}

}  // namespace
}  // namespace fc::mbs::test
