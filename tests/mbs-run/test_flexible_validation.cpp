// Validation of flexible bodies in mbs-run ("Done when"), on a
// uniform cantilever written by tests/mbs-run/beam_body.h (Hermite beam
// elements, lumped masses, clamped-root modes):
// - a damped cantilever under gravity settles at beam theory's q L^4 / (8 EI),
//   the modal truncation error falling as modes are added;
// - a very stiff flexible pendulum converges to the rigid compound pendulum
//   (1-DOF equation integrated by RK4 here) as 1/stiffness, with a bounded
//   number of steps;
// - a flexible beam pendulum agrees with a brute-force planar model of the
//   same lumped masses in minimal coordinates (no invariants, no constraints);
// - Kane, Ryan & Banerjee's spin-up beam: linear modes without geometric
//   stiffening stay bounded below the first bending frequency and diverge
//   above it (the known failure), both as the brute-force linear model does.
#include <gtest/gtest.h>

#include <string>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "beam_body.h"
#include "helpers.h"
#include "common/h5io.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/model/model.h"
#include "mbs-run/output/results.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

// Body-frame transverse tip deflection from the recorded modal coordinates.
double tipDeflection(const FlexBody& b, const Eigen::VectorXd& w) {
  const FlexInterface& tip = b.interface("tip");
  return tip.shapes.col(1).head(w.size()).dot(w);
}

// Rotation of a body about global z from its Euler parameters (planar motion).
double angleZ(const Eigen::Vector4d& p) { return 2.0 * std::atan2(p(3), p(0)); }

std::string beamScene(const std::string& file, int modes, double zeta, const std::string& joint,
                      const std::string& gravity, const std::string& sim) {
  char head[512];
  std::snprintf(head, sizeof head, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: %s, modes: %d, damping_ratio: %g}
joints:
  - %s
)",
                file.c_str(), modes, zeta, joint.c_str());
  return std::string(head) + (gravity.empty() ? "" : "forces:\n  - {type: gravity, g: " + gravity + "}\n") +
         "simulation: " + sim + "\n";
}

TEST(FlexibleValidation, DampedCantileverSettlesAtBeamTheoryDeflection) {
  BeamSpec s;  // L = 1 m, rho A = 1 kg/m, EI = 80 N m^2: first mode 5.4 Hz
  s.elements = 20;
  s.modes = 4;
  const BeamModel bm = cantileverBeam(s);
  const std::string file = writeBeam(bm, "cantilever");
  const double g = 9.81;
  const double exact = s.rho_a * g * std::pow(s.length, 4) / (8 * s.ei);
  // Gravity on the lumped masses as the engine applies it (along -y).
  Eigen::VectorXd F = Eigen::VectorXd::Zero(bm.K.rows());
  for (int k = 1; k <= s.elements; ++k) F(2 * k - 2) = -bm.node_mass(k) * g;
  const double fe_static = -bm.K.ldlt().solve(F)(2 * s.elements - 2);
  std::printf("[   info   ] q L^4/8EI = %.6e m; 20-element lumped FE static %.6e m (%.2e relative)\n", exact,
              fe_static, fe_static / exact - 1);
  // Lumped nodal loads on cubic elements: O(h^2) error, 1/(8 n^2)-ish; at
  // n = 20 it must be below 1e-3 (measured 3e-4 would do; this bound is the
  // discretisation, not the engine).
  EXPECT_NEAR(fe_static / exact, 1.0, 1e-3);

  double previous_error = 0.0;
  for (int n = 1; n <= s.modes; ++n) {
    // Critically damped modes (zeta = 1): the slowest decays as exp(-omega_1 t),
    // omega_1 = 34 rad/s, so 2 s leave exp(-68) of the initial transient.
    const Results r = simulate(sceneFromText(beamScene(file, n, 1.0,
                                                       "{name: clamp, type: fixed, bodies: [ground, beam], points: "
                                                       "[[0, 0, 0], root]}",
                                                       "[0, -9.81, 0]",
                                                       "{t_end: 2.0, output_step: 0.05, rtol: 1.0e-8}")),
                               {true});
    ASSERT_EQ(r.status, "completed");
    const double tip = -tipDeflection(bm.body, r.modal[1].back());
    // Modal truncation with n modes: sum_j phi_j(tip) phi_j^T F / omega_j^2.
    double modal = 0.0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd phi = bm.body.shapes.col(j);
      double fj = 0.0;
      for (int k = 1; k <= s.elements; ++k) fj += phi(6 * k + 1) * (-bm.node_mass(k) * g);
      modal -= phi(6 * s.elements + 1) * fj / bm.body.eigenvalues(j);
    }
    const double trunc = tip / fe_static - 1;
    std::printf("[   info   ] %d modes: settled tip deflection %.8e m, modal static %.8e m, truncation %+.2e, vs "
                "beam theory %+.2e, frame drift %.1e m, %ld steps\n",
                n, tip, modal, trunc, tip / exact - 1, r.position[1].back().norm(), r.steps);
    // Settled to the n-mode static solution: transient exp(-68), integrator
    // error at rtol 1e-8 on a 1.5e-2 m deflection.
    EXPECT_NEAR(tip, modal, 1e-7 * exact);
    // The truncation error alternates in sign (the modal loads of a uniform
    // load alternate against phi_j(tip): one mode overshoots by 1.3 %), and
    // its size is about the next term, which in beam theory goes as
    // phi_j(L) int(phi_j) / omega_j^2 ~ beta_j^-5, beta_j ~ (j - 1/2) pi: the
    // error from n to n + 1 modes falls at least by ((n + 1/2)/(n - 1/2))^5
    // (3.5 from 3 to 4 modes; 14.7, 5.8, 3.8 measured), so by 3x at least.
    if (n > 1) {
      EXPECT_LT(trunc * previous_error, 0.0);
      EXPECT_LT(std::abs(trunc), std::abs(previous_error) / 3);
    }
    previous_error = trunc;
    if (n == 1) { EXPECT_NEAR(trunc, 0.0, 0.02); }  // one mode carries 98.7 % (beam theory: 1.0131 q L^4/8EI)
    // Four modes: truncation (2e-5) + discretisation (8.3e-4, bound above).
    if (n == 4) { EXPECT_NEAR(tip / exact, 1.0, 1e-3); }
  }
  std::filesystem::remove(file);
}

// Rigid compound pendulum about z from the horizontal: I_o theta'' = -m g c cos(theta).
double rigidPendulumAngle(double I_o, double mgc, double t) {
  auto f = [&](double, const Eigen::VectorXd& y) {
    Eigen::VectorXd d(2);
    d << y(1), -mgc / I_o * std::cos(y(0));
    return d;
  };
  return rk4(f, Eigen::Vector2d(0, 0), 0.0, t, std::max(1, static_cast<int>(t / 1e-4)))(0);
}

TEST(FlexibleValidation, StiffPendulumConvergesToTheRigidOne) {
  double I_o = 0, mgc = 0;
  {
    BeamSpec s;
    s.elements = 10;
    const BeamModel bm = cantileverBeam(s);
    for (long k = 0; k < bm.body.nodeCount(); ++k) {
      I_o += bm.node_mass(k) * std::pow(bm.body.nodes(k, 0), 2) + bm.node_rotary(k);
      mgc += bm.node_mass(k) * 9.81 * bm.body.nodes(k, 0);
    }
  }
  struct Run {
    double err;
    long steps;
    std::string integrator;
  };
  // Modal damping 0.7: it leaves the quasi-static deflection (the 1/stiffness
  // error measured here) unchanged and ends the release transient within a
  // period. With zeta = 0.02 the stiff modes ring for 15 ms at 3.4e3 and
  // 2.1e4 rad/s, which TR-BDF2 resolves to rtol 1e-8 (accuracy, not
  // stability): 12 200 / 12 700 / 6 000 steps for scales 1 / 1e2 / 1e4, measured.
  auto run = [&](double scale, int modes, const char* integ, double rtol, double atol, double t_end) {
    BeamSpec s;
    s.elements = 10;
    s.modes = 2;
    s.stiffness_scale = scale;
    const std::string file = writeBeam(cantileverBeam(s), "stiff");
    char sim[160];
    std::snprintf(sim, sizeof sim, "{t_end: %g, output_step: 0.01, rtol: %g, atol: %g, integrator: %s}", t_end, rtol,
                  atol, integ);
    const Results r = simulate(
        sceneFromText(beamScene(file, modes, 0.7,
                                "{name: pivot, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], root], "
                                "axes: [[0, 0, 1], [0, 0, 1]]}",
                                "[0, -9.81, 0]", sim)),
        {true});
    std::filesystem::remove(file);
    EXPECT_EQ(r.status, "completed");
    Run out{0.0, r.steps, r.integrator};
    for (double t : {0.25, 0.5, 0.75, 1.0}) {
      if (t > t_end + 1e-12) break;
      const std::size_t k = rowAt(r.time, t);
      out.err = std::max(out.err, std::abs(angleZ(r.orientation[1][k]) - rigidPendulumAngle(I_o, mgc, r.time[k])));
    }
    std::printf("[   info   ] stiffness x %.0e, %d modes, %s rtol %.0e: angle error vs rigid pendulum %.3e rad, %ld "
                "steps\n",
                scale, modes, integ, rtol, out.err, r.steps);
    return out;
  };
  // Accuracy: Dormand-Prince at rtol 1e-8, atol 1e-8 (its error on the rigid
  // body is ~1e-9 rad, far below the elastic effect at every scale), over the
  // first 0.25 s: its step follows the stiffest mode (h omega_2 ~ 0.07, 297 000
  // steps per second at scale 1e4, measured), which is the cost TR-BDF2 avoids.
  const Run e1 = run(1.0, 2, "dopri5", 1e-8, 1e-8, 0.25), e2 = run(1e2, 2, "dopri5", 1e-8, 1e-8, 0.25),
            e4 = run(1e4, 2, "dopri5", 1e-8, 1e-8, 0.25);
  // The elastic deflection, and so the angle error, scales as 1/stiffness:
  // each factor 100 must buy at least a factor 30.
  EXPECT_LT(e2.err, e1.err / 30);
  EXPECT_LT(e4.err, e2.err / 30);
  // Step count: the explicit method's grows with the stiffest mode (stability
  // limit 3.3/omega); TR-BDF2 (L-stable) at rtol 1e-8 needs at most 3x the
  // rigid body's (`modes: 0`) steps at scale 1e4, and fewer than at scale 1
  // (measured 2 114 / 1 045 for scales 1 / 1e4, rigid 542).
  const Run rigid = run(1.0, 0, "trbdf2", 1e-8, 1e-11, 1.0), t1 = run(1.0, 2, "trbdf2", 1e-8, 1e-11, 1.0),
            t4 = run(1e4, 2, "trbdf2", 1e-8, 1e-11, 1.0);
  EXPECT_LT(t4.steps, 3 * rigid.steps);
  EXPECT_LT(t4.steps, t1.steps);
  EXPECT_LT(t4.steps, e4.steps / 3);  // dopri5 needs more in a quarter of the time
  // At rtol 1e-8 TR-BDF2's own error (~5e-6 rad here, order 2) hides the
  // elastic part at scale 1e4; it must still be at the rigid run's level.
  EXPECT_LT(t4.err, 2 * rigid.err + e4.err);

  // `integrator: auto` cannot see modal stiffness in the scene (joints may
  // clamp it); the run finds it: Dormand-Prince held at its stability
  // boundary with steps below 1.6 ms tries the IMEX method (modal stiffness
  // implicit, switch_trial.h) and hands over since it is cheaper and agrees.
  // The stiff beam must switch, take a fraction of dopri5's steps at the
  // same tolerance, and stay as close to the rigid pendulum; the rigid body
  // must not switch (the candidate was TR-BDF2 before, 166 steps
  // and ~1e-5 rad; IMEX 334 steps and 1.2e-7 rad, measured).
  const Run d6 = run(1e4, 2, "dopri5", 1e-6, 1e-9, 0.25), a6 = run(1e4, 2, "auto", 1e-6, 1e-9, 0.25),
            a0 = run(1.0, 0, "auto", 1e-6, 1e-9, 0.25);
  EXPECT_EQ(d6.integrator, "dopri5");
  EXPECT_EQ(a6.integrator, "dopri5+imex");
  EXPECT_EQ(a0.integrator, "dopri5");
  EXPECT_LT(a6.steps, d6.steps / 5);
  // Both errors are the elastic deflection (~1e-7 rad at scale 1e4, e4 above)
  // plus the integration error at rtol 1e-6 (IMEX, order 3: below 1e-6 rad).
  EXPECT_LT(a6.err, 1e-6);
}

TEST(FlexibleValidation, HingedBodyWantsPinnedModes) {
  // A body on a revolute with clamped-root modes: the free frame rotation and
  // the modes together nearly span the rigid rotation shape, so the coupled
  // system has a mode far above the clamped frequencies (near 1e5 rad/s
  // against omega_2 = 2.1e3, from dopri5's stability-limited step) and an
  // explicit integrator's step follows it. Modes with the hinge's own
  // reference condition (pinned root, rigid rotation removed) are orthogonal
  // to the frame rotation: same physics, no such mode.
  double I_o = 0, mgc = 0;
  std::vector<double> err;
  std::vector<long> steps;
  for (bool pinned : {false, true}) {
    BeamSpec s;
    s.elements = 10;
    s.modes = 2;
    s.stiffness_scale = 1e2;
    s.pinned_root = pinned;
    const BeamModel bm = cantileverBeam(s);
    if (I_o == 0)
      for (long k = 0; k < bm.body.nodeCount(); ++k) {
        I_o += bm.node_mass(k) * std::pow(bm.body.nodes(k, 0), 2) + bm.node_rotary(k);
        mgc += bm.node_mass(k) * 9.81 * bm.body.nodes(k, 0);
      }
    if (pinned) { EXPECT_LT(bm.body.interface("root").shapes.leftCols(3).norm(), 1e-15); }  // pin: no translation
    const std::string file = writeBeam(bm, pinned ? "pinned" : "clamped");
    const Results r = simulate(
        sceneFromText(beamScene(file, 2, 0.7,
                                "{name: pivot, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], root], "
                                "axes: [[0, 0, 1], [0, 0, 1]]}",
                                "[0, -9.81, 0]",
                                "{t_end: 0.25, output_step: 0.01, rtol: 1.0e-8, atol: 1.0e-8, integrator: dopri5}")),
        {true});
    std::filesystem::remove(file);
    ASSERT_EQ(r.status, "completed");
    err.push_back(std::abs(angleZ(r.orientation[1].back()) - rigidPendulumAngle(I_o, mgc, r.time.back())));
    steps.push_back(r.steps);
    std::printf("[   info   ] stiffness x 1e2, %s root modes: angle error vs rigid pendulum %.3e rad, %ld steps\n",
                pinned ? "pinned" : "clamped", err.back(), r.steps);
  }
  // Both converge to the rigid pendulum at this stiffness (elastic error
  // ~1e-5 rad, the stiff-pendulum test), so they agree to that order...
  EXPECT_LT(err[0], 3e-5);
  EXPECT_LT(err[1], 3e-5);
  // ... and the pinned modes cost at least 10x fewer steps (measured 7 434
  // against 342).
  EXPECT_LT(10 * steps[1], steps[0]);
}

void flexiblePendulumMatchesBruteForcePlanarModel(bool node_form) {
  BeamSpec s;
  s.elements = 12;
  s.modes = 3;
  s.ei = 20.0;  // softer: first mode 2.7 Hz, tip deflection ~10 % of L while swinging
  const BeamModel bm = cantileverBeam(s);
  const std::string file = writeBeam(bm, "pendulum");
  Model m = sceneFromText(beamScene(file, 3, 0.0,
                                    "{name: pivot, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], root], "
                                    "axes: [[0, 0, 1], [0, 0, 1]]}",
                                    "[0, -9.81, 0]", "{t_end: 1.2, output_step: 0.01, rtol: 1.0e-10}"));
  // Both forms of the inertia's second-order terms against the reference
  // (3 modes on 12 nodes load with the invariants; the node form forced).
  ASSERT_FALSE(m.bodies[1].flex->nodal);
  if (node_form) {
    auto f = std::make_shared<FlexibleBodyData>(*m.bodies[1].flex);
    f->nodal = std::make_shared<NodalInertia>(nodalInertia(bm.body, 3));
    m.bodies[1].flex = f;
  }
  const Results r = simulate(m, {true});
  ASSERT_EQ(r.status, "completed");
  PlanarBeam ref{bm.body, 3, Eigen::Vector2d(0, -9.81), {}};
  auto f = [&](double, const Eigen::VectorXd& y) {
    Eigen::VectorXd d(8);
    d.head(4) = y.tail(4);
    d.tail(4) = ref.accel(y.head(4), y.tail(4));
    return d;
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(8);
  double t = 0, err_angle = 0, err_tip = 0, tip_max = 0;
  for (double tc : {0.3, 0.6, 0.9, 1.2}) {
    y = rk4(f, y, t, tc, static_cast<int>(std::lround((tc - t) / 2e-5)));
    t = tc;
    const std::size_t k = rowAt(r.time, tc);
    const double tip_ref = tipDeflection(bm.body, y.segment(1, 3));
    err_angle = std::max(err_angle, std::abs(angleZ(r.orientation[1][k]) - y(0)));
    err_tip = std::max(err_tip, std::abs(tipDeflection(bm.body, r.modal[1][k]) - tip_ref));
    tip_max = std::max(tip_max, std::abs(tip_ref));
  }
  std::printf("[   info   ] flexible pendulum vs planar brute force: angle %.2e rad, tip deflection %.2e m (of "
              "%.3g m), %ld steps (%s)\n",
              err_angle, err_tip, tip_max, r.steps, node_form ? "node form" : "invariants");
  EXPECT_GT(tip_max, 1e-3);  // the beam really bends (4.8 mm, 0.5 % of L)
  // Both solve the same equations to rtol 1e-10 (RK4 at h = 2e-5 s against
  // omega_3 = 300 rad/s: local error (h omega)^5 / 120 ~ 1e-14 per step);
  // 1e-8 allows for the error growth of the swing over 1.2 s.
  EXPECT_LT(err_angle, 1e-8);
  EXPECT_LT(err_tip, 1e-8);
  std::filesystem::remove(file);
}

TEST(FlexibleValidation, FlexiblePendulumMatchesBruteForcePlanarModel) { flexiblePendulumMatchesBruteForcePlanarModel(false); }
TEST(FlexibleValidation, FlexiblePendulumNodeFormMatchesBruteForcePlanarModel) {
  flexiblePendulumMatchesBruteForcePlanarModel(true);
}

// Many modes on few nodes (40 pinned-root modes of a 24-element beam: 24
// nodal rows) load with the node form, and a run with it is the run with the
// invariants to rounding: the same right-hand side, the same steps.
TEST(FlexibleValidation, ManyModesLoadTheNodeFormAndRunAsTheInvariants) {
  BeamSpec s;
  s.elements = 24;
  s.modes = 40;
  s.ei = 20.0;
  s.pinned_root = true;
  const BeamModel bm = cantileverBeam(s);
  const std::string file = writeBeam(bm, "nodeform");
  const Model m = sceneFromText(beamScene(file, 40, 0.0,
                                          "{name: pivot, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], "
                                          "root], axes: [[0, 0, 1], [0, 0, 1]]}",
                                          "[0, -9.81, 0]", "{t_end: 0.05, output_step: 0.01, rtol: 1.0e-8, integrator: imex}"));
  ASSERT_TRUE(m.bodies[1].flex->nodal);
  EXPECT_EQ(m.bodies[1].flex->nodal->rows(), 24);  // y of nodes 1..24; the pin's node does not move
  Model mi = m;
  auto f = std::make_shared<FlexibleBodyData>(*m.bodies[1].flex);
  f->nodal.reset();
  mi.bodies[1].flex = f;
  const Results a = simulate(m, {true}), b = simulate(mi, {true});
  ASSERT_EQ(a.status, "completed");
  ASSERT_EQ(b.status, "completed");
  // Rounding-level differences of the right-hand side (1e-12 relative, see
  // test_nodal_inertia.cpp) grow by the error control's step choices at most
  // to the order of the local error, rtol 1e-8 x the 0.05 rad swing and the
  // ~1e-4 m deflection: 1e-10 rad and 1e-12 m, a thousandth of what any
  // wrong term would make of the tip.
  EXPECT_NEAR(angleZ(a.orientation[1].back()), angleZ(b.orientation[1].back()), 1e-10);
  EXPECT_NEAR(tipDeflection(bm.body, a.modal[1].back()), tipDeflection(bm.body, b.modal[1].back()), 1e-12);
  std::printf("[   info   ] node form vs invariants, 40 modes: %ld / %ld steps, %.3g / %.3g s CPU, tip %.6e m\n", a.steps,
              b.steps, a.cpu_seconds, b.cpu_seconds, tipDeflection(bm.body, a.modal[1].back()));
  std::filesystem::remove(file);
}

TEST(FlexibleValidation, FlexibleDoublePendulumMatchesBruteForceChain) {
  // Two beams, the second hinged at the first's deforming tip: the joint
  // point moves with beam 1's modes (interface shapes), which the single
  // pendulum (hinged at the clamped root) does not exercise.
  BeamSpec s1, s2;
  s1.elements = 10;
  s1.modes = 2;
  s1.ei = 20.0;
  s2.elements = 8;
  s2.modes = 2;
  s2.length = 0.8;
  s2.ei = 10.0;
  const BeamModel bm1 = cantileverBeam(s1), bm2 = cantileverBeam(s2);
  const std::string f1 = writeBeam(bm1, "dp1"), f2 = writeBeam(bm2, "dp2");
  const Results r = simulate(sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: one
    flexible: {file: )" + f1 + R"(, modes: 2}
  - name: two
    flexible: {file: )" + f2 + R"(, modes: 2}
    position: [1.0, 0, 0]
joints:
  - {name: R1, type: revolute, bodies: [ground, one], points: [[0, 0, 0], root], axes: [[0, 0, 1], [0, 0, 1]]}
  - {name: R2, type: revolute, bodies: [one, two], points: [tip, root], axes: [[0, 0, 1], [0, 0, 1]]}
forces:
  - {type: gravity, g: [0, -9.81, 0]}
simulation: {t_end: 1.0, output_step: 0.01, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  PlanarDoubleBeam ref{bm1.body, bm2.body, 2, 2, Eigen::Vector2d(0, -9.81)};
  auto f = [&](double, const Eigen::VectorXd& y) {
    Eigen::VectorXd d(12);
    d.head(6) = y.tail(6);
    d.tail(6) = ref.accel(y.head(6), y.tail(6));
    return d;
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(12);
  double t = 0, err_angle = 0, err_tip = 0, tip_max = 0;
  for (double tc : {0.25, 0.5, 0.75, 1.0}) {
    y = rk4(f, y, t, tc, static_cast<int>(std::lround((tc - t) / 2e-5)));
    t = tc;
    const std::size_t k = rowAt(r.time, tc);
    err_angle = std::max({err_angle, std::abs(std::remainder(angleZ(r.orientation[1][k]) - y(0), 2 * M_PI)),
                          std::abs(std::remainder(angleZ(r.orientation[2][k]) - y(3), 2 * M_PI))});
    const double tip1 = tipDeflection(bm1.body, y.segment(1, 2)), tip2 = tipDeflection(bm2.body, y.segment(4, 2));
    err_tip = std::max({err_tip, std::abs(tipDeflection(bm1.body, r.modal[1][k]) - tip1),
                        std::abs(tipDeflection(bm2.body, r.modal[2][k]) - tip2)});
    tip_max = std::max({tip_max, std::abs(tip1), std::abs(tip2)});
  }
  std::printf("[   info   ] flexible double pendulum vs planar brute-force chain: angles %.2e rad, tip deflections "
              "%.2e m (of %.3g m), violation %.1e, %ld steps\n",
              err_angle, err_tip, tip_max, r.max_violation, r.steps);
  EXPECT_GT(tip_max, 1e-3);  // the beams really bend
  // Same equations at rtol 1e-10 and RK4 h = 2e-5 s (omega_2 ~ 300 rad/s:
  // (h omega)^5/120 ~ 1e-14 per step); 1e-8 for the growth of errors in a
  // double pendulum over 1 s.
  EXPECT_LT(err_angle, 1e-8);
  EXPECT_LT(err_tip, 1e-8);
  std::filesystem::remove(f1);
  std::filesystem::remove(f2);
}

TEST(FlexibleValidation, SpinUpDriveLaw) {
  // Kane's law: rate (Os/T)(t - (T/2 pi) sin(2 pi t/T)) for t < T, then Os.
  Drive d;
  d.active = true;
  d.spin_rate = 6.0;
  d.spin_time = 15.0;
  for (double t : {0.0, 3.0, 7.5, 14.0, 15.0, 20.0}) {
    const double rate = t < 15 ? 6.0 / 15 * (t - 15 / (2 * M_PI) * std::sin(2 * M_PI * t / 15)) : 6.0;
    EXPECT_NEAR(d.rate(t), rate, 1e-14);
    // Angle and acceleration consistent with the rate (central differences,
    // h = 1e-4: truncation h^2 max|rate'''| / 6 ~ 1e-9, rounding 1e-16 x 45 rad / h ~ 1e-10).
    const double h = 1e-4;
    if (t > 0) {
      EXPECT_NEAR((d.angle(t + h) - d.angle(t - h)) / (2 * h), d.rate(t), 1e-8);
      EXPECT_NEAR((d.rate(t + h) - d.rate(t - h)) / (2 * h), d.accel(t), 1e-8);
    }
  }
  EXPECT_EQ(d.angle(0.0), 0.0);
  EXPECT_NEAR(d.angle(15.0), 6.0 * 15 / 2, 1e-12);  // the mean rate over the spin-up is Os/2
  try {
    sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: a, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}}
joints:
  - {name: hub, type: revolute, bodies: [ground, a], points: [[0,0,0],[0,0,0]], axes: [[0,0,1],[0,0,1]],
     drive: {spin_up: {rate: 6, time: -1}}}
)");
    ADD_FAILURE() << "a negative spin-up time was accepted";
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test.yaml:7"), std::string::npos) << msg;
    EXPECT_NE(msg.find("time"), std::string::npos) << msg;
    EXPECT_NE(msg.find("> 0"), std::string::npos) << msg;
  }
}

// Kane, Ryan & Banerjee (1987): L = 10 m, rho A = 1.2 kg/m, EI = 14 000 N m^2
// (E = 7e10 Pa, I = 2e-7 m^4), first bending frequency
// 1.875^2 sqrt(EI / rho A L^4) = 3.80 rad/s; spin-up over T = 15 s to Os.
struct SpinUp {
  double tip_max = 0, tip_end = 0, ref_max = 0, diff = 0;
  double t_cross = -1, t_cross_ref = -1;  // first output time with |tip| > 10 m
  Results r;
};

SpinUp spinUp(const BeamModel& bm, const std::string& file, double Os, double t_end) {
  const double T = 15.0;
  char joint[400], sim[200];
  std::snprintf(joint, sizeof joint,
                "{name: hub, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], root], axes: [[0, 0, 1], "
                "[0, 0, 1]], drive: {angle0: 0.0, spin_up: {rate: %g, time: %g}}}",
                Os, T);
  std::snprintf(sim, sizeof sim, "{t_end: %g, output_step: 0.05, rtol: 1.0e-9}", t_end);
  SpinUp out;
  out.r = simulate(sceneFromText(beamScene(file, 4, 0.0, joint, "", sim)), {true});
  Drive d;
  d.active = true;
  d.spin_rate = Os;
  d.spin_time = T;
  PlanarBeam ref{bm.body, 4, Eigen::Vector2d::Zero(), {}};
  auto f = [&](double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd q = y.head(5), qd = y.tail(5);
    q(0) = d.angle(t);
    qd(0) = d.rate(t);
    Eigen::VectorXd dy(10);
    dy.head(5) = qd;
    dy.tail(5) = ref.accel(q, qd, true, d.accel(t));
    return dy;
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(10);
  double t = 0;
  for (std::size_t k = 0; k < out.r.time.size(); ++k) {
    const double tk = out.r.time[k];
    if (tk > t) y = rk4(f, y, t, tk, std::max(1, static_cast<int>(std::lround((tk - t) / 1e-3))));
    t = tk;
    const double tip = tipDeflection(bm.body, out.r.modal[1][k]);
    const double tip_ref = tipDeflection(bm.body, y.segment(1, 4));
    EXPECT_TRUE(std::isfinite(tip));
    out.tip_max = std::max(out.tip_max, std::abs(tip));
    out.ref_max = std::max(out.ref_max, std::abs(tip_ref));
    // Compared while the deflection is below the beam's length: beyond, the
    // exponential growth amplifies any difference (and nothing is physical).
    if (std::abs(tip_ref) < 10.0)
      out.diff = std::max(out.diff, std::abs(tip - tip_ref) / std::max(1.0, std::abs(tip_ref)));
    if (out.t_cross < 0 && std::abs(tip) > 10.0) out.t_cross = tk;
    if (out.t_cross_ref < 0 && std::abs(tip_ref) > 10.0) out.t_cross_ref = tk;
    out.tip_end = tip;
  }
  return out;
}

TEST(FlexibleValidation, KaneSpinUpBeamLinearModesFailAboveFirstFrequency) {
  BeamSpec s;
  s.length = 10.0;
  s.rho_a = 1.2;
  s.ei = 14000.0;
  s.elements = 20;
  s.modes = 4;
  const BeamModel bm = cantileverBeam(s);
  const double w1 = std::sqrt(bm.body.eigenvalues(0));
  // Beam theory's first frequency; 20 lumped-mass elements are 1.6e-3 low
  // (O(h^2) from lumping, measured), so 3e-3.
  EXPECT_NEAR(w1, 1.8751 * 1.8751 * std::sqrt(s.ei / (s.rho_a * std::pow(s.length, 4))), 3e-3 * w1);
  const std::string file = writeBeam(bm, "kane");

  // Below: Os = 2 rad/s < omega_1 = 3.80 rad/s. The linear model is bounded
  // (its chordwise stiffness omega_1^2 - Os^2 stays positive).
  const SpinUp slow = spinUp(bm, file, 2.0, 20.0);
  ASSERT_EQ(slow.r.status, "completed");
  std::printf("[   info   ] Kane spin-up Os = 2 rad/s: largest tip deflection %.4e m (reference %.4e m), "
              "difference %.2e, %ld steps\n",
              slow.tip_max, slow.ref_max, slow.diff, slow.r.steps);
  EXPECT_LT(slow.tip_max, 0.05 * s.length);
  // Engine vs brute-force planar model of the same beam (RK4, h = 1 ms
  // against omega_4 = 130 rad/s: error ~ (0.13)^4 / 120 per unit time ~ 1e-6
  // relative at worst); engine at rtol 1e-9.
  EXPECT_LT(slow.diff, 1e-5 * std::max(1.0, slow.ref_max) + 1e-5 * slow.ref_max);

  // Above: Os = 10 rad/s. Once the rate passes omega_1 (t ~ 8 s) the linear
  // model's chordwise stiffness omega_1^2 - Omega^2 is negative and the tip
  // deflection grows exponentially, at ~sqrt(Omega^2 - omega_1^2): the known
  // failure of linear modes without geometric (centrifugal) stiffening; the
  // real beam stiffens and its deflection stays a small fraction of L.
  const SpinUp fast = spinUp(bm, file, 10.0, 11.0);
  std::printf("[   info   ] Kane spin-up Os = 10 rad/s: status '%s', tip deflection %.3e m at %.2f s (reference "
              "%.3e m); |tip| > L at %.2f s (reference %.2f s); difference until then %.2e\n",
              fast.r.status.c_str(), fast.tip_end, fast.r.time.back(), fast.ref_max, fast.t_cross, fast.t_cross_ref,
              fast.diff);
  // Same linear equations: the engine and the brute-force model agree until
  // the deflection reaches the beam's length, and cross it at the same time.
  EXPECT_LT(fast.diff, 1e-4);
  EXPECT_NEAR(fast.t_cross, fast.t_cross_ref, 0.051);
  // Diverged: more than the beam's length (an impossible linear deflection),
  // or the run stopped with a diagnosis; never NaN (checked per row above).
  EXPECT_TRUE(fast.tip_max > s.length || fast.r.status != "completed");
  EXPECT_GT(fast.ref_max, s.length);  // the independent linear model diverges too
  std::filesystem::remove(file);
}

// Initial modal state (`modal_coordinates`, `modal_velocities`): a clamped
// beam (frame held by a fixed joint at the root, clamped modes) without
// gravity or damping decouples into modal oscillators, q_j'' + omega_j^2 q_j
// = 0, so mode 1 started at q0 with rate v0 follows q0 cos(w t) + v0/w sin(w t)
// and the others stay at rest.
TEST(FlexibleValidation, InitialModalStateStartsTheModalOscillators) {
  BeamSpec s;
  s.elements = 10;
  s.modes = 3;
  const BeamModel bm = cantileverBeam(s);
  const std::string file = writeBeam(bm, "modal0");
  const double w1 = std::sqrt(bm.body.eigenvalues(0)), q0 = 2e-3, v0 = -0.05;
  const double period = 2 * M_PI / w1;
  char scene[1024];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: %s, modes: 3}
    modal_coordinates: [%.17g, 0, 0]
    modal_velocities: [%.17g, 0, 0]
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
simulation: {t_end: %.17g, output_step: %.17g, rtol: 1.0e-10}
)",
                file.c_str(), q0, v0, 1.25 * period, period / 40);
  const Results r = simulate(sceneFromText(scene), {true});
  ASSERT_EQ(r.status, "completed");
  double err = 0.0, others = 0.0;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const double t = r.time[k];
    err = std::max(err, std::abs(r.modal[1][k](0) - (q0 * std::cos(w1 * t) + v0 / w1 * std::sin(w1 * t))));
    others = std::max(others, r.modal[1][k].tail(2).cwiseAbs().maxCoeff());
  }
  std::printf("[   info   ] omega_1 %.4g rad/s: mode-1 error %.2e (amplitude %.2e), other modes %.2e\n", w1, err,
              std::hypot(q0, v0 / w1), others);
  // rtol 1e-10 on an exactly linear system: the error is the integration's.
  EXPECT_LT(err, 1e-8 * std::hypot(q0, v0 / w1));  // measured 1e-10 relative: two decades of margin
  EXPECT_LT(others, 1e-10);
  // Wrong length: a located error naming the key and the count expected.
  std::string bad = scene;
  bad.replace(bad.find("modal_velocities: ["), std::string("modal_velocities: [").size(), "modal_velocities: [1, ");
  try {
    sceneFromText(bad);
    FAIL() << "expected an InputError";
  } catch (const fc::InputError& e) {
    EXPECT_NE(e.keyPath().find("modal_velocities"), std::string::npos) << e.keyPath();
    EXPECT_NE(std::string(e.what()).find("expected a list of 3 numbers, got 4"), std::string::npos) << e.what();
  }
  std::filesystem::remove(file);
}

// Modal energy per mode: on the clamped beam without gravity or
// damping the modes are decoupled oscillators, so a mode started alone keeps
// E_j = 1/2 omega_j^2 q0^2 + 1/2 v0^2 and the others stay at zero; with the
// frame held, the body's kinetic energy is 1/2 |qdot|^2 (M-orthonormal modes),
// so sum_j E_j = /energy/kinetic + /energy/strain at every row. The summary's
// share of the highest quarter of the modes (here mode 3 of 3) is 0 when only
// mode 1 moves and 1 when only mode 3 does.
TEST(FlexibleValidation, ModalEnergyPerModeIsConstantForAFreeModeAndSumsToTheBodysEnergy) {
  BeamSpec s;
  s.elements = 10;
  s.modes = 3;
  const BeamModel bm = cantileverBeam(s);
  const std::string file = writeBeam(bm, "modal_energy");
  for (int mode : {0, 2}) {
    const double w = std::sqrt(bm.body.eigenvalues(mode)), q0 = 2e-3, v0 = -0.05;
    double q[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    q[mode] = q0;
    v[mode] = v0;
    char scene[1024];
    std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: %s, modes: 3}
    modal_coordinates: [%.17g, %.17g, %.17g]
    modal_velocities: [%.17g, %.17g, %.17g]
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
simulation: {t_end: %.17g, output_step: %.17g, rtol: 1.0e-10}
)",
                  file.c_str(), q[0], q[1], q[2], v[0], v[1], v[2], 1.25 * 2 * M_PI / w, 2 * M_PI / w / 40);
    const Model m = sceneFromText(scene);
    const Results r = simulate(m, {true});
    ASSERT_EQ(r.status, "completed");
    const std::string out = (std::filesystem::temp_directory_path() / ("modal_energy_" + std::to_string(::getpid()) + ".h5")).string();
    writeResults(out, m, r, "test");
    fc::H5File f(out, fc::H5File::Mode::Read);
    const Eigen::MatrixXd E = f.readMatrix("/bodies/beam/modal_energy");
    const Eigen::VectorXd kinetic = f.readVector("/energy/kinetic"), strain = f.readVector("/energy/strain");
    ASSERT_EQ(E.cols(), 3);
    ASSERT_EQ(E.rows(), kinetic.size());
    const double e0 = 0.5 * w * w * q0 * q0 + 0.5 * v0 * v0;
    double drift = 0.0, others = 0.0, balance = 0.0;
    for (long k = 0; k < E.rows(); ++k) {
      drift = std::max(drift, std::abs(E(k, mode) / e0 - 1));
      for (int j = 0; j < 3; ++j)
        if (j != mode) others = std::max(others, E(k, j));
      balance = std::max(balance, std::abs(E.row(k).sum() - kinetic(k) - strain(k)) / e0);
    }
    std::printf("[   info   ] mode %d alone: E = %.6e J, drift %.2e, other modes %.2e J, |sum E - T - U| / E %.2e\n",
                mode + 1, e0, drift, others, balance);
    // rtol 1e-10 on an exactly linear system: the energy's error is the
    // integration's (relative 1e-10 measured on the coordinate, the previous test).
    EXPECT_LT(drift, 1e-8);
    EXPECT_LT(others, 1e-18 * e0 + 1e-20);
    EXPECT_LT(balance, 1e-9);  // the same state evaluated twice: round-off plus the frame's (zero) motion
    const Eigen::VectorXd peaks = f.readVector("/bodies/beam/modal_energy_peak");
    EXPECT_NEAR(peaks(mode), E.col(mode).maxCoeff(), 1e-15 * e0);
    const double share = f.doubleAttribute("/bodies/beam", "highest_modes_energy_share");
    EXPECT_NEAR(share, mode == 2 ? 1.0 : 0.0, 1e-12);
    std::filesystem::remove(out);
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace fc::mbs::test
