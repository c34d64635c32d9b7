// The segment-against-edge and edge-against-plane contacts (force_elements.h,
// contactState) against references that do not come from the code:
// - the closest points of two segments by hand (a crossing, an end clamped,
//   parallel segments);
// - a rod resting across a fixed edge, skewed: the penetration r + h - 0.012
//   by hand, the push along the common normal of the two lines, the moment of
//   that force about the rod's centre (Euler's equations at t ~ 0);
// - a rigid rod falling flat onto a fixed edge (linear law): impact at the
//   free flight's time, contact for half a period pi sqrt(m_eff / k), and the
//   rebound of a rigid-body impact with e = 1 and the effective mass
//   m_eff = 1 / (1/m + a^2 / I) of a point a off the centre (Goldsmith,
//   Impact, 1960, ch. 2): v' = v0 (2 m_eff / m - 1), omega' = 2 m_eff v0 a / I;
//   with damping, the Lankarani-Nikravesh restitution as the point contact's;
// - a panel's face sloping across another panel's rim between its nodes (the
//   monitor's 0, the rim's distance to the face by hand);
// - the closest points of a segment and a triangle by hand (through the face,
//   an end over the face, beside an edge, past a vertex), with the
//   barycentric weights that share the force among the triangle's nodes;
// - a rod pressed by a constant force onto a clamped beam's edge (its mesh
//   nodes): static deflection F x^3 / (3 EI) (Euler-Bernoulli) plus F / k;
// - a flexible beam's edge (its mesh nodes) against a fixed plane patch: the
//   same statics with the load carried by the nodes that touch.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "beam_body.h"
#include "helpers.h"
#include "mbs-run/mechanics/force_elements.h"
#include "mbs-run/monitors/distance.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

using Eigen::Vector3d;

TEST(EdgeContact, ClosestPointsOfTwoSegmentsByHand) {
  double s = -1, t = -1;
  // x axis [0, 2] and a segment along y at x = 0.5, z = 1: s = 0.25, t = 0.5, distance 1.
  closestSegmentPoints({0, 0, 0}, {2, 0, 0}, {0.5, -1, 1}, {0.5, 1, 1}, s, t);
  EXPECT_NEAR(s, 0.25, 1e-15);
  EXPECT_NEAR(t, 0.5, 1e-15);
  // The second segment beyond the first's end (x = 3): s clamps to 1, t = 0.5,
  // the points (2, 0, 0) and (3, 0, 1).
  closestSegmentPoints({0, 0, 0}, {2, 0, 0}, {3, -1, 1}, {3, 1, 1}, s, t);
  EXPECT_NEAR(s, 1.0, 1e-15);
  EXPECT_NEAR(t, 0.5, 1e-15);
  // Both ends clamped: segment 2 from (3, 1, 0) to (3, 2, 0): closest (2,0,0)-(3,1,0).
  closestSegmentPoints({0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {3, 2, 0}, s, t);
  EXPECT_NEAR(s, 1.0, 1e-15);
  EXPECT_NEAR(t, 0.0, 1e-15);
  // Parallel, overlapping: any pair at the lines' distance; the one returned must be it.
  closestSegmentPoints({0, 0, 0}, {2, 0, 0}, {1, 0, 0.5}, {3, 0, 0.5}, s, t);
  const Vector3d c1 = Vector3d(0, 0, 0) + s * Vector3d(2, 0, 0), c2 = Vector3d(1, 0, 0.5) + t * Vector3d(2, 0, 0);
  EXPECT_NEAR((c1 - c2).norm(), 0.5, 1e-15);
}

TEST(SurfaceContact, ClosestPointsOfASegmentAndATriangleByHand) {
  // The triangle a = (0,0,0), b = (1,0,0), c = (0,1,0) in z = 0.
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  double s = -1;
  Vector3d l;
  // Through the face at (0.2, 0.3, 0), a quarter along the segment: distance 0,
  // s = 0.25, weights (0.5, 0.2, 0.3).
  EXPECT_EQ(closestSegmentTrianglePoints({0.2, 0.3, -0.5}, {0.2, 0.3, 1.5}, a, b, c, s, l), 0.0);
  EXPECT_NEAR(s, 0.25, 1e-15);
  EXPECT_NEAR((l - Vector3d(0.5, 0.2, 0.3)).norm(), 0.0, 1e-15);
  // A vertical segment from (0.1, 0.2, 0.3) up: its lower end over the face,
  // distance 0.3, s = 0, weights (0.7, 0.1, 0.2).
  EXPECT_NEAR(closestSegmentTrianglePoints({0.1, 0.2, 0.3}, {0.1, 0.2, 2.0}, a, b, c, s, l), 0.3, 1e-15);
  EXPECT_EQ(s, 0.0);
  EXPECT_NEAR((l - Vector3d(0.7, 0.1, 0.2)).norm(), 0.0, 1e-15);
  // A horizontal segment along x at y = -0.4, z = 0.3, from x = 0.5 to 1.5:
  // closest to the edge ab, the whole overlap x in [0.5, 1] at distance 0.5
  // (any pair there; the one returned must be at that distance, on ab).
  const double d = closestSegmentTrianglePoints({0.5, -0.4, 0.3}, {1.5, -0.4, 0.3}, a, b, c, s, l);
  EXPECT_NEAR(d, 0.5, 1e-15);
  EXPECT_NEAR(l[2], 0.0, 1e-15);
  EXPECT_NEAR(l.sum(), 1.0, 1e-15);
  const Vector3d ci = Vector3d(0.5, -0.4, 0.3) + s * Vector3d(1, 0, 0), cj = l[0] * a + l[1] * b + l[2] * c;
  EXPECT_NEAR((ci - cj).norm(), 0.5, 1e-15);
  // A segment from (-1, 2, 0) to (-1, 2, 1), beyond vertex c: the vertex, at
  // distance sqrt(1 + 1) from the segment's lower end.
  EXPECT_NEAR(closestSegmentTrianglePoints({-1, 2, 0}, {-1, 2, 1}, a, b, c, s, l), std::sqrt(2.0), 1e-15);
  EXPECT_EQ(s, 0.0);
  EXPECT_NEAR((l - Vector3d(0, 0, 1)).norm(), 0.0, 1e-15);
  // A vertical segment through z = 0 at (0.75, 0.75), outside the triangle
  // beyond edge bc: closest to that edge's middle (0.5, 0.5, 0), distance
  // sqrt(0.125), s = 0.5, weights (0, 0.5, 0.5).
  EXPECT_NEAR(closestSegmentTrianglePoints({0.75, 0.75, -1.0}, {0.75, 0.75, 1.0}, a, b, c, s, l), std::sqrt(0.125),
              1e-15);
  EXPECT_NEAR(s, 0.5, 1e-15);
  EXPECT_NEAR((l - Vector3d(0, 0.5, 0.5)).norm(), 0.0, 1e-15);
}

TEST(SurfaceContact, FaceAcrossAPanelRimByHand) {
  // The SAR lay-up 1 case in miniature: a triangle of a bent panel whose two
  // nodes A, B lie 2 mm above a 2.0 x 1.3 m mid-plane rectangle (z = 0), 20 mm
  // inside its rim x = -1, and whose third node C hangs below it outside the
  // rim: z = 0.002 - (0.04 / 0.3)(-0.98 - x), so at the rim the face is
  // 0.002 - 0.02 (0.04 / 0.3) = -2/3 mm, below the mid-plane. The monitor's
  // distance is 0 (the face crosses the rectangle at x = -0.985), although
  // every node is 2 mm off it; the rim as a segment against the face is the
  // line's distance to the plane, (2/3 mm) cos(atan(0.04 / 0.3)).
  BodyGeometry tri;
  tri.vertices.resize(3, 3);
  tri.vertices << -0.98, -0.98, -1.28, 0.1, -0.1, 0.0, 0.002, 0.002, -0.038;
  tri.triangles.push_back({0, 1, 2});
  const BodyGeometry rect = rectangleGeometry(2.0, 1.3);
  EXPECT_EQ(geometryDistance(tri, tri.vertices, rect, rect.vertices), 0.0);
  double s = -1;
  Vector3d l;
  const Vector3d a = tri.vertices.col(0), b = tri.vertices.col(1), c = tri.vertices.col(2);
  const Vector3d p(-1.0, -0.65, 0.0), q(-1.0, 0.65, 0.0);
  const double d = closestSegmentTrianglePoints(p, q, a, b, c, s, l);
  const double ref = (2.0e-3 / 3.0) * std::cos(std::atan(0.04 / 0.3));
  EXPECT_NEAR(d, ref, 1e-15);
  EXPECT_NEAR(((p + s * (q - p)) - (l[0] * a + l[1] * b + l[2] * c)).norm(), d, 1e-15);
  EXPECT_NEAR(l.sum(), 1.0, 1e-15);
  EXPECT_GE(l.minCoeff(), 0.0);
}

// A fixed ground with an edge along x (points [-1, 0, 0] and [1, 0, 0]).
const char* kGround = R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
)";

TEST(EdgeContact, SkewedRodOnEdgePushesAlongTheCommonNormal) {
  // The rod's axis: frame at (0.1, -0.1, 0.012), points (-0.1, -0.1, 0) and
  // (0.5, 0.5, 0) in its axes: the line (0.1 + u, -0.1 + u, 0.012). The edge
  // is the x axis. The lines' common normal is (1,0,0) x (1,1,0) = +z, the
  // closest points (0.2, 0, 0.012) on the rod (s = 1/3, body point (0.1, 0.1, 0))
  // and (0.2, 0, 0) on the edge (t = 0.6), distance 0.012; with r = 0.01 and
  // h = 0.005 the penetration is 0.003 and the force k 0.003 = 300 N along +z
  // at the body point (0.1, 0.1, 0): moment (0.1, 0.1, 0) x (0, 0, 300) = (30, -30, 0).
  const double m = 2.0, I = 0.05, k = 1.0e5, F = k * 0.003, dt = 1e-6;
  char s[1400];
  std::snprintf(s, sizeof s, R"(%s  - {name: rod, rigid: {mass: %g, inertia: [[%g,0,0],[0,%g,0],[0,0,%g]]},
     position: [0.1, -0.1, 0.012]}
forces:
  - {name: cross, type: contact, bodies: [rod, ground], segment: {points: [[-0.1, -0.1, 0], [0.5, 0.5, 0]], radius: 0.01},
     edge: {points: [[-1, 0, 0], [1, 0, 0]], half_thickness: 0.005}, stiffness: %g}
simulation: {t_end: %g, output_step: %g, rtol: 1.0e-12, integrator: dopri5}
)",
                kGround, m, I, I, I, k, dt, dt);
  const Results r = simulate(sceneFromText(s), {true});
  ASSERT_EQ(r.status, "completed");
  EXPECT_NEAR(r.contact_penetration[0].front(), 0.003, 1e-15);
  EXPECT_NEAR(r.contact_force[0].front(), F, 1e-9 * F);
  // After dt the velocities are F dt / m along +z and I^-1 (30, -30, 0) dt, to
  // first order in dt (the force changes by k v dt over the step: relative
  // 1e-6 here).
  const Vector3d v = r.velocity[1].back(), w = r.angular_velocity[1].back();
  std::printf("[   info   ] skewed rod: v = (%.3e, %.3e, %.9e) (F dt / m = %.9e), w = (%.9e, %.9e, %.3e)\n", v.x(), v.y(),
              v.z(), F * dt / m, w.x(), w.y(), w.z());
  EXPECT_NEAR(v.z(), F * dt / m, 1e-5 * F * dt / m);
  EXPECT_NEAR(v.x(), 0.0, 1e-12);
  EXPECT_NEAR(v.y(), 0.0, 1e-12);
  EXPECT_NEAR(w.x(), 30.0 * dt / I, 1e-5 * 30.0 * dt / I);
  EXPECT_NEAR(w.y(), -30.0 * dt / I, 1e-5 * 30.0 * dt / I);
  EXPECT_NEAR(w.z(), 0.0, 1e-12);
}

struct Bounce {
  double t_in = -1.0, t_out = -1.0;
  double energy_error = 0.0;
};

Bounce measure(const Results& r) {
  Bounce b;
  const std::vector<double>& d = r.contact_penetration.at(0);
  for (std::size_t i = 1; i < r.time.size(); ++i) {
    const double t = r.time[i - 1] + (r.time[i] - r.time[i - 1]) * d[i - 1] / (d[i - 1] - d[i]);
    if (b.t_in < 0 && d[i - 1] <= 0 && d[i] > 0) b.t_in = t;
    else if (b.t_in >= 0 && b.t_out < 0 && d[i - 1] > 0 && d[i] <= 0) b.t_out = t;
  }
  const double e0 = r.kinetic[0] + r.potential[0] + r.strain[0];
  for (std::size_t i = 0; i < r.time.size(); ++i)
    b.energy_error =
        std::max(b.energy_error, std::abs(r.kinetic[i] + r.potential[i] + r.strain[i] + r.dissipated[i] - e0));
  return b;
}

// A rod along y (1 m, its centre the frame origin) falling flat at v0 from
// z = 0.1 onto the fixed edge along x at y = a (r = 0.01, h = 0.005: touching
// at z = 0.015).
Results fallingRod(double a, double m, double I, double k, const std::string& extra, double t_end, double rtol) {
  char s[1600];
  std::snprintf(s, sizeof s, R"(%s  - {name: rod, rigid: {mass: %.17g, inertia: [[%.17g,0,0],[0,%.17g,0],[0,0,%.17g]]},
     position: [0, 0, 0.1], velocity: [0, 0, -1.0]}
forces:
  - {name: cross, type: contact, bodies: [rod, ground], segment: {points: [[0, -0.5, 0], [0, 0.5, 0]], radius: 0.01},
     edge: {points: [[-1, %.17g, 0], [1, %.17g, 0]], half_thickness: 0.005}, stiffness: %.17g%s}
simulation: {t_end: %.17g, output_step: 1.0e-5, rtol: %.17g, integrator: dopri5}
)",
                kGround, m, I, I, I, a, a, k, extra.c_str(), t_end, rtol);
  return simulate(sceneFromText(s), {true});
}

TEST(EdgeContact, RodFallingOnAnEdgeReboundsAsARigidImpact) {
  const double m = 2.0, I = 0.1, k = 1.0e7, v0 = 1.0;
  for (const double a : {0.0, 0.3}) {
    const double meff = 1.0 / (1.0 / m + a * a / I);
    const double T = M_PI * std::sqrt(meff / k);
    // rtol 1e-11: the 3 kHz contact on the 1 J impact needs it for the run's
    // own energy-balance check (at 1e-10 the balance error, 6e-7 J, exceeds
    // the bound the run derives from rtol).
    const Results r = fallingRod(a, m, I, k, "", 0.085 + T + 0.002, 1e-11);
    ASSERT_EQ(r.status, "completed");
    const Bounce b = measure(r);
    const double vz = r.velocity[1].back().z(), wx = r.angular_velocity[1].back().x();
    const double vz_ref = v0 * (2.0 * meff / m - 1.0), wx_ref = 2.0 * meff * v0 * a / I;
    std::printf("[   info   ] rod on edge a = %.1f: impact %.9f s (0.085), contact %.9f s (%.9f), v' %.9f (%.9f), "
                "w' %.9f (%.9f), energy %.2e J\n",
                a, b.t_in, b.t_out - b.t_in, T, vz, vz_ref, wx, wx_ref, b.energy_error);
    ASSERT_GT(b.t_out, 0.0);
    // Row interpolation (1e-5 s rows: free flight on one side, curvature
    // w^2 step^3 / 6 ~ 2e-12 s on the other) and rtol 1e-11.
    EXPECT_NEAR(b.t_in, 0.085, 1e-9);
    // The rigid-impact reference is linear in the rod's turn phi during
    // contact. The distance of the two lines is z_c cos(phi) + a sin(phi)
    // (z_c the rod's height, r + h = 0.015 m at contact): its next term,
    // z_c phi^2 / 2 with phi <= w' T / 2 = 1.8e-3 rad, is 2.4e-8 m, 9e-5 of
    // the 0.27 mm the contact compresses; 2e-4 bounds it. The contact lasts
    // 0.84 ms at a = 0.3 (measured 2.7e-5 off), 1.4 ms at a = 0.
    EXPECT_NEAR(b.t_out - b.t_in, T, 2e-4 * T);
    EXPECT_NEAR(vz, vz_ref, 2e-4 * v0);
    EXPECT_NEAR(wx, wx_ref, 2e-4 * std::max(1.0, wx_ref));
    // Elastic: the energy of the 1 J impact back to the run's accuracy.
    EXPECT_LT(b.energy_error, 1e-7);
  }
}

TEST(EdgeContact, RodOnEdgeRestitutionAsThePointContact) {
  // The segment contact uses the point contact's law: its rebound ratio for
  // e = 0.9 at v0 is the 1-DOF integration's 0.913176678 (test_contact.cpp,
  // HuntCrossleyRestitution; tests/data/mbs-run/contact/ln_restitution.py).
  const double m = 2.0, I = 0.1, k = 1.0e7;
  const Results r = fallingRod(0.0, m, I, k, ", restitution: 0.9, impact_speed: 1.0", 0.085 + 0.006, 1e-10);
  ASSERT_EQ(r.status, "completed");
  const double e = r.velocity[1].back().z();
  std::printf("[   info   ] rod on edge, e = 0.9: rebound ratio %.9f (0.913176678)\n", e);
  // As the point contact's check: the run's error at rtol 1e-10 (1e-8 measured there).
  EXPECT_NEAR(e, 0.913176678, 5e-8);
  EXPECT_NEAR(r.dissipated.back(), 0.5 * m * (1.0 - e * e), 1e-7);
}

// The clamped cantilever of beam_body.h (1 m along x, EI 80 N m^2, 20
// elements, 6 modes, bending in y), modal damping 20 % so that it settles.
// Its static flexibility at x with the modes kept, against Euler-Bernoulli's
// x^3 / (3 EI): each of a uniform cantilever's modes carries 12 / (beta_i L)^4
// of the tip's (Blevins, Formulas for Natural Frequency and Mode Shape,
// table 8-1: beta L = 1.875, 4.694, 7.855, 10.996, 14.137, 17.279, 20.420,
// ...), so the modes beyond the sixth miss 12 sum_{i>6} 1 / (beta_i L)^4 =
// 1.9e-4 of it; the 20 cubic elements are exact at the nodes.
constexpr double kEI = 80.0, kTruncation = 1.9e-4;

TEST(EdgeContact, RodPressedOnABeamEdgeDeflectsItStatically) {
  BeamSpec spec;
  spec.modes = 6;
  const BeamModel beam = cantileverBeam(spec);
  const std::string file = writeBeam(beam, "edge_press");
  // A rod along z (r = 0.005) over the beam's node at x = 0.95 (h = 0.005),
  // touching at y = 0.01, pushed down by F = 1 N: at rest the beam's node
  // deflects F x^3 / (3 EI) and the contact compresses F / k. A guide keeps
  // the rod moving along y only: free, it slides off the bent beam's end
  // (the normal tilts with the slope, 5 mm / m at x = 0.95), as a real rod
  // would; the tilt changes the force's y part by slope^2 / 2 ~ 1.5e-5.
  const double F = 1.0, k = 1.0e4, x = 0.95;
  char s[1600];
  std::snprintf(s, sizeof s, R"(%s  - name: beam
    flexible: {file: %s, modes: 6, damping_ratio: 0.2}
  - {name: rod, rigid: {mass: 0.05, inertia: [[1e-3,0,0],[0,1e-3,0],[0,0,1e-3]]}, position: [%g, 0.0101, 0]}
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
  - {name: guide, type: prismatic, bodies: [ground, rod], points: [[%g, 0, 0], [0, 0, 0]], axes: [[0, 1, 0], [0, 1, 0]]}
forces:
  - {name: press, type: contact, bodies: [rod, beam], segment: {points: [[0, 0, -0.1], [0, 0, 0.1]], radius: 0.005},
     edge: {from: [0, 0, 0], to: [1, 0, 0], half_thickness: 0.005}, stiffness: %g,
     restitution: 0.3, impact_speed: 0.05}
  - {type: force, body: rod, force: [0, %g, 0]}
simulation: {t_end: 3.0, output_step: 0.01, rtol: 1.0e-8, integrator: dopri5}
)",
                kGround, file.c_str(), x, x, k, -F);
  const Results r = simulate(sceneFromText(s), {true});
  std::filesystem::remove(file);
  ASSERT_EQ(r.status, "completed");
  const double y_ref = 0.01 - F / k - F * x * x * x / (3.0 * kEI);
  const double y = r.position[2].back().y();
  std::printf("[   info   ] rod on the beam edge: y %.9e m (Euler-Bernoulli %.9e), force %.9f N, |v| %.2e m/s\n", y,
              y_ref, r.contact_force[0].back(), r.velocity[2].back().norm());
  // At rest (e^-19 of the start after 3 s of 20 % damping on 31 rad/s).
  EXPECT_LT(r.velocity[2].back().norm(), 1e-6);
  // The force is along the edge's normal, tilted by the beam's slope
  // F x^2 / (2 EI) = 5.6e-3 rad at x = 0.95: its size is F / cos = F (1 + 1.6e-5).
  EXPECT_NEAR(r.contact_force[0].back(), F, 3e-5 * F);
  // The beam's part to the truncation of its modes (1.9e-4 of it, above).
  EXPECT_NEAR(y, y_ref, 2.0 * kTruncation * F * x * x * x / (3.0 * kEI));
}

TEST(EdgeContact, BeamEdgeOnAPlaneCarriesTheLoadThroughItsNodes) {
  // The same cantilever, its edge (all 21 nodes, h = 0.005) over a fixed
  // plane y = -0.0051 patch x in [0.899, 1.001] (a rectangle about x = 0.95,
  // half sizes 0.051 and 1): the nodes at x = 0.9, 0.95, 1.0 may touch, each
  // a spring k = 1e5 N/m once its deflection passes the 0.1 mm gap. A 1 N
  // load down at the tip. Reference: Euler-Bernoulli's influence
  // coefficients a(x, y) = x^2 (3 y - x) / (6 EI) (x <= y) with the pads'
  // springs, (I + k A) P = k (a_tip - gap) over the nodes in contact: the
  // node at 0.9 comes out lifted (7.9 um short of the pad), the two others
  // carry P = 0.05970 and 0.91857 N, total 0.978269 N, the deepest
  // penetration 9.1857 um at the tip.
  BeamSpec spec;
  spec.modes = 6;
  const BeamModel beam = cantileverBeam(spec);
  const std::string file = writeBeam(beam, "edge_plane");
  char s[1600];
  std::snprintf(s, sizeof s, R"(%s  - name: beam
    flexible: {file: %s, modes: 6, damping_ratio: 0.2}
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
forces:
  - {name: pads, type: contact, bodies: [beam, ground], edge: {from: [0, 0, 0], to: [1, 0, 0], half_thickness: 0.005},
     plane: {point: [0.95, -0.0051, 0], normal: [0, 1, 0], rectangle: {axis: [1, 0, 0], half_sizes: [0.051, 1.0]}},
     stiffness: 1.0e5, restitution: 0.3, impact_speed: 0.05}
  - {type: force, body: beam, point: tip, force: [0, -1.0, 0]}
simulation: {t_end: 3.0, output_step: 0.01, rtol: 1.0e-8, integrator: dopri5}
)",
                kGround, file.c_str());
  const Results r = simulate(sceneFromText(s), {true});
  std::filesystem::remove(file);
  ASSERT_EQ(r.status, "completed");
  std::printf("[   info   ] beam edge on pads: force %.9f N (0.978269 N), deepest %.6e m (9.1857e-06), clamp y %.3e N\n",
              r.contact_force[0].back(), r.contact_penetration[0].back(), r.reaction[0].back().y());
  // The pads' split is fixed by the beam's flexibilities, each off by the
  // modes' truncation (1.9e-4 of itself, above): 1e-3 N. The penetration is
  // a small difference of millimetre deflections (9.2 um out of the free
  // tip's 4.2 mm), so the same relative error weighs ~10x more on it: 5e-3
  // of it (measured: force 1.9e-4 N, penetration 2.6e-3 of it).
  EXPECT_NEAR(r.contact_force[0].back(), 0.978269, 1e-3);
  EXPECT_NEAR(r.contact_penetration[0].back(), 9.1857e-6, 5e-3 * 9.1857e-6);
  // Statics in y: the pads and the clamp carry the 1 N (the reaction is the
  // force on the joint's first body, the ground).
  EXPECT_NEAR(r.contact_force[0].back() - r.reaction[0].back().y(), 1.0, 1e-6);
}

TEST(EdgeContact, BadInputIsNamed) {
  const std::string head = std::string(kGround) + R"(  - {name: rod, rigid: {mass: 2.0, inertia: [[0.01,0,0],[0,0.01,0],[0,0,0.01]]}}
forces:
)";
  auto fails = [&](const std::string& force, const std::string& expect) {
    try {
      sceneFromText(head + force + "simulation: {t_end: 0.1}\n");
      ADD_FAILURE() << "no error for " << force;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  };
  fails("  - {type: contact, bodies: [rod, ground], segment: {points: [[0,0,0],[0,1,0]]}, plane: {point: [0,0,0], "
        "normal: [0,0,1]}, stiffness: 1.0}\n",
        "not a plane");
  fails("  - {type: contact, bodies: [rod, ground], segment: {points: [[0,0,0],[0,1,0]]}, edge: {points: [[0,0,0]]}, "
        "stiffness: 1.0}\n",
        "at least two points");
  fails("  - {type: contact, bodies: [rod, ground], segment: {points: [[0,0,0],[0,1,0]]}, edge: {from: [0,0,0], "
        "to: [1,0,0]}, stiffness: 1.0}\n",
        "is rigid");
  fails("  - {type: contact, bodies: [rod, ground], point: [0,0,0], edge: {points: [[0,0,0],[1,0,0]]}, "
        "plane: {point: [0,0,0], normal: [0,0,1]}, stiffness: 1.0}\n",
        "expected one of");
  fails("  - {type: contact, bodies: [rod, ground], edge: {points: [[0,0,0],[1,0,0]]}, plane: {point: [0,0,0], "
        "normal: [0,0,1], rectangle: {axis: [0,0,1], half_sizes: [1,1]}}, stiffness: 1.0}\n",
        "in the plane");
  fails("  - {type: contact, bodies: [rod, ground], segment: {points: [[0,0,0],[0,1,0]]}, surface: {half_thickness: "
        "0.001}, stiffness: 1.0}\n",
        "is rigid");
  fails("  - {type: contact, bodies: [rod, ground], point: [0,0,0], plane: {point: [0,0,0], normal: [0,0,1]}, "
        "surface: {}, stiffness: 1.0}\n",
        "met by a 'segment'");
}

}  // namespace
}  // namespace fc::mbs::test
