// Contact monitor: the distance kernels against hand-computed
// configurations (skew, parallel and disjoint segments, every Voronoi region
// of a triangle, a segment through a triangle), and the monitor in runs: a
// rod crossing another rod and a plate at constant velocity (distance
// |z0 - v t| exactly), and a flexible beam whose mesh nodes are moved by its
// modal coordinates (distance to a parallel rod = gap - largest deflection).
// The broad phase (bounding_volume_tree.h) against the brute force, bit for bit, on
// random poses and deformations of meshes, segments and points, on a
// closed-form bump under a rod, and on the samples of a run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "common/rotations.h"

#include "beam_body.h"
#include "helpers.h"
#include "mbs-run/monitors/bounding_volume_tree.h"
#include "mbs-run/monitors/distance.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

using Eigen::Vector3d;

TEST(DistanceKernels, Segments) {
  const Vector3d o(0, 0, 0), x(1, 0, 0);
  EXPECT_NEAR(segmentSegmentDistance(o, x, Vector3d(0.5, -1, 2), Vector3d(0.5, 1, 2)), 2.0, 1e-15);  // skew
  EXPECT_NEAR(segmentSegmentDistance(o, x, Vector3d(0.5, 1, 0), Vector3d(2, 1, 0)), 1.0, 1e-15);     // parallel
  EXPECT_NEAR(segmentSegmentDistance(o, x, Vector3d(2, 1, 0), Vector3d(3, 1, 0)), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(segmentSegmentDistance(o, x, Vector3d(0.3, -1, 0), Vector3d(0.3, 1, 0)), 0.0, 1e-15);  // crossing
  EXPECT_NEAR(segmentSegmentDistance(o, o, Vector3d(3, 4, 0), Vector3d(3, 4, 0)), 5.0, 1e-15);       // points
}

TEST(DistanceKernels, PointTriangleRegions) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  auto cp = [&](const Vector3d& p) { return closestPointOnTriangle(p, a, b, c); };
  EXPECT_NEAR((cp(Vector3d(0.2, 0.2, 3)) - Vector3d(0.2, 0.2, 0)).norm(), 0.0, 1e-15);  // face
  EXPECT_NEAR((cp(Vector3d(-1, -1, 1)) - a).norm(), 0.0, 1e-15);                        // vertex a
  EXPECT_NEAR((cp(Vector3d(2, -1, 0)) - b).norm(), 0.0, 1e-15);                         // vertex b
  EXPECT_NEAR((cp(Vector3d(-0.5, 2, 0)) - c).norm(), 0.0, 1e-15);                       // vertex c
  EXPECT_NEAR((cp(Vector3d(1, 1, 0)) - Vector3d(0.5, 0.5, 0)).norm(), 0.0, 1e-15);      // edge bc
  EXPECT_NEAR((cp(Vector3d(0.5, -2, 1)) - Vector3d(0.5, 0, 0)).norm(), 0.0, 1e-15);     // edge ab
  EXPECT_NEAR((cp(Vector3d(-3, 0.4, 0)) - Vector3d(0, 0.4, 0)).norm(), 0.0, 1e-15);     // edge ca
}

TEST(DistanceKernels, SegmentTriangle) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(segmentTriangleDistance(Vector3d(0.2, 0.2, -1), Vector3d(0.2, 0.2, 1), a, b, c), 0.0);   // through
  EXPECT_NEAR(segmentTriangleDistance(Vector3d(0.1, 0.1, 0.5), Vector3d(0.3, 0.2, 0.5), a, b, c), 0.5, 1e-15);
  EXPECT_NEAR(segmentTriangleDistance(Vector3d(2, 2, -1), Vector3d(2, 2, 1), a, b, c),
              (Vector3d(2, 2, 0) - Vector3d(0.5, 0.5, 0)).norm(), 1e-15);  // beside the edge bc
  EXPECT_NEAR(segmentTriangleDistance(Vector3d(-1, 0.5, 0.2), Vector3d(2, 0.5, 0.2), a, b, c), 0.2, 1e-15);
}

// A w x h grid of 2 nx ny triangles in the body x-y plane ([0, w] x [0, h]),
// with `modes` smooth mode shapes (bending along z, some in-plane stretch).
BodyGeometry gridMesh(int nx, int ny, double w, double h, int modes) {
  BodyGeometry g;
  g.vertices.resize(3, (nx + 1) * (ny + 1));
  g.modal_displacement.setZero(3 * g.vertices.cols(), modes);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const int k = j * (nx + 1) + i;
      const double x = w * i / nx, y = h * j / ny;
      g.vertices.col(k) = Vector3d(x, y, 0);
      for (int m = 0; m < modes; ++m) {
        g.modal_displacement(3 * k + 2, m) = std::sin((m + 1) * M_PI * x / w) * std::cos(m * M_PI * y / h);
        g.modal_displacement(3 * k, m) = 0.1 * std::sin(m * y / h) * x / w;
      }
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      g.triangles.push_back({a, b, c});
      g.triangles.push_back({a, c, d});
    }
  return g;
}

double bruteForce(const BodyGeometry& ga, const Vector3d& ra, const Eigen::Matrix3d& Aa, const Eigen::VectorXd& wa,
                  const BodyGeometry& gb, const Vector3d& rb, const Eigen::Matrix3d& Ab, const Eigen::VectorXd& wb) {
  return geometryDistance(ga, placedVertices(ga, ra, Aa, wa), gb, placedVertices(gb, rb, Ab, wb));
}

TEST(ContactTree, EqualsBruteForceBitForBit) {
  // A 24 x 16 panel (768 triangles, 4 modes) against a bent truss (3
  // segments, 2 modes), a cloud of points, a coarse second panel and a
  // rectangle, at random poses and deformations from crossing to 1 m apart.
  const BodyGeometry panel = gridMesh(24, 16, 1.5, 1.0, 4);
  BodyGeometry truss;
  truss.vertices.resize(3, 4);
  truss.vertices << 0, 0.3, 0.6, 0.9, 0, 0.05, 0.02, 0, 0, 0, 0.01, 0;
  truss.segments = {{0, 1}, {1, 2}, {2, 3}};
  truss.modal_displacement.setZero(12, 2);
  for (int k = 0; k < 4; ++k) {
    truss.modal_displacement(3 * k + 1, 0) = std::sin(M_PI * k / 3);
    truss.modal_displacement(3 * k + 2, 1) = std::sin(2 * M_PI * k / 3);
  }
  BodyGeometry points;
  points.vertices = Eigen::Matrix3Xd::Random(3, 7) * 0.3;
  const BodyGeometry coarse = gridMesh(3, 2, 0.6, 0.4, 1), plate = rectangleGeometry(0.8, 0.5);
  const std::vector<const BodyGeometry*> others = {&truss, &points, &coarse, &plate};
  const BoundingTree tpanel = buildBoundingTree(panel);
  std::vector<BoundingTree> tothers;
  for (const auto* g : others) tothers.push_back(buildBoundingTree(*g));

  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto rot = [&] { return expRotation(Vector3d(u(rng), u(rng), u(rng)) * 3.0); };
  int crossing = 0, apart = 0;
  for (int trial = 0; trial < 240; ++trial) {
    // The panel turned about its centre; the other body's origin within 0.6 m of it.
    const Eigen::Matrix3d Aa = rot(), Ab = rot();
    const Vector3d ra = -Aa * Vector3d(0.75, 0.5, 0), rb = 0.6 * Vector3d(u(rng), u(rng), u(rng));
    const Eigen::VectorXd wa = Eigen::VectorXd::NullaryExpr(4, [&] { return 0.05 * u(rng); });
    const std::size_t o = trial % others.size();
    const BodyGeometry& gb = *others[o];
    const Eigen::VectorXd wb = Eigen::VectorXd::NullaryExpr(gb.modal_displacement.cols(), [&] { return 0.05 * u(rng); });
    PlacedGeometry pa(panel, tpanel, ra, Aa, wa), pb(gb, tothers[o], rb, Ab, wb);
    const double tree = treeDistance(pa, pb), brute = bruteForce(panel, ra, Aa, wa, gb, rb, Ab, wb);
    ASSERT_EQ(tree, brute) << "trial " << trial << " against geometry " << o;
    // Either order of the pair (the monitor's pairs name either body first).
    PlacedGeometry qa(panel, tpanel, ra, Aa, wa), qb(gb, tothers[o], rb, Ab, wb);
    ASSERT_EQ(treeDistance(qb, qa), bruteForce(gb, rb, Ab, wb, panel, ra, Aa, wa)) << "trial " << trial << " swapped";
    (brute == 0.0 ? crossing : apart) += 1;
  }
  // The trials cover both intersecting and separated configurations.
  EXPECT_GT(crossing, 40);
  EXPECT_GT(apart, 40);
  std::printf("[   info   ] %d crossing, %d apart\n", crossing, apart);
}

TEST(ContactTree, BumpUnderARodClosedForm) {
  // Unit square mesh (20 x 20 cells) with one mode z = sin(pi x) sin(pi y),
  // amplitude w, under a rod along x at y = 0.5, height 0.3 (the grid has a
  // node at the bump's apex): distance 0.3 - w for w > 0 (the apex), 0.3 for
  // w <= 0 (the straight edges x = 0, 1 are at z = 0), zero once w > 0.3 (the
  // rod passes through the surface). Both bodies moved by one rigid motion.
  BodyGeometry sq = gridMesh(20, 20, 1.0, 1.0, 1);
  for (Eigen::Index k = 0; k < sq.vertices.cols(); ++k) {
    sq.modal_displacement.middleRows(3 * k, 3).setZero();
    sq.modal_displacement(3 * k + 2, 0) = std::sin(M_PI * sq.vertices(0, k)) * std::sin(M_PI * sq.vertices(1, k));
  }
  const BodyGeometry rod = rodGeometry(2.0);  // along body x, centred
  const BoundingTree ts = buildBoundingTree(sq), tr = buildBoundingTree(rod);
  const Eigen::Matrix3d A = expRotation(Vector3d(0.3, -1.1, 0.7));
  const Vector3d r(2.0, -1.0, 0.5);
  for (double w : {-0.2, 0.0, 0.05, 0.1, 0.25, 0.31, 0.5}) {
    PlacedGeometry ps(sq, ts, r, A, Eigen::VectorXd::Constant(1, w));
    PlacedGeometry pr(rod, tr, A * Vector3d(0.5, 0.5, 0.3) + r, A, Eigen::VectorXd());
    const double expected = w <= 0 ? 0.3 : std::max(0.0, 0.3 - w);
    // Rounding of the rotated coordinates (~1e-16 m each).
    EXPECT_NEAR(treeDistance(ps, pr), expected, 1e-14) << "w = " << w;
  }
}

TEST(ContactMonitor, RodsAndPlateCrossingAtConstantVelocity) {
  // Rod `r` (along y, body x turned by 90 deg about z) at z = 1 moving down at
  // 1 m/s over a fixed rod along x and a fixed 2 x 1.3 plate at z = 0.3.
  const Results res = simulate(sceneFromText(R"(
bodies:
  - {name: a, rod: {length: 1.0, diameter: 0.01, mass: 1.0}, fixed: true}
  - {name: p, plate: {length: 2.0, width: 1.3, thickness: 0.002, mass: 1.0}, fixed: true, position: [0, 0, 0.3]}
  - name: r
    rod: {length: 1.0, diameter: 0.01, mass: 1.0}
    position: [0, 0, 1.0]
    orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]
    velocity: [0, 0, -1.0]
outputs: {distances: [[r, a], [p, r]]}
simulation: {t_end: 1.5, output_step: 0.05, rtol: 1.0e-10}
)"),
                               {true});
  ASSERT_EQ(res.status, "completed");
  ASSERT_EQ(res.distances.size(), 2u);
  for (std::size_t n = 0; n < res.time.size(); ++n) {
    const double t = res.time[n];
    EXPECT_NEAR(res.distances[0][n], std::abs(1.0 - t), 1e-9) << t;
    EXPECT_NEAR(res.distances[1][n], std::abs(0.7 - t), 1e-9) << t;
  }
}

TEST(ContactMonitor, FlexibleMeshMovesWithTheModes) {
  BeamSpec spec;
  spec.modes = 3;
  const BeamModel beam = cantileverBeam(spec);
  const std::string file = writeBeam(beam, "distance");
  const Eigen::Vector3d q(0.05, -0.02, 0.01);
  // Tip deflection along y of each node for these modal coordinates.
  double vmax = -1e9;
  for (long k = 0; k < beam.body.nodeCount(); ++k) vmax = std::max(vmax, beam.body.shapes.row(6 * k + 1).head(3).dot(q));
  char scene[1200];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - name: beam
    flexible: {file: %s, modes: 3}
    modal_coordinates: [0.05, -0.02, 0.01]
  - {name: rail, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true,
     geometry: {segment: [[-0.5, 0.3, 0], [1.5, 0.3, 0]]}}
outputs: {distances: [[beam, rail]]}
simulation: {t_end: 0.01, output_step: 0.01}
)",
                file.c_str());
  const Results res = simulate(sceneFromText(scene), {true});
  ASSERT_EQ(res.status, "completed");
  std::printf("[   info   ] largest deflection toward the rail %.6f m, distance %.6f m\n", vmax, res.distances[0][0]);
  ASSERT_GT(vmax, 0.01);  // the check means something
  EXPECT_NEAR(res.distances[0][0], 0.3 - vmax, 1e-12);
  std::filesystem::remove(file);
}

TEST(ContactMonitor, RunEqualsBruteForceAtEverySample) {
  // A vibrating flexible beam (modal velocities), a rod sweeping past it and
  // a plate: every sampled distance is the brute force's on the sampled poses.
  BeamSpec spec;
  spec.modes = 3;
  const BeamModel beam = cantileverBeam(spec);
  const std::string file = writeBeam(beam, "distance_run");
  char scene[1400];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - name: beam
    flexible: {file: %s, modes: 3}
    modal_velocities: [0.4, -0.3, 0.2]
  - name: r
    rod: {length: 0.6, diameter: 0.01, mass: 1.0}
    position: [0.5, 0.2, -0.3]
    orientation: [0.7071067811865476, 0.7071067811865476, 0, 0]
    velocity: [0.1, -0.1, 0.3]
    angular_velocity: [0.5, 1.0, 0.0]
  - {name: p, plate: {length: 2.0, width: 1.3, thickness: 0.002, mass: 1.0}, fixed: true, position: [0.5, 0, 0.2]}
outputs: {distances: [[beam, r], [p, beam], [r, p]]}
simulation: {t_end: 2.0, output_step: 0.02}
)",
                file.c_str());
  const Model m = sceneFromText(scene);
  const Results res = simulate(m, {true});
  ASSERT_EQ(res.status, "completed");
  int crossing = 0;
  for (std::size_t k = 0; k < m.distance_pairs.size(); ++k)
    for (std::size_t n = 0; n < res.time.size(); ++n) {
      const auto pr = m.distance_pairs[k];
      auto placed = [&](int b) {
        const BodyGeometry& g = *m.bodies[b].geometry;
        const Eigen::VectorXd w = m.bodies[b].flex ? res.modal[b][n] : Eigen::VectorXd();
        return placedVertices(g, res.position[b][n], rotationMatrix(res.orientation[b][n]), w);
      };
      const double brute = geometryDistance(*m.bodies[pr[0]].geometry, placed(pr[0]), *m.bodies[pr[1]].geometry,
                                            placed(pr[1]));
      // The run's rotation matrix comes from the same normalised Euler
      // parameters; allow the rounding of that one product (1e-15 m).
      ASSERT_NEAR(res.distances[k][n], brute, 1e-15) << "pair " << k << " t = " << res.time[n];
      crossing += brute == 0.0;
    }
  EXPECT_GT(crossing, 0);  // the rod passes through the beam or the plate at some samples
  std::filesystem::remove(file);
}

TEST(ContactMonitor, BodyWithoutGeometryIsAnError) {
  try {
    sceneFromText(R"(
bodies:
  - {name: a, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}}
  - {name: b, rod: {length: 1.0, diameter: 0.01, mass: 1.0}}
outputs: {distances: [[a, b]]}
simulation: {t_end: 1.0}
)");
    FAIL() << "no error";
  } catch (const fc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has no geometry"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fc::mbs::test
