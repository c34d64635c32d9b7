// Stops on revolute joints, against closed forms:
// - the impulse kernel: the velocity jump of a constrained system keeps the
//   other constraints, reverses the stop's rate by e and loses (1 - e^2) of
//   the approach energy of the relative motion, also with redundant rows;
// - a pendulum falling onto a stop hits it at the time and rate of the
//   free pendulum (quadrature of the energy integral), rebounds with e w,
//   each flight returns at the rate it left (so the impact rates follow e^k
//   and the rise heights e^2k), rests once the remaining bounces fit in one
//   integrator step, and then the stop holds the static torque m g L/2 cos;
// - a rotor driven into a stop by a constant torque (the rotational bouncing
//   ball) bounces at the closed-form times and rates and rests at its Zeno
//   time t1 + 2 e v1 / ((1 - e) a) with the static torque;
// - a stop_only revolute beside two spherical joints on its axis (the
//   flexible SAR's hinge) gives the same impact;
// - energy over many elastic (e = 1) impacts between two stops is conserved;
// - an arm on a spinning platform rests on a stop with the torque of the
//   rotating frame's statics (gravity against the centrifugal moment) and
//   leaves it when that torque reaches zero, at the closed-form time;
// - a plastic stop holds a body pushed into it (statics) and lets it go at
//   the moment a pull exceeds the push, the motion after that in closed form;
// - a latch (an angle-crossing event that locks) stops the joint at the
//   crossing with the plastic loss in the dissipated energy;
// - two free bodies colliding at an internal stop keep their linear and
//   angular momentum (the impulse is internal: only the constrained system's
//   momentum balance can give that);
// - a flexible beam hitting a stop: the impulse enters at the joint
//   interface, the modes are excited, and T + U + dissipated is conserved;
// - bad limits are reported at their key.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "beam_body.h"
#include "common/input.h"
#include "common/rotations.h"
#include "helpers.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/run/joint_limits.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

TEST(JointLimitsKernel, ImpulseKeepsConstraintsAndReversesTheRate) {
  // Three coordinates, an SPD mass matrix, one constraint row twice
  // (redundant) and the stop row g.
  Eigen::Matrix3d M;
  M << 4, 1, 0.5, 1, 3, 0.2, 0.5, 0.2, 2;
  Eigen::MatrixXd Phi(2, 3);
  Phi << 1, -1, 0.5, 2, -2, 1;  // the second row is twice the first
  Eigen::RowVectorXd g(3);
  g << 0.3, 1.0, -0.7;
  // A v- that satisfies Phi v = 0.
  Eigen::Vector3d v(1.0, 2.0, 2.0);
  ASSERT_NEAR((Phi * v).norm(), 0.0, 1e-14);
  Eigen::VectorXd phit = Eigen::VectorXd::Zero(2);
  for (double e : {0.0, 0.3, 1.0}) {
    const double rate = g.dot(v);
    const ImpactSolution s = constrainedImpact(M, Phi, phit, g, v, -e * rate);
    EXPECT_NEAR((Phi * s.v_plus).norm(), 0.0, 1e-13);
    EXPECT_NEAR(g.dot(s.v_plus), -e * rate, 1e-13);
    // M dv = Phi^T mu + g^T P: dv is M^-1 times a combination of the rows,
    // so M dv - g^T P lies in the row space of Phi: orthogonal to its null space.
    const Eigen::Vector3d r = M * (s.v_plus - v) - g.transpose() * s.impulse;
    const Eigen::Vector3d nullv = Eigen::Vector3d(1, 1, 0);  // Phi * [1,1,0] = 0
    EXPECT_NEAR(r.dot(nullv), 0.0, 1e-12);
    // Energy: in the one-dimensional motion left by Phi, the rate's kinetic
    // energy is 1/2 m_eff rate^2 with the effective mass along it, so the
    // loss is (1 - e^2) of it. m_eff from the constrained mobility: motions
    // with Phi u = 0 form span{n1, n2}; the loss is that of an impact of
    // a 2-DOF system along g, 1/2 (1 - e^2) rate^2 / (g N (N^T M N)^-1 N^T g^T).
    Eigen::Matrix<double, 3, 2> N;
    N.col(0) = nullv;
    N.col(1) = Eigen::Vector3d(0, 1, 2);  // Phi * [0,1,2] = 0
    ASSERT_NEAR((Phi * N).norm(), 0.0, 1e-14);
    const double w = (g * N * (N.transpose() * M * N).inverse() * N.transpose() * g.transpose())(0, 0);
    const double loss = 0.5 * v.dot(M * v) - 0.5 * s.v_plus.dot(M * s.v_plus);
    EXPECT_NEAR(loss, 0.5 * (1 - e * e) * rate * rate / w, 1e-12) << e;
    EXPECT_NEAR(s.impulse, -(1 + e) * rate / w, 1e-12) << e;
  }
}

TEST(JointLimitsKernel, RestRule) {
  EXPECT_TRUE(shouldRest(0.0, 5.0, -1.0, 1e-9));   // plastic: always (a pull releases it afterwards)
  EXPECT_FALSE(shouldRest(0.5, 1e-6, -1.0, 1e-9));  // pulled away: it leaves
  EXPECT_TRUE(shouldRest(0.5, 1e-5, 10.0, 1e-9));   // apex 5e-12 rad < 1e-9
  EXPECT_FALSE(shouldRest(0.5, 1e-3, 10.0, 1e-9));  // apex 5e-8 rad > 1e-9
  // The remaining bounces last 2 e|v-| / ((1 - e) a) = 2 * 1e-3 / (0.5 * 10) = 4e-4 s:
  EXPECT_DOUBLE_EQ(zenoRemainder(0.5, 1e-3, 10.0), 4e-4);
  EXPECT_TRUE(shouldRest(0.5, 1e-3, 10.0, 1e-9, 5e-4));   // all within one 0.5 ms step
  EXPECT_FALSE(shouldRest(0.5, 1e-3, 10.0, 1e-9, 3e-4));  // not within a 0.3 ms step
  EXPECT_FALSE(shouldRest(1.0, 1e-3, 10.0, 1e-9, 1.0));   // elastic: no accumulation
}

// The rod pendulum of test_events.cpp: m = 1, L = 1, d = 0.01, pivot at one
// end, starting horizontal at rest; the angle beta about +y grows as it
// falls: I_o beta'' = m g (L/2) cos(beta).
constexpr double kG = 9.81;
double rodInertia() {
  const double r = 0.005;
  return (3 * r * r + 1.0) / 12 + 0.25;
}
std::string pendulumScene(const std::string& limits, const std::string& sim, const std::string& extra = "") {
  return testScene("ground_and_rod.yaml") + R"(joints:
  - {name: R, type: revolute, bodies: [ground, arm], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]],
     limits: )" + limits + R"(}
forces:
  - {name: g, type: gravity, g: [0, 0, -9.81]}
)" + extra + "simulation: " + sim + "\n";
}

// Time for the pendulum to fall from 0 to beta: t = int_0^beta dB / sqrt(2 k sin B),
// k = m g (L/2) / I_o; with B = u^2 the integrand 2u / sqrt(2 k sin u^2) is
// smooth, integrated by Simpson's rule with 20000 intervals (error ~1e-15).
double fallTime(double beta) {
  const double k = kG * 0.5 / rodInertia();
  const double U = std::sqrt(beta);
  const int n = 20000;
  auto f = [&](double u) {
    if (u == 0) return 2.0 / std::sqrt(2 * k);  // limit of 2u / sqrt(2 k u^2)
    return 2 * u / std::sqrt(2 * k * std::sin(u * u));
  };
  double s = f(0) + f(U);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * f(U * i / n);
  return s * U / (3 * n);
}

TEST(JointLimits, PendulumBouncesWithRestitutionThenRests) {
  const double bs = M_PI / 3, e = 0.5, rtol = 1e-9;
  const Results r = simulate(
      sceneFromText(pendulumScene("{max: 1.0471975511965976, restitution: 0.5}",
                                  "{t_end: 3.0, output_step: 0.01, rtol: 1.0e-9}")),
      {true});
  ASSERT_EQ(r.status, "completed");
  const auto& imp = r.limit_impacts[0];
  ASSERT_GE(imp.size(), 3u);
  // First impact: the free pendulum's time and rate at beta_s.
  const double k = kG * 0.5 / rodInertia();
  const double w0 = std::sqrt(2 * k * std::sin(bs));
  const double t0 = fallTime(bs);
  std::printf("[   info   ] first impact at %.12f s (closed form %.12f), rate %.12f (%.12f) rad/s; %zu impacts\n",
              imp[0][0], t0, imp[0][1], w0, imp.size());
  // rtol 1e-9 on the angle (~1 rad) and its rate: the location is exact on
  // the dense output, so the time error is the angle error over the rate.
  EXPECT_NEAR(imp[0][0], t0, 1e-7);
  EXPECT_NEAR(imp[0][1], w0, 1e-7);
  // Each impact reverses the rate with e; between impacts the flight is
  // conservative, so it comes back at the rate it left: impact k at e^k w0.
  for (std::size_t i = 0; i < imp.size(); ++i) {
    EXPECT_NEAR(imp[i][2], -e * imp[i][1], 1e-10 * w0) << i;
    EXPECT_NEAR(imp[i][1], std::pow(e, int(i)) * w0, 1e-6 * w0) << i;
    // Energy lost: (1 - e^2) of the impact's kinetic energy 1/2 I w^2.
    EXPECT_NEAR(imp[i][4], 0.5 * rodInertia() * (1 - e * e) * imp[i][1] * imp[i][1], 1e-6 * k) << i;
  }
  // Flight k lasts 2 w_k / (a) only for a constant acceleration; the heights
  // instead are exact: the apex after impact k is where 1/2 I (e^k+1 w0)^2 =
  // m g L/2 (sin bs - sin beta): the rise in potential per flight falls by e^2.
  double prev_rise = 0;
  for (std::size_t i = 0; i + 1 < imp.size() && i < 4; ++i) {
    double lowest = bs;
    for (std::size_t n = 0; n < r.time.size(); ++n)
      if (r.time[n] > imp[i][0] && r.time[n] < imp[i + 1][0]) lowest = std::min(lowest, r.joint_angle[0][n]);
    const double rise = std::sin(bs) - std::sin(lowest);
    const double expect = 0.5 * rodInertia() * std::pow(e * imp[i][1], 2) / (kG * 0.5);
    // The output grid (10 ms) samples the apex within 1/2 a (5 ms)^2 of the angle.
    EXPECT_NEAR(rise, expect, 0.5 * k * 0.5 * 25e-6 + 1e-9) << i;
    if (i > 0) {
      EXPECT_NEAR(rise / prev_rise, e * e, 0.02) << i;
    }
    prev_rise = rise;
  }
  // Rest: once the remaining bounces, 2 e w / ((1 - e) a) with a = k cos(bs)
  // the acceleration into the stop (constant in the limit of small flights),
  // fit in one integrator step (at most max_step = 10 output steps = 0.1 s),
  // or their apex (e w)^2 / (2 a) is below atol = 1e-3 rtol: never later than
  // the apex rule alone would rest (21 impacts), and with a remainder below 0.1 s.
  const double atol = 1e-3 * rtol, a = k * std::cos(bs);
  int apex_rule = 0;
  while (std::pow(e * std::pow(e, apex_rule) * w0, 2) >= 2 * a * atol) ++apex_rule;
  EXPECT_LE(double(imp.size()), double(apex_rule + 2));
  EXPECT_LE(zenoRemainder(e, e * std::abs(imp.back()[1]), a), 0.1);
  std::printf("[   info   ] rests at impact %zu (the apex rule alone: %d): remaining bounces %.2e s, apex %.2e rad\n",
              imp.size(), apex_rule + 1, zenoRemainder(e, e * std::abs(imp.back()[1]), a),
              std::pow(e * imp.back()[1], 2) / (2 * a));
  // Resting: the stop holds the static gravity torque, pushing the angle
  // down: -m g (L/2) cos(bs).
  EXPECT_EQ(r.limit_state[0].back(), 1);
  EXPECT_NEAR(r.limit_torque[0].back(), -kG * 0.5 * std::cos(bs), 1e-6);
  EXPECT_NEAR(r.joint_angle[0].back(), bs, 1e-9);
  // The energy the impacts took is in the dissipated channel.
  const double E0 = r.kinetic[0] + r.potential[0];
  const double Eend = r.kinetic.back() + r.potential.back() + r.dissipated.back();
  EXPECT_NEAR(Eend, E0, 1e-6);
  EXPECT_NEAR(r.dissipated.back(), kG * 0.5 * std::sin(bs), 1e-6);  // all the fall's energy
}

TEST(JointLimits, StopOnlyJointOnAHingeOfTwoSphericals) {
  // The flexible SAR's hinge 2/3: two spherical joints on the hinge line hold
  // the bodies, a stop_only revolute on the same line carries the stop. On
  // the rigid pendulum it must give the revolute's closed forms.
  const Results r = simulate(sceneFromText(testScene("ground_and_rod.yaml") + R"(joints:
  - {name: Sa, type: spherical, bodies: [ground, arm], points: [[0, 0.1, 0], [-0.5, 0.1, 0]]}
  - {name: Sb, type: spherical, bodies: [ground, arm], points: [[0, -0.1, 0], [-0.5, -0.1, 0]]}
  - {name: R, type: revolute, bodies: [ground, arm], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]],
     stop_only: true, limits: {max: 1.0471975511965976, restitution: 0.5}}
forces:
  - {name: g, type: gravity, g: [0, 0, -9.81]}
simulation: {t_end: 1.0, output_step: 0.01, rtol: 1.0e-9}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  const int R = 2;
  ASSERT_GE(r.limit_impacts[R].size(), 2u);
  const double k = kG * 0.5 / rodInertia();
  const double w0 = std::sqrt(2 * k * std::sin(M_PI / 3));
  EXPECT_NEAR(r.limit_impacts[R][0][0], fallTime(M_PI / 3), 1e-7);
  EXPECT_NEAR(r.limit_impacts[R][0][1], w0, 1e-7);
  EXPECT_NEAR(r.limit_impacts[R][0][2], -0.5 * w0, 1e-7);
  EXPECT_NEAR(r.limit_impacts[R][1][1], 0.5 * w0, 1e-6);
  EXPECT_LT(r.max_violation, 1e-8);
}

TEST(JointLimits, ElasticImpactsConserveEnergy) {
  // Between stops at -0.5 and 0.8 rad, thrown upward at 8 rad/s so that it
  // reaches both, elastic: it bounces for ever, ~50 impacts in 8 s.
  const std::string scene = pendulumScene("{min: -0.5, max: 0.8, restitution: 1.0}",
                                          "{t_end: 8.0, output_step: 0.01, rtol: 1.0e-9}");
  const std::string thrown = std::string(scene).replace(scene.find("position: [0.5, 0, 0]"), 21,
                                                         "position: [0.5, 0, 0]\n    angular_velocity: [0, -8, 0]"
                                                         "\n    velocity: [0, 0, 4]");
  const Results r = simulate(sceneFromText(thrown), {true});
  ASSERT_EQ(r.status, "completed");
  ASSERT_GT(r.limit_impacts[0].size(), 20u);
  double dE = 0, dmax = 0;
  const double E0 = r.kinetic[0] + r.potential[0];
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    dE = std::max(dE, std::abs(r.kinetic[n] + r.potential[n] - E0));
    dmax = std::max(dmax, r.dissipated[n]);
  }
  for (const auto& i : r.limit_impacts[0]) EXPECT_NEAR(i[2], -i[1], 1e-9 * std::abs(i[1]));
  for (double a : r.joint_angle[0]) {
    EXPECT_GE(a, -0.5 - 1e-9);
    EXPECT_LE(a, 0.8 + 1e-9);
  }
  std::printf("[   info   ] %zu elastic impacts: |E - E0| <= %.2e J of %.3g J, dissipated %.2e J\n",
              r.limit_impacts[0].size(), dE, std::abs(E0) + 4.9, dmax);
  // Local errors of rtol 1e-9 per step add up over the ~1e3 steps; the
  // impulses themselves are exact (e = 1 keeps T to rounding).
  EXPECT_LT(dE, 1e-6);
  EXPECT_LT(dmax, 1e-12);
}

TEST(JointLimits, PlasticStopHoldsWhilePushedAndReleasesWhenPulled) {
  // A rotor (no gravity) turning into its min stop at 0 under a constant
  // torque -2 N m about y; e = 0: it stays. At t = 1 a +5 N m torque joins:
  // the net +3 N m pulls it off at that instant, and then
  // angle = 3/I (t - 1)^2 / 2.
  const double I = 0.3;
  const Results r = simulate(sceneFromText(testScene("ground_and_rotor.yaml") + R"(    angular_velocity: [0, -1.0, 0]
joints:
  - {name: R, type: revolute, bodies: [ground, rotor], points: [[0,0,0],[0,0,0]], axes: [[0,1,0],[0,1,0]],
     initial_angle: 0.5, limits: {min: 0.0, restitution: 0.0}}
forces:
  - {name: push, type: torque, body: rotor, torque: [0, -2, 0]}
  - {name: pull, type: torque, body: rotor, torque: [0, 5, 0], enabled: false}
events:
  - {time: 1.0, enable: [pull]}
simulation: {t_end: 1.5, output_step: 0.01, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  ASSERT_EQ(r.limit_impacts[0].size(), 1u);
  // Impact: 0.5 = t + t^2 (rate -1, accel -2/0.3): t = (-1 + sqrt(1 + 4 (1/0.3) 0.5 ... ) closed form.
  const double acc = 2.0 / I;  // into the stop
  const double ti = (-1.0 + std::sqrt(1.0 + 2 * acc * 0.5)) / acc;
  EXPECT_NEAR(r.limit_impacts[0][0][0], ti, 1e-9);
  EXPECT_NEAR(r.limit_impacts[0][0][1], -(1.0 + acc * ti), 1e-8);
  EXPECT_NEAR(r.limit_impacts[0][0][4], 0.5 * I * std::pow(1.0 + acc * ti, 2), 1e-8);  // all of T
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    const double t = r.time[n];
    if (t > ti + 0.01 && t < 1.0) {
      EXPECT_EQ(r.limit_state[0][n], -1) << t;
      EXPECT_NEAR(r.limit_torque[0][n], 2.0, 1e-7) << t;  // statics: the stop returns the push
      EXPECT_NEAR(r.joint_angle[0][n], 0.0, 1e-9) << t;
    }
    if (t > 1.0 + 1e-9) {
      EXPECT_EQ(r.limit_state[0][n], 0) << t;
      EXPECT_NEAR(r.joint_angle[0][n], 0.5 * (3.0 / I) * (t - 1.0) * (t - 1.0), 1e-8) << t;
    }
  }
  bool released = false;
  for (const std::string& l : r.event_log)
    if (l.find("leaves its min stop") != std::string::npos) {
      released = true;
      EXPECT_EQ(l.rfind("t=1:", 0), 0u) << l;
    }
  EXPECT_TRUE(released);
}

// The rotational bouncing ball: a rotor (no gravity, I = 0.3 kg m^2) starts
// at rest 0.5 rad above its min stop under a constant torque of -2 N m, so
// its acceleration a = 2/I into the stop never changes and everything is in
// closed form: first impact at t1 = sqrt(2 0.5/a) with v1 = a t1, impact k
// at rate e^(k-1) v1, flight k lasting 2 e^k v1 / a, and the flights summing
// to the Zeno time t_inf = t1 + 2 e v1 / ((1 - e) a), after which the rotor
// rests with the stop holding the full 2 N m.
struct ZenoRun {
  Results r;
  double a, t1, v1, t_inf;
};
ZenoRun bouncingRotor(double e, double rtol) {
  const double I = 0.3, torque = 2.0, theta0 = 0.5;
  char sim[160];
  std::snprintf(sim, sizeof sim, "simulation: {t_end: %.17g, output_step: 0.001, rtol: %g}\n",
                // t_inf plus 0.3 s of rest
                std::sqrt(2 * theta0 * I / torque) * (1 + 2 * e / (1 - e)) + 0.3, rtol);
  char lim[64];
  std::snprintf(lim, sizeof lim, "{min: 0.0, restitution: %g}}\n", e);
  ZenoRun z{simulate(sceneFromText(testScene("ground_and_rotor.yaml") + R"(joints:
  - {name: R, type: revolute, bodies: [ground, rotor], points: [[0,0,0],[0,0,0]], axes: [[0,1,0],[0,1,0]],
     initial_angle: 0.5, limits: )" + lim + R"(forces:
  - {name: push, type: torque, body: rotor, torque: [0, -2, 0]}
)" + sim),
                     {true}),
            torque / I, 0, 0, 0};
  z.t1 = std::sqrt(2 * theta0 / z.a);
  z.v1 = z.a * z.t1;
  z.t_inf = z.t1 + 2 * e * z.v1 / ((1 - e) * z.a);
  return z;
}

// The exact angle of the bouncing rotor at time t (parabolic flights).
double bouncingAngle(double t, double e, double a, double t1, double v1) {
  if (t <= t1) return 0.5 - 0.5 * a * t * t;
  double tk = t1, v = v1;
  for (int k = 0; k < 200; ++k) {
    const double w = e * v, flight = 2 * w / a;
    if (t <= tk + flight) return w * (t - tk) - 0.5 * a * (t - tk) * (t - tk);
    tk += flight;
    v = w;
  }
  return 0.0;  // past the accumulation point: at rest on the stop
}

TEST(JointLimits, ZenoSequenceRestsAtItsAccumulationTimeWithTheStaticTorque) {
  for (double e : {0.5, 0.8}) {
    for (double rtol : {1e-6, 1e-9}) {
      const ZenoRun z = bouncingRotor(e, rtol);
      const Results& r = z.r;
      ASSERT_EQ(r.status, "completed") << e << " " << rtol;
      const auto& imp = r.limit_impacts[0];
      ASSERT_GE(imp.size(), 1u);
      // The impacts follow the closed form: the motion is quadratic, so the
      // 5th-order integrator is exact up to rounding and the location is to
      // machine precision (1e-9 s and rad/s leave room for the bisection).
      double tk = z.t1, v = z.v1;
      for (std::size_t k = 0; k < imp.size(); ++k) {
        EXPECT_NEAR(imp[k][0], tk, 1e-9) << e << " " << rtol << " impact " << k;
        EXPECT_NEAR(imp[k][1], -v, 1e-9) << k;
        tk += 2 * e * v / z.a;
        v *= e;
      }
      // Rest: the log names the accumulation time the remaining bounces would
      // have reached, t_rest + 2 e v / ((1 - e) a): the Zeno time of the
      // closed form, to rounding.
      double t_rest = -1, t_acc = -1;
      for (const std::string& l : r.event_log) {
        const auto p = l.find("would have ended at t=");
        if (p == std::string::npos) continue;
        t_rest = std::stod(l.substr(2));
        t_acc = std::stod(l.substr(p + 22));
      }
      ASSERT_GT(t_rest, 0) << "no rest with a Zeno remainder in the log";
      EXPECT_NEAR(t_acc, z.t_inf, 1e-9) << e << " " << rtol;
      EXPECT_NEAR(t_rest, imp.back()[0], 1e-8);  // the log prints 10 digits
      // The rule rests once the remainder fits in one integrator step (at most
      // max_step = 10 output steps = 0.01 s here) - a bounded number of
      // impacts: fewer than the n with 2 e^n v1 / ((1 - e) a) < 1e-4 s.
      EXPECT_LE(z.t_inf - t_rest, 0.01);
      const int bound = int(std::ceil(std::log(1e-4 * (1 - e) * z.a / (2 * z.v1)) / std::log(e)));
      EXPECT_LE(int(imp.size()), bound);
      // The motion is the exact one within the remainder's apex (the bounces
      // the rest leaves out rise at most (e v_n)^2 / (2 a)), and afterwards
      // the stop holds the torque's statics exactly.
      const double w_last = e * std::abs(imp.back()[1]);
      const double apex = w_last * w_last / (2 * z.a);
      double worst = 0;
      for (std::size_t n = 0; n < r.time.size(); ++n) {
        const double t = r.time[n];
        worst = std::max(worst, std::abs(r.joint_angle[0][n] - bouncingAngle(t, e, z.a, z.t1, z.v1)));
        if (t > z.t_inf) {
          EXPECT_EQ(r.limit_state[0][n], -1) << t;
          EXPECT_NEAR(r.limit_torque[0][n], 2.0, 1e-9) << t;
          EXPECT_NEAR(r.joint_angle[0][n], 0.0, 1e-12) << t;
        }
      }
      EXPECT_LE(worst, apex + 1e-9) << e << " " << rtol;
      std::printf("[   info   ] e = %.1f, rtol %.0e: %zu impacts, rests at %.9f s, Zeno time %.9f s (closed form "
                  "%.9f s), angle within %.2e rad of the exact bounces (remainder apex %.2e)\n",
                  e, rtol, imp.size(), t_rest, t_acc, z.t_inf, worst, apex);
    }
  }
}

TEST(JointLimits, LatchEventLocksWithAPlasticLoss) {
  // A latch is an angle-crossing event that locks the joint: the rotor
  // (I_y = 0.3, 2 rad/s, no loads) reaches 1 rad at t = 0.5 exactly and stops
  // there; its kinetic energy 1/2 I w^2 = 0.6 J goes to the dissipated energy.
  const Results r = simulate(sceneFromText(testScene("ground_and_rotor.yaml") + R"(    angular_velocity: [0, 2.0, 0]
joints:
  - {name: R, type: revolute, bodies: [ground, rotor], points: [[0,0,0],[0,0,0]], axes: [[0,1,0],[0,1,0]]}
events:
  - {joint: R, angle: 1.0, direction: rising, lock: [R]}
simulation: {t_end: 1.0, output_step: 0.05, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    const double t = r.time[n];
    const double expect = t < 0.5 ? 2.0 * t : 1.0;
    EXPECT_NEAR(r.joint_angle[0][n], expect, 1e-9) << t;
    EXPECT_NEAR(r.kinetic[n] + r.dissipated[n], 0.6, 1e-9) << t;
  }
  EXPECT_NEAR(r.dissipated.back(), 0.6, 1e-9);
}

TEST(JointLimits, RestingReactionFollowsStaticsAndReleasesSmoothly) {
  // An arm drooping by beta = 0.3 rad from a platform spun up about the
  // vertical (Kane's spin-up, 10 rad/s over 2 s) rests on a stop at beta,
  // pushed by gravity. In the rotating frame the stop's torque is the static
  // balance of gravity and the centrifugal moment,
  //   tau = -(m g L/2 cos(beta) - w^2 sin(beta) cos(beta) (I_t - I_a)),
  // (I_t about the hinge across the rod, I_a about its axis), and the arm
  // leaves the stop when tau reaches 0: w(t)^2 = m g L/2 / ((I_t - I_a) sin(beta)),
  // w(t) = (W/T)(t - T/(2 pi) sin(2 pi t/T)).
  const double beta = 0.3, m = 1.0, L = 1.0, r = 0.0005, W = 10.0, T = 2.0;
  const double It = m * (3 * r * r + L * L) / 12 + m * 0.25 * L * L, Ia = 0.5 * m * r * r;
  char scene[1600];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: platform, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}}
  - name: arm
    rod: {length: 1.0, diameter: 0.001, mass: 1.0}
    position: [%.17g, 0, %.17g]
    orientation: [%.17g, 0, %.17g, 0]
joints:
  - {name: P, type: revolute, bodies: [ground, platform], points: [[0,0,0],[0,0,0]], axes: [[0,0,1],[0,0,1]],
     drive: {angle0: 0.0, spin_up: {rate: %g, time: %g}}}
  - {name: R, type: revolute, bodies: [platform, arm], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]],
     initial_angle: %.17g, limits: {max: %.17g, restitution: 0.0}}
forces:
  - {name: g, type: gravity, g: [0, 0, -9.81]}
simulation: {t_end: 1.6, output_step: 0.01, rtol: 1.0e-10}
)",
                0.5 * std::cos(beta), -0.5 * std::sin(beta), std::cos(beta / 2), std::sin(beta / 2), W, T, beta, beta);
  const Results res = simulate(sceneFromText(scene), {true});
  ASSERT_EQ(res.status, "completed");
  auto w = [&](double t) { return W / T * (t - T / (2 * M_PI) * std::sin(2 * M_PI * t / T)); };
  const double wc2 = m * kG * 0.5 * L / ((It - Ia) * std::sin(beta));
  double a = 0.5, b = 2.0;  // w(t) rises monotonically over the spin-up: bisection for w^2 = wc^2
  for (int i = 0; i < 200; ++i) ((w(0.5 * (a + b)) * w(0.5 * (a + b)) < wc2) ? a : b) = 0.5 * (a + b);
  const double t_release = 0.5 * (a + b);
  double released_at = -1;
  for (const std::string& l : res.event_log)
    if (l.find("leaves its max stop") != std::string::npos) released_at = std::stod(l.substr(2));
  std::printf("[   info   ] release at %.9f s (statics %.9f s)\n", released_at, t_release);
  // The release is located on the dense output by bisection; the torque's
  // rate there is ~30 N m/s, so rtol 1e-10 on the states gives ~1e-9 s.
  EXPECT_NEAR(released_at, t_release, 1e-7);
  const int R = 1;
  for (std::size_t n = 0; n < res.time.size(); ++n) {
    const double t = res.time[n];
    if (t < t_release - 1e-3) {
      EXPECT_EQ(res.limit_state[R][n], 1) << t;
      const double tau = -(m * kG * 0.5 * L * std::cos(beta) -
                           w(t) * w(t) * std::sin(beta) * std::cos(beta) * (It - Ia));
      EXPECT_NEAR(res.limit_torque[R][n], tau, 1e-6) << t;
      EXPECT_NEAR(res.joint_angle[R][n], beta, 1e-9) << t;
    } else if (t > t_release + 1e-3) {
      EXPECT_EQ(res.limit_state[R][n], 0) << t;
      EXPECT_LT(res.joint_angle[R][n], beta) << t;  // lifting
    }
  }
  EXPECT_EQ(res.limit_impacts[R].size(), 0u);  // it never comes back in 1.6 s
}

TEST(JointLimits, InternalImpactKeepsMomentum) {
  // Two free rods hinged at their ends (no ground, no gravity), folding
  // toward each other; the hinge's stop at 0.3 rad is internal, so linear and
  // angular momentum must be the same after the impacts.
  const Results r = simulate(sceneFromText(R"(
bodies:
  - name: a
    rod: {length: 1.0, diameter: 0.02, mass: 1.0}
    position: [-0.5, 0, 0]
    velocity: [0.1, 0.2, -0.3]
    angular_velocity: [0.2, 1.0, 0.1]
  - name: b
    rod: {length: 1.0, diameter: 0.02, mass: 2.0}
    position: [0.5, 0, 0]
    velocity: [0.1, 0.2, 0.3]
    angular_velocity: [0.2, -1.0, 0.1]
joints:
  - {name: H, type: revolute, bodies: [a, b], points: [[0.5,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]],
     limits: {min: -0.3, max: 0.3, restitution: 0.6}}
simulation: {t_end: 2.0, output_step: 0.01, rtol: 1.0e-10}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  ASSERT_GE(r.limit_impacts[0].size(), 2u);
  // Linear momentum and angular momentum about the origin, from the output
  // (rods: the CoM at the frame origin, I_c = m (3 r^2 + L^2)/12 across).
  auto momenta = [&](std::size_t n, Eigen::Vector3d& p, Eigen::Vector3d& h) {
    p.setZero();
    h.setZero();
    const double mass[2] = {1.0, 2.0};
    for (int k = 0; k < 2; ++k) {
      const double m = mass[k], Ia = 0.5 * m * 0.01 * 0.01, It = m * (3 * 1e-4 + 1.0) / 12;
      const Eigen::Matrix3d A = fc::rotationMatrix(r.orientation[k][n]);
      const Eigen::Matrix3d J = A * Eigen::Vector3d(Ia, It, It).asDiagonal() * A.transpose();
      p += m * r.velocity[k][n];
      h += r.position[k][n].cross(m * r.velocity[k][n]) + J * r.angular_velocity[k][n];
    }
  };
  Eigen::Vector3d p0, h0, p1, h1;
  momenta(0, p0, h0);
  momenta(r.time.size() - 1, p1, h1);
  std::printf("[   info   ] %zu impacts, |dp| %.2e, |dh| %.2e, dissipated %.4g J\n", r.limit_impacts[0].size(),
              (p1 - p0).norm(), (h1 - h0).norm(), r.dissipated.back());
  // rtol 1e-10 per step over ~1e3 steps on momenta of order 1.
  EXPECT_LT((p1 - p0).norm(), 1e-7);
  EXPECT_LT((h1 - h0).norm(), 1e-7);
  EXPECT_GT(r.dissipated.back(), 1e-3);
  const double E0 = r.kinetic[0], E1 = r.kinetic.back() + r.dissipated.back();
  EXPECT_NEAR(E1, E0, 1e-7);
  for (const auto& i : r.limit_impacts[0]) EXPECT_NEAR(i[2], -0.6 * i[1], 1e-9);
}

double E0ref(double I) { return 0.5 * I * 4.0; }

TEST(JointLimits, FlexibleBeamImpulseThroughTheInterface) {
  // A clamped-root flexible beam (tests' Euler-Bernoulli generator, 4 modes)
  // turning about z at its root interface into a stop at 0.4 rad.
  BeamSpec spec;
  spec.modes = 4;
  const BeamModel beam = cantileverBeam(spec);
  const std::string file = writeBeam(beam, "stop");
  // The effective inertia the stop meets: the beam's mass matrix (the
  // invariants, undeformed) on the motions the revolute leaves, the frame's
  // rotation about z and the modes; the loss of the first impact is
  // 1/2 (1 - e^2) rate^2 I_eff with 1/I_eff = (M_r^-1)_00.
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(beam.body, 4);
  const FlexibleInertia fi = flexibleInertia(inv, Eigen::Matrix3d::Identity(), Eigen::VectorXd::Zero(4),
                                             Eigen::VectorXd::Zero(4), Eigen::Vector3d(0, 0, 2.0));
  std::vector<int> keep = {5, 6, 7, 8, 9};
  Eigen::MatrixXd Mr(5, 5);
  for (int a = 0; a < 5; ++a)
    for (int b = 0; b < 5; ++b) Mr(a, b) = fi.M(keep[a], keep[b]);
  const double I_eff = 1.0 / Mr.inverse()(0, 0);
  const double I_rigid = fi.M(5, 5);
  for (double e : {1.0, 0.5}) {
    char scene[1400];
    std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: %s, modes: 4}
    angular_velocity: [0, 0, 2.0]
joints:
  - {name: R, type: revolute, bodies: [ground, beam], points: [[0,0,0], root], axes: [[0,0,1],[0,0,1]],
     limits: {max: 0.4, restitution: %g}}
simulation: {t_end: 0.6, output_step: 0.005, rtol: 1.0e-9}
)",
                  file.c_str(), e);
    const Results r = simulate(sceneFromText(scene), {true});
    ASSERT_EQ(r.status, "completed");
    ASSERT_GE(r.limit_impacts[0].size(), 1u);
    const auto& i0 = r.limit_impacts[0][0];
    EXPECT_NEAR(i0[0], 0.2, 1e-6);  // rate 2, no load before it
    EXPECT_NEAR(i0[1], 2.0, 1e-6);
    EXPECT_NEAR(i0[2], -e * i0[1], 1e-9);
    EXPECT_NEAR(i0[4], 0.5 * (1 - e * e) * i0[1] * i0[1] * I_eff, 1e-6 * E0ref(I_rigid));
    double umax = 0, dE = 0;
    const double E0 = r.kinetic[0] + r.strain[0];
    for (std::size_t n = 0; n < r.time.size(); ++n) {
      umax = std::max(umax, r.strain[n]);
      dE = std::max(dE, std::abs(r.kinetic[n] + r.strain[n] + r.dissipated[n] - E0));
    }
    std::printf("[   info   ] flexible beam, e = %.1f: %zu impacts, max strain energy %.3g J of %.3g J, energy "
                "balance %.2e J\n", e, r.limit_impacts[0].size(), umax, E0, dE);
    EXPECT_GT(umax, 1e-3 * E0);  // the impulse excites the modes
    EXPECT_LT(dE, 1e-6 * E0);
    if (e == 1.0) {
      EXPECT_LT(r.dissipated.back(), 1e-10 * E0);
    }
    else EXPECT_GT(r.dissipated.back(), 0.5 * (1 - e * e) * 4.0 * I_eff * 0.99);
    if (e == 0.5)
      std::printf("[   info   ] the stop meets %.4g of the beam's %.4g kg m^2 (the rest is carried by the modes)\n",
                  I_eff, I_rigid);
  }
  std::filesystem::remove(file);
}

TEST(JointLimits, BadLimitsAreReportedAtTheirKey) {
  auto err = [](const std::string& limits, const char* type = "revolute") {
    try {
      sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: arm, rod: {length: 1.0, diameter: 0.01, mass: 1.0}}
joints:
  - {name: R, type: )" + std::string(type) + R"(, bodies: [ground, arm], points: [[0,0,0],[-0.5,0,0]],)" +
                    (std::string(type) == "revolute" ? " axes: [[0,1,0],[0,1,0]]," : "") + " limits: " + limits +
                    R"(}
simulation: {t_end: 1.0}
)");
    } catch (const fc::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(err("{min: 0.5, max: 0.1}").find("expected max > min"), std::string::npos);
  EXPECT_NE(err("{min: 0.1, restitution: 1.5}").find("restitution"), std::string::npos);
  EXPECT_NE(err("{min: 0.1}").find("outside the limits"), std::string::npos);
  EXPECT_NE(err("{restitution: 0.5}").find("expected 'min', 'max'"), std::string::npos);
  EXPECT_NE(err("{max: 0.1, bounce: 1}").find("bounce"), std::string::npos);
  EXPECT_NE(err("{max: 0.1}", "spherical").find("only revolute joints have limits"), std::string::npos);
}

}  // namespace
}  // namespace fc::mbs::test
