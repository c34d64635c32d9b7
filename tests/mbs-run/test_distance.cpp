// Contact monitor (issue 13): the distance kernels against hand-computed
// configurations (skew, parallel and disjoint segments, every Voronoi region
// of a triangle, a segment through a triangle), and the monitor in runs: a
// rod crossing another rod and a plate at constant velocity (distance
// |z0 - v t| exactly), and a flexible beam whose mesh nodes are moved by its
// modal coordinates (distance to a parallel rod = gap - largest deflection).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "beam_body.h"
#include "helpers.h"
#include "mbs-run/distance.h"
#include "mbs-run/simulation.h"

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
