// The one-sided contact force element (force_elements.h, contactState)
// against closed forms of a point mass striking a fixed plane:
// - linear law, no damping: the contact is half a period of the spring on the
//   mass, pi sqrt(m/k), the rebound speed equals the arrival speed and
//   T + V is conserved; the impact time is the free flight's h / v0;
// - with gravity: impact at sqrt(2 h / g) (free fall); in contact the mass
//   oscillates about the static penetration d_s = m g / k, so the contact lasts
//   (2 pi - 2 atan(v0 / (w d_s))) / w (the second zero of
//   d(t) = d_s (1 - cos wt) + (v0 / w) sin wt), and the ball rises back to h;
// - Hertz law (exponent 1.5): the contact lasts 2.9432 d* / v0 with
//   d* = (5 m v0^2 / (4 k))^(2/5) (Johnson, Contact Mechanics, 1985, eq. 11.24;
//   2.9432 = (4/5) B(2/5, 1/2));
// - Hunt-Crossley damping with Lankarani and Nikravesh's hysteresis factor
//   3 (1 - e^2) / (4 v0) (J. Mech. Des. 112:369, 1990): the rebound speed over
//   the arrival speed recovers e to within the law's own approximation error.
// The plane is also put on the moving body (a block landing on a fixed post,
// spinning), where only the exact gradient keeps the energy balance; and on a
// flexible cantilever's tip interface struck by a ball, against the modal
// impact solution (the linear ball-and-modes system in contact, solved by its
// own eigenvectors).
#include <gtest/gtest.h>

#include <cmath>

#include "beam_body.h"
#include "helpers.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

struct Bounce {
  double t_in = -1.0, t_out = -1.0;  // first zero crossings of the penetration, rising and falling
  double v_in = 0.0, v_out = 0.0;    // normal speed before and after
  double energy_error = 0.0;         // max |T + V + U + D - E0| (U: modal strain energy)
  double peak_force = 0.0;
};

// The contact's times from the penetration rows, linearly interpolated between
// the two rows that straddle each zero (the motion is free flight on one side:
// the interpolation's error is the contact's curvature over one row, see below).
Bounce measure(const Results& r, int body) {
  Bounce b;
  const std::vector<double>& d = r.contact_penetration.at(0);
  for (std::size_t i = 1; i < r.time.size(); ++i) {
    const double t = r.time[i - 1] + (r.time[i] - r.time[i - 1]) * d[i - 1] / (d[i - 1] - d[i]);
    if (b.t_in < 0 && d[i - 1] <= 0 && d[i] > 0) {
      b.t_in = t;
      b.v_in = std::abs(r.velocity[body][i - 1].z());
    } else if (b.t_in >= 0 && b.t_out < 0 && d[i - 1] > 0 && d[i] <= 0) {
      b.t_out = t;
      b.v_out = std::abs(r.velocity[body][i].z());
    }
  }
  const double e0 = r.kinetic[0] + r.potential[0] + r.strain[0];
  for (std::size_t i = 0; i < r.time.size(); ++i)
    b.energy_error =
        std::max(b.energy_error, std::abs(r.kinetic[i] + r.potential[i] + r.strain[i] + r.dissipated[i] - e0));
  b.peak_force = r.peak_contact_force.at(0).value;
  return b;
}

// A 2 kg ball (its centre is the contact point: a sphere's radius is the
// plane's offset) at height h moving down at v0, over a fixed plane z = 0.
std::string ballScene(double h, double v0, double k, double n, const std::string& extra, double g, double t_end,
                      double step) {
  char s[2048];
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: ball, rigid: {mass: 2.0, inertia: [[0.01,0,0],[0,0.01,0],[0,0,0.01]]}, position: [0, 0, %.17g],
     velocity: [0, 0, %.17g]}
forces:
  - {name: floor, type: contact, bodies: [ball, ground], point: [0, 0, 0],
     plane: {point: [0, 0, 0], normal: [0, 0, 1]}, stiffness: %.17g, exponent: %.17g%s}
  - {type: gravity, g: [0, 0, %.17g]}
simulation: {t_end: %.17g, output_step: %.17g, rtol: 1.0e-10, integrator: dopri5}
)",
                h, -v0, k, n, extra.c_str(), -g, t_end, step);
  return s;
}

TEST(Contact, LinearElasticBounceHalfPeriod) {
  const double m = 2.0, k = 1.0e5, h = 0.1, v0 = 1.0, step = 1e-5;
  const Results r = simulate(sceneFromText(ballScene(h, v0, k, 1.0, "", 0.0, 0.14, step)), {true});
  ASSERT_EQ(r.status, "completed");
  const Bounce b = measure(r, 1);
  const double T = M_PI * std::sqrt(m / k);  // 14.05 ms
  std::printf("[   info   ] linear bounce: impact %.9f s (closed form %.9f), contact %.9f s (%.9f), rebound %.9f m/s, "
              "energy %.2e J, peak force %.5g N (k v0/w %.5g)\n",
              b.t_in, h / v0, b.t_out - b.t_in, T, b.v_out, b.energy_error, b.peak_force, v0 * std::sqrt(k * m));
  // Interpolating a zero across a row of 1e-5 s: free flight on one side,
  // on the other d = v0 t - w^2 v0 t^3 / 6: the crossing is off by at most
  // w^2 step^3 / 6 ~ 1e-11 s; the integration (rtol 1e-10) adds ~1e-10 s.
  EXPECT_NEAR(b.t_in, h / v0, 1e-9);
  EXPECT_NEAR(b.t_out - b.t_in, T, 1e-8);
  // Conservative: rebound at the arrival speed, energy to the run's accuracy
  // (dopri5 rtol 1e-10; measured 1.1e-8 J of the 1 J and 5e-9 m/s).
  EXPECT_NEAR(b.v_out, v0, 1e-7);
  EXPECT_LT(b.energy_error, 1e-7);
  // The peak force k d_max = v0 sqrt(k m) falls between output rows: within
  // the rows' sampling of a cosine peak, 1 - cos(w step / 2) ~ 1.3e-6.
  EXPECT_NEAR(b.peak_force, v0 * std::sqrt(k * m), 2e-6 * v0 * std::sqrt(k * m));
  EXPECT_NEAR(r.velocity[1].back().z(), v0, 1e-7);
}

TEST(Contact, DropUnderGravityReturnsToItsHeight) {
  const double m = 2.0, k = 2.0e4, h = 0.2, g = 9.81, step = 1e-5;
  const Results r = simulate(sceneFromText(ballScene(h, 0.0, k, 1.0, "", g, 0.5, step)), {true});
  ASSERT_EQ(r.status, "completed");
  const Bounce b = measure(r, 1);
  const double v0 = std::sqrt(2 * g * h), w = std::sqrt(k / m), ds = m * g / k;
  const double T = (2 * M_PI - 2 * std::atan(v0 / (w * ds))) / w;
  double apex = -1e9;  // highest point after the bounce
  for (std::size_t i = 0; i < r.time.size(); ++i)
    if (r.time[i] > b.t_out) apex = std::max(apex, r.position[1][i].z());
  std::printf("[   info   ] drop: impact %.9f s (sqrt(2h/g) %.9f), contact %.9f s (%.9f), v in %.9f out %.9f "
              "(%.9f), apex %.9f m, energy %.2e J\n",
              b.t_in, std::sqrt(2 * h / g), b.t_out - b.t_in, T, b.v_in, b.v_out, v0, apex, b.energy_error);
  // Crossings as above (w = 100 rad/s: interpolation error ~1e-13 s); the
  // integration's rtol 1e-10 over 0.5 s.
  EXPECT_NEAR(b.t_in, std::sqrt(2 * h / g), 1e-9);
  EXPECT_NEAR(b.t_out - b.t_in, T, 1e-8);
  // The apex between rows of 1e-5 s: g step^2 / 8 ~ 1.2e-10 m below it.
  EXPECT_NEAR(apex, h, 1e-8);
  // dopri5 at rtol 1e-10 over ~0.5 s: the local errors add up, and the step
  // across each zero of the penetration loses the method's order (the
  // force's derivative jumps there); measured 1.5e-7 J (4e-8 of the 3.9 J).
  EXPECT_LT(b.energy_error, 5e-7);
}

TEST(Contact, HertzContactDuration) {
  const double m = 2.0, k = 1.0e8, h = 0.05, v0 = 1.0, step = 1e-6;
  const Results r = simulate(sceneFromText(ballScene(h, v0, k, 1.5, "", 0.0, 0.06, step)), {true});
  ASSERT_EQ(r.status, "completed");
  const Bounce b = measure(r, 1);
  const double dstar = std::pow(5.0 * m * v0 * v0 / (4.0 * k), 0.4);
  const double c = 0.8 * std::tgamma(0.4) * std::sqrt(M_PI) / std::tgamma(0.9);  // 2.9432
  std::printf("[   info   ] Hertz: contact %.9f s (%.4f d*/v0 = %.9f), rebound %.9f m/s, energy %.2e J\n",
              b.t_out - b.t_in, c, c * dstar / v0, b.v_out, b.energy_error);
  // ~1.3 ms contact sampled every 1e-6 s; at the zeros d ~ v0 t, curvature
  // ~ k d^1.5 / m: the crossings are off by far less than 1e-9 s.
  EXPECT_NEAR(b.t_out - b.t_in, c * dstar / v0, 1e-8);
  EXPECT_NEAR(b.v_out, v0, 1e-7);
  EXPECT_LT(b.energy_error, 1e-7);
}

TEST(Contact, HuntCrossleyRestitution) {
  // The effective restitution of the Lankarani-Nikravesh law from the 1-DOF
  // equation m d'' = -max(0, k d^n (1 + alpha d')) integrated independently
  // (tests/data/mbs-run/contact/ln_restitution.py, scipy DOP853, rtol 1e-12):
  // 0.953506045 for e = 0.95 and 0.913176678 for e = 0.9, for either
  // exponent (the law scales out k, m and v0). The law's approximation error
  // is second order in 1 - e: e_eff - e = 1.40 (1-e)^2 and 1.32 (1-e)^2.
  const double m = 2.0, k = 1.0e5, h = 0.1, v0 = 1.0, step = 1e-5;
  const struct {
    double e, exact;
  } cases[] = {{0.95, 0.953506045}, {0.9, 0.913176678}};
  for (const auto& cs : cases) {
    char extra[128];
    std::snprintf(extra, sizeof extra, ", restitution: %.17g, impact_speed: %.17g", cs.e, v0);
    const Results r = simulate(sceneFromText(ballScene(h, v0, k, 1.0, extra, 0.0, 0.14, step)), {true});
    ASSERT_EQ(r.status, "completed");
    const Bounce b = measure(r, 1);
    const double e = r.velocity[1].back().z() / v0;
    std::printf("[   info   ] Hunt-Crossley e = %.2f: rebound ratio %.9f (1-DOF reference %.9f), dissipated %.9f J "
                "(m v0^2 (1 - e'^2) / 2 = %.9f), energy %.2e J\n",
                cs.e, e, cs.exact, r.dissipated.back(), 0.5 * m * v0 * v0 * (1 - e * e), b.energy_error);
    // The law as given: against the independent 1-DOF integration (its 9
    // digits). The run's global error at rtol 1e-10 with the order lost at the
    // two zeros of the penetration: measured 1.1e-8 and 1.4e-8.
    EXPECT_NEAR(e, cs.exact, 5e-8);
    // The closed form: LN's relation holds to its second-order error, bounded
    // by 1.5 (1 - e)^2 (the 1-DOF figures above give 1.32-1.40).
    EXPECT_NEAR(e, cs.e, 1.5 * (1 - cs.e) * (1 - cs.e));
    EXPECT_GT(e, cs.e);  // the approximation under-predicts the loss' restitution: e_eff > e
    // Everything the contact took is in `dissipated`.
    // To the energy balance's error (measured 2.3e-8 and 3.0e-8 J, i.e. 2-3e-8
    // of the 1 J impact energy, as in the other runs at this rtol).
    EXPECT_NEAR(r.dissipated.back(), 0.5 * m * v0 * v0 * (1 - e * e), 1e-7);
    EXPECT_LT(b.energy_error, 1e-7);
  }
}

TEST(Contact, PlaneOnASpinningBlockConservesEnergy) {
  // The plane on the moving body: a block (bottom face z = -0.05 in its axes)
  // spinning about a tilted axis lands on a fixed post tip. The penetration's
  // gradient through the block's rotation is what the force uses; only the
  // exact gradient of the potential keeps T + V constant through the impact.
  const Results r = simulate(sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: block, rigid: {mass: 1.5, inertia: [[0.004,0,0],[0,0.006,0],[0,0,0.008]]}, position: [0.01, -0.02, 0.12],
     velocity: [0, 0, -1.0], angular_velocity: [0.8, 0.5, 3.0]}
forces:
  - {name: post, type: contact, bodies: [ground, block], point: [0, 0, 0],
     plane: {point: [0, 0, -0.05], normal: [0, 0, -1]}, stiffness: 1.0e5, radius: 0.5}
simulation: {t_end: 0.2, output_step: 1.0e-4, rtol: 1.0e-10, integrator: dopri5}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  double dE = 0, peak = 0;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    dE = std::max(dE, std::abs(r.kinetic[i] + r.potential[i] + r.dissipated[i] - r.kinetic[0]));
    peak = std::max(peak, r.contact_force[0][i]);
  }
  std::printf("[   info   ] spinning block on a post: peak force %.5g N, energy balance %.2e J of %.4f J\n", peak,
              dE, r.kinetic[0]);
  EXPECT_GT(peak, 100.0);  // it did strike (v0 sqrt(k m) ~ 387 N for a central blow)
  EXPECT_LT(dE, 1e-8);     // rtol 1e-10 on ~0.8 J
}

TEST(Contact, NeverPullsAndIsZeroApart) {
  // A fast separation with a large hysteresis factor: the force is clipped
  // at zero (no tension), and the run's energy balance stays closed.
  const double v0 = 1.0;
  const Results r = simulate(
      sceneFromText(ballScene(0.1, v0, 1.0e5, 1.0, ", restitution: 0.3, impact_speed: 0.2", 0.0, 0.14, 1e-5)),
      {true});
  ASSERT_EQ(r.status, "completed");
  double fmin = 1e9, dE = 0;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    fmin = std::min(fmin, r.contact_force[0][i]);
    if (r.contact_penetration[0][i] <= 0) {
      EXPECT_EQ(r.contact_force[0][i], 0.0);
    }
    dE = std::max(dE, std::abs(r.kinetic[i] + r.potential[i] + r.dissipated[i] - r.kinetic[0]));
  }
  EXPECT_GE(fmin, 0.0);
  EXPECT_LT(dE, 1e-7);  // as the other bounces at rtol 1e-10 (2-3e-8 of the 1 J)
  EXPECT_GT(r.dissipated.back(), 0.0);
}

TEST(Contact, BallStrikesFlexibleCantileverTip) {
  // A clamped Euler-Bernoulli cantilever (beam_body.h: 1 m, 1 kg/m, EI 80,
  // 20 elements, 4 modes kept: 31.4, 197, 551, 1080 rad/s) struck at its tip
  // interface by a 0.2 kg ball at v0 along -y, linear contact k = 2e3 N/m.
  // Reference: in contact the ball y_b and the modal coordinates q obey
  // M x'' + K x = 0, x = [y_b, q], M = diag(m, I),
  // K = k a a^T + diag(0, Omega^2), a = [-1, psi] (psi: the tip's y shapes),
  // from x = 0, x' = [-v0, 0]: x(t) = sum_i phi_i phi_i^T M x'(0) sin(w_i t) / w_i
  // with K phi = w^2 M phi, M-orthonormal; contact ends at the first zero of
  // d = a^T x. The run must give the same contact time, rebound speed and
  // energy left in the beam. v0 is small (1 cm/s, tip slopes ~1e-4) so the
  // geometric terms the linear reference leaves out (the plane's turn with
  // the tip, ~slope^2) stay below 1e-7.
  BeamSpec spec;
  spec.modes = 4;
  const BeamModel beam = cantileverBeam(spec);
  const std::string file = writeBeam(beam, "contact_tip");
  const int nm = 4;
  const double m = 0.2, k = 2.0e3, v0 = 0.01, gap = 1.0e-4;
  const Eigen::VectorXd psi = beam.body.interface("tip").shapes.col(1).head(nm);
  const Eigen::VectorXd Om2 = beam.body.eigenvalues.head(nm);
  Eigen::VectorXd a(nm + 1), Mdiag(nm + 1);
  a << -1.0, psi;
  Mdiag << m, Eigen::VectorXd::Ones(nm);
  Eigen::MatrixXd K = k * a * a.transpose();
  K.diagonal().tail(nm) += Om2;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, Eigen::MatrixXd(Mdiag.asDiagonal()));
  const Eigen::VectorXd w = es.eigenvalues().cwiseSqrt();
  const Eigen::MatrixXd Phi = es.eigenvectors();  // M-orthonormal
  Eigen::VectorXd xd0 = Eigen::VectorXd::Zero(nm + 1);
  xd0(0) = -v0;
  const Eigen::VectorXd c = Phi.transpose() * Mdiag.asDiagonal() * xd0;
  auto x = [&](double t) { return Eigen::VectorXd(Phi * (c.array() * (w.array() * t).sin() / w.array()).matrix()); };
  auto xd = [&](double t) { return Eigen::VectorXd(Phi * (c.array() * (w.array() * t).cos()).matrix()); };
  double lo = 1e-6;
  while (a.dot(x(lo + 1e-6)) > 0) lo += 1e-6;
  double hi = lo + 1e-6;
  for (int it = 0; it < 60; ++it) (a.dot(x(0.5 * (lo + hi))) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double T = 0.5 * (lo + hi);
  const Eigen::VectorXd xe = x(T), xde = xd(T);
  const double beam_energy = 0.5 * (xde.tail(nm).squaredNorm() + Om2.dot(xe.tail(nm).cwiseAbs2()));

  char scene[1600];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: %s, modes: %d}
  - {name: ball, rigid: {mass: %.17g, inertia: [[1e-4,0,0],[0,1e-4,0],[0,0,1e-4]]}, position: [1.0, %.17g, 0],
     velocity: [0, %.17g, 0]}
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
forces:
  - {name: tip, type: contact, bodies: [ball, beam], point: [0, 0, 0], plane: {point: tip, normal: [0, 1, 0]},
     stiffness: %.17g}
simulation: {t_end: %.17g, output_step: 1.0e-5, rtol: 1.0e-10}
)",
                file.c_str(), nm, m, gap, -v0, k, gap / v0 + 1.2 * T);
  const Results r = simulate(sceneFromText(scene), {true});
  std::filesystem::remove(file);
  ASSERT_EQ(r.status, "completed");
  const Bounce b = measure(r, 2);
  // The beam's energy at separation, from the row nearest it (the free beam's
  // energy is constant after it, so any later row serves: the last).
  const Eigen::VectorXd qe = r.modal[1].back(), qde = r.modal_rate[1].back();
  const double beam_run = 0.5 * (qde.squaredNorm() + Om2.dot(qe.cwiseAbs2()));
  std::printf("[   info   ] ball on the cantilever tip: impact %.9f s (%.9f), contact %.9f s (modal solution %.9f), "
              "rebound %.9f m/s (%.9f), beam energy %.6e J (%.6e), energy balance %.2e J\n",
              b.t_in, gap / v0, b.t_out - b.t_in, T, r.velocity[2].back().y(), xde(0), beam_run, beam_energy,
              b.energy_error);
  // Contact ended before t_end (the ball outruns the tip afterwards).
  ASSERT_GT(b.t_out, 0.0);
  EXPECT_NEAR(b.t_in, gap / v0, 1e-9);
  // The row interpolation (1e-5 s rows, contact curvature w^2 step^2 ~ 1e-6
  // of a row) and the run's rtol 1e-10: well below 1e-7 of the ~25 ms.
  EXPECT_NEAR(b.t_out - b.t_in, T, 1e-7 * T);
  EXPECT_NEAR(r.velocity[2].back().y(), xde(0), 1e-6 * v0);
  EXPECT_NEAR(beam_run, beam_energy, 1e-5 * 0.5 * m * v0 * v0);
  EXPECT_LT(b.energy_error, 1e-6 * 0.5 * m * v0 * v0);
}

TEST(Contact, OutsideThePatchNoForceAndTheDistanceToIt) {
  // A ball 0.02 m behind the plane but 1.0 m from the patch's centre (radius
  // 0.6): no force, and the reported penetration is minus its distance to the
  // patch disk, -hypot(0.4, 0.02), not the +0.02 it would have on an unbounded plane.
  const Results r = simulate(sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: ball, rigid: {mass: 2.0, inertia: [[0.01,0,0],[0,0.01,0],[0,0,0.01]]}, position: [1.0, 0, -0.02]}
forces:
  - {name: pad, type: contact, bodies: [ball, ground], point: [0, 0, 0], plane: {point: [0, 0, 0], normal: [0, 0, 1]},
     stiffness: 1.0e5, radius: 0.6}
simulation: {t_end: 0.01, output_step: 0.005}
)"),
                             {true});
  ASSERT_EQ(r.status, "completed");
  EXPECT_EQ(r.contact_force[0].back(), 0.0);
  EXPECT_NEAR(r.contact_penetration[0].back(), -std::hypot(0.4, 0.02), 1e-12);
  EXPECT_NEAR(r.position[1].back().z(), -0.02, 1e-12);  // nothing pushed it
}

TEST(Contact, BadInputIsNamed) {
  const std::string head = R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: ball, rigid: {mass: 2.0, inertia: [[0.01,0,0],[0,0.01,0],[0,0,0.01]]}}
forces:
)";
  auto error = [&](const std::string& f) {
    try {
      sceneFromText(head + f);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("  - {type: contact, bodies: [ball, ground], point: [0,0,0], plane: {point: [0,0,0], normal: [0,0,1]}, "
                  "stiffness: 1e5, restitution: 0.5}\n")
                .find("impact_speed"),
            std::string::npos);
  EXPECT_NE(error("  - {type: contact, bodies: [ball, ground], point: [0,0,0], plane: {point: [0,0,0], normal: [0,0,0]}, "
                  "stiffness: 1e5}\n")
                .find("non-zero"),
            std::string::npos);
  EXPECT_NE(error("  - {type: contact, bodies: [ball, ground], point: [0,0,0], plane: {point: [0,0,0], nromal: [0,0,1]}, "
                  "stiffness: 1e5}\n")
                .find("nromal"),
            std::string::npos);
}

}  // namespace
}  // namespace fc::mbs::test
