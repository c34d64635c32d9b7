// Input options beyond the basic panel: gmsh .geo meshes with physical-group
// sets, mode selection by frequency, consistent mass.
#include <gtest/gtest.h>

#include <cmath>

#include "feprep_test_support.h"
#include "plate_references.h"

namespace fc::feprep::test {
namespace {

std::string squareYaml(const std::string& mesh, const std::string& reference, const std::string& modes,
                       const std::string& extra = "") {
  return std::string(R"(
materials:
  alu: {type: isotropic, E: 70.0e9, nu: 0.3, rho: 2700}
body:
  shell:
    )") + mesh + R"(
    material: alu
    thickness: 0.01
    element: dkt
  interfaces: {P: [0.1, 0.2, 0.0]}
  reference: )" + reference + "\n  " + modes + "\n" + extra;
}

double navierSquareHz(int m, int n) {
  const double D = 70e9 * 1e-6 / (12 * (1 - 0.09)), rhoA = 27.0;
  return M_PI * M_PI * (m * m + n * n) * std::sqrt(D / rhoA) / (2 * M_PI);
}

const std::string kGeo = std::string("mesh: {file: ") + FLEXCOMP_SOURCE_DIR + "/meshes/square_1m.geo}";
const std::string kSS = "{pin: [edge_xmin, edge_xmax, edge_ymin, edge_ymax]}";

TEST(Options, GeoFileSquareWithPhysicalEdgesMatchesNavier) {
  const BuildResult r = runYaml(squareYaml(kGeo, kSS, "modes: 3"));
  // The .geo mesh (lc = a/20, 502 triangles) is coarser than the built-in one;
  // measured 0.7 % on mode 1, 1.2 % on mode 3.
  EXPECT_NEAR(r.body.frequencies_hz(0) / navierSquareHz(1, 1), 1.0, 0.015);
  EXPECT_NEAR(r.body.frequencies_hz(1) / navierSquareHz(1, 2), 1.0, 0.02);
  EXPECT_NEAR(r.body.frequencies_hz(2) / navierSquareHz(1, 2), 1.0, 0.02);
  // The interface point was embedded into the gmsh surface: a node sits on it.
  const FlexInterface& p = r.body.interface("P");
  EXPECT_LT((r.body.nodes.row(p.node) - Eigen::RowVector3d(0.1, 0.2, 0.0)).norm(), 1e-12);
}

TEST(Options, GeoFileUnknownSetNamesTheReferenceLine) {
  try {
    runYaml(squareYaml(kGeo, "{pin: [edge_xmim]}", "modes: 3"), "geo.yaml");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 11);
    EXPECT_EQ(e.keyPath(), "body.reference.pin[0]");
    EXPECT_NE(std::string(e.what()).find("did you mean 'edge_xmin'"), std::string::npos) << e.what();
  }
}

TEST(Options, GradedFromAppliesToRectanglesOnlyAndMustBeALength) {
  try {
    runYaml(squareYaml("mesh: {file: " + std::string(FLEXCOMP_SOURCE_DIR) + "/meshes/square_1m.geo, graded_from: 0.1}",
                       kSS, "modes: 3"), "graded.yaml");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.keyPath(), "body.shell.mesh.graded_from");
    EXPECT_NE(std::string(e.what()).find("rectangle"), std::string::npos) << e.what();
  }
  try {
    runYaml(squareYaml("rectangle: {length: 1.0, width: 1.0}\n    mesh: {size: 0.1, graded_from: -0.1}", kSS,
                       "modes: 3"), "graded.yaml");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.keyPath(), "body.shell.mesh.graded_from");
  }
}

TEST(Options, MaxFrequencyReturnsExactlyTheModesBelowIt) {
  // Navier: 48.4, 121.0 (twice), 193.6 Hz ... so 150 Hz keeps three modes and
  // 300 Hz keeps (1,1), (1,2), (2,1), (2,2), (1,3), (3,1): six (240, 242 Hz),
  // provided the discrete ones stay on the same side (they do within 0.5 %).
  const std::string mesh = "rectangle: {length: 1.0, width: 1.0}\n    mesh: {size: 0.05}";
  EXPECT_EQ(runYaml(squareYaml(mesh, kSS, "max_frequency_hz: 150")).body.modeCount(), 3);
  const BuildResult r = runYaml(squareYaml(mesh, kSS, "max_frequency_hz: 300"));
  EXPECT_EQ(r.body.modeCount(), 6);
  EXPECT_LT(r.body.frequencies_hz(5), 300.0);
}

TEST(Options, ConsistentMassCantileverMatchesLeissa) {
  const std::string mesh = "rectangle: {length: 1.0, width: 1.0}\n    mesh: {size: 0.05}";
  const BuildResult r = runYaml(squareYaml(mesh, "{clamp: [edge_xmin]}", "modes: 3", "  mass: consistent\n"));
  const double D = 70e9 * 1e-6 / (12 * (1 - 0.09)), scale = std::sqrt(D / 27.0) / (2 * M_PI);
  // Measured 0.2-0.6 % below Leissa's Ritz upper bounds (lumped mass: 0.4-1.1 %).
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(r.body.frequencies_hz(i) / (kLeissaCantileverSquare[i] * scale), 1.0, 0.01) << "mode " << i + 1;
}

}  // namespace
}  // namespace fc::feprep::test
