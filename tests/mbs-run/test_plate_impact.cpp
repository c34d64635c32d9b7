// A point mass striking the centre of a clamped square plate built by fe-prep
// (DST shells, all four edges clamped for the modes), through the one-sided
// linear `contact` force element, against the plate's modal impact solution
// computed here from the same body's modes.
//
// Reference: in contact, the mass's normal coordinate z_b and the plate's
// modal coordinates q obey the linear system M x'' + K x = 0, x = [z_b, q],
// M = diag(m, M_q) (M_q the body's modal mass, computeInertiaInvariants),
// K = k a a^T + diag(0, Lambda), a = [-1, psi] (psi: the centre interface's z
// shapes), the penetration being d = a^T x; from the first touch (x = 0,
// x' = [-v0, 0]) its solution is x(t) = sum_i phi_i phi_i^T M x'(0)
// sin(w_i t) / w_i over K phi = w^2 M phi (M-orthonormal), and the contact
// ends at the first zero of d. The contact force is k d, its peak the
// largest k d(t) on the way. That is the classical modal solution of a
// mass-plate impact with a linear contact spring (e.g. Goldsmith, Impact,
// 1960, ch. 4, and Christoforou & Yigit's spring-mass impact models), exact
// for the linear model; mbs-run integrates the full floating-frame equations
// of the flexible body (frame held by a fixed joint at the clamped edge) and
// the contact element's plane moving with the interface. No gravity: the
// mass arrives at v0 (dropped from v0^2 / 2g), so the plate starts
// undeformed, as the reference does. v0 is small (2 cm/s; the centre turns by
// ~1e-5 rad) so the geometric terms the linear reference leaves out (the
// plane's turn with the interface, ~slope^2) stay below 1e-8 of the motion.
//
// The same impact through the segment-against-surface contact: a short rod
// standing on the mass (its lower end the mass's centre, radius r) against the
// plate's shell triangles (half thickness h), started r + h higher. Its lower
// end stays over the centre node (the plate's deflection is symmetric about
// it), so the closest point is that node with weight 1 and the contact is the
// point contact's: the same modal solution, to the same tolerances. (The
// triangles near the centre only, `near:`, as a scene would select them.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "../fe-prep/feprep_test_support.h"
#include "common/flexbody.h"
#include "helpers.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

// A 0.4 m square aluminium plate, 3 mm thick, clamped on its four edges; the
// body frame at its centre; interfaces at the centre (the struck point) and
// at the middle of the clamped edge x = -0.2 (a held node: the fixed joint's
// point; a rigid patch over the edge would overlap the clamped sets).
constexpr const char* kPlate = R"(
materials:
  al: {type: isotropic, E: 70.0e9, nu: 0.3, rho: 2700}
body:
  name: plate
  shell: {rectangle: {length: 0.4, width: 0.4}, material: al, thickness: 0.003, mesh: {size: 0.05}}
  interfaces:
    centre: [0, 0, 0]
    edge: [-0.2, 0, 0]
  reference: {clamp: [edge_xmin, edge_xmax, edge_ymin, edge_ymax]}
  mass: lumped
  modes: 6
)";

void massOnClampedPlate(bool surface) {
  const int nm = 6;
  const feprep::BuildResult built = feprep::test::runYaml(kPlate);
  const fc::FlexBody& body = built.body;
  const std::string file = writeTempBody(body, "plate_impact");
  const double m = 0.05, k = 2.0e4, v0 = 0.02, gap = 2.0e-4;
  // The reference system from the body's own modes.
  const Eigen::VectorXd psi = body.interface("centre").shapes.col(2).head(nm);
  const Eigen::VectorXd lambda = body.eigenvalues.head(nm);
  const Eigen::MatrixXd Mq = fc::computeInertiaInvariants(body, nm).modalMass();
  Eigen::VectorXd a(nm + 1);
  a << -1.0, psi;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(nm + 1, nm + 1), K = k * a * a.transpose();
  M(0, 0) = m;
  M.bottomRightCorner(nm, nm) = Mq;
  K.diagonal().tail(nm) += lambda;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  const Eigen::VectorXd w = es.eigenvalues().cwiseSqrt();
  const Eigen::MatrixXd Phi = es.eigenvectors();  // M-orthonormal
  Eigen::VectorXd xd0 = Eigen::VectorXd::Zero(nm + 1);
  xd0(0) = -v0;
  const Eigen::VectorXd c = Phi.transpose() * M * xd0;
  auto x = [&](double t) { return Eigen::VectorXd(Phi * (c.array() * (w.array() * t).sin() / w.array()).matrix()); };
  auto xd = [&](double t) { return Eigen::VectorXd(Phi * (c.array() * (w.array() * t).cos()).matrix()); };
  // First zero of d = a^T x after the touch (scanned at 1 us, then bisected),
  // and the peak of k d on the way.
  double lo = 1e-6, peak = 0.0;
  while (a.dot(x(lo + 1e-6)) > 0) {
    lo += 1e-6;
    peak = std::max(peak, k * a.dot(x(lo)));
  }
  double hi = lo + 1e-6;
  for (int it = 0; it < 60; ++it) (a.dot(x(0.5 * (lo + hi))) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double T = 0.5 * (lo + hi);
  const Eigen::VectorXd xe = x(T), xde = xd(T);
  const double plate_energy = 0.5 * (xde.tail(nm).dot(Mq * xde.tail(nm)) + lambda.dot(xe.tail(nm).cwiseAbs2()));
  ASSERT_LT(T, 0.05);

  // The contact: the mass's centre against the plane through the centre
  // interface, or a rod on the mass (r = 1 mm) against the plate's triangles
  // (h = 1.5 mm), started r + h higher.
  const double rh = surface ? 0.0025 : 0.0;
  const std::string contact =
      surface ? "segment: {points: [[0, 0, 0], [0, 0, 0.05]], radius: 0.001}, surface: {half_thickness: 0.0015, "
                "near: {from: [-0.05, 0, 0], to: [0.05, 0, 0], distance: 0.02}}"
              : "point: [0, 0, 0], plane: {point: centre, normal: [0, 0, 1]}";
  char scene[1800];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: plate
    flexible: {file: %s, modes: %d}
  - {name: mass, rigid: {mass: %.17g, inertia: [[1e-6,0,0],[0,1e-6,0],[0,0,1e-6]]}, position: [0, 0, %.17g],
     velocity: [0, 0, %.17g]}
joints:
  - {name: clamp, type: fixed, bodies: [ground, plate], points: [[-0.2, 0, 0], edge]}
forces:
  - {name: centre, type: contact, bodies: [mass, plate], %s,
     stiffness: %.17g}
simulation: {t_end: %.17g, output_step: 2.0e-6, rtol: 1.0e-10}
)",
                file.c_str(), nm, m, gap + rh, -v0, contact.c_str(), k, gap / v0 + 1.3 * T);
  const Results r = simulate(sceneFromText(scene), {true});
  std::filesystem::remove(file);
  ASSERT_EQ(r.status, "completed");
  // Contact times from the penetration rows (linear interpolation between the
  // rows that straddle each zero).
  const std::vector<double>& d = r.contact_penetration.at(0);
  double t_in = -1.0, t_out = -1.0, run_peak = 0.0;
  for (std::size_t i = 1; i < r.time.size(); ++i) {
    const double t = r.time[i - 1] + (r.time[i] - r.time[i - 1]) * d[i - 1] / (d[i - 1] - d[i]);
    if (t_in < 0 && d[i - 1] <= 0 && d[i] > 0) t_in = t;
    else if (t_in >= 0 && t_out < 0 && d[i - 1] > 0 && d[i] <= 0) t_out = t;
    run_peak = std::max(run_peak, r.contact_force.at(0)[i]);
  }
  const Eigen::VectorXd qe = r.modal[1].back(), qde = r.modal_rate[1].back();
  const double plate_run = 0.5 * (qde.dot(Mq * qde) + lambda.dot(qe.cwiseAbs2()));
  const double e_in = 0.5 * m * v0 * v0;
  double balance = 0.0;
  const double e0 = r.kinetic[0] + r.potential[0] + r.strain[0];
  for (std::size_t i = 0; i < r.time.size(); ++i)
    balance = std::max(balance, std::abs(r.kinetic[i] + r.potential[i] + r.strain[i] + r.dissipated[i] - e0));
  std::printf("[   info   ] mass on the clamped plate, %s (f1 %.1f Hz): impact %.9f s (%.9f), contact %.9f s (modal "
              "solution %.9f), peak force %.6f N (%.6f), rebound %.9f m/s (%.9f), plate energy %.6e J (%.6e) of %.3e J, "
              "energy balance %.2e J\n",
              surface ? "rod on its triangles" : "point on the centre's plane", std::sqrt(lambda(0)) / (2 * M_PI), t_in, gap / v0, t_out - t_in, T, run_peak, peak,
              r.velocity[2].back().z(), xde(0), plate_run, plate_energy, e_in, balance);
  ASSERT_GT(t_out, 0.0);  // the mass left the plate before t_end
  EXPECT_NEAR(t_in, gap / v0, 1e-9);
  // Row interpolation: the contact's curvature over a 2 us row, w^2 dt^2 / 8 of
  // the penetration's slope time, ~1e-6 of the contact at the highest
  // frequency in contact; the run at rtol 1e-10: 1e-5 relative.
  EXPECT_NEAR(t_out - t_in, T, 1e-5 * T);
  // The peak between rows: a row misses it by at most the curvature over half
  // a row, (w dt / 2)^2 / 2 ~ 1e-3 relative for the stiffest contact mode; the
  // reference's own scan at 1 us misses it by less.
  EXPECT_NEAR(run_peak, peak, 2e-3 * peak);
  EXPECT_NEAR(r.velocity[2].back().z(), xde(0), 1e-5 * v0);
  EXPECT_NEAR(plate_run, plate_energy, 1e-5 * e_in);
  // Elastic contact, no damping: T + V + U conserved to the integration's
  // tolerance (rtol 1e-10 over ~1e3 steps).
  EXPECT_LT(balance, 1e-6 * e_in);
}

TEST(PlateImpact, MassOnClampedPlateMatchesModalSolution) { massOnClampedPlate(false); }

TEST(PlateImpact, RodOnThePlatesTrianglesMatchesModalSolution) { massOnClampedPlate(true); }

}  // namespace
}  // namespace fc::mbs::test
