// The flexible body file: exact rigid properties, M-orthonormal modes,
// interfaces that move rigidly with their nodes, offset reference conditions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/flexbody.h"
#include "feprep_test_support.h"

namespace fc::feprep::test {
namespace {

const char* kPanel = R"(
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  name: panel
  shell:
    rectangle: {length: 2.0, width: 1.3}
    material: cfrp_iso
    thickness: 0.002
    element: dst
    mesh: {triangles: 300}
  interfaces:
    S1: [-1.0, 0.65, 0.0705]
    S2: [-0.05, 0.65, -0.025]
    inner: [0.3, 0.2, 0.04]
  reference: free
  modes: 8
)";

FlexBodyFile roundTrip(const BuildResult& r, const std::string& name) {
  const std::string path = scratchDir(name) + "/body.h5";
  Provenance p;
  p.inputs_sha256 = std::string(64, '0');
  writeFlexBody(path, r.body, computeInertiaInvariants(r.body), p);
  return readFlexBody(path, -1, FlexBodyParts::All);
}

// Phi^T M Phi with M the lumped (diagonal) mass the modes were computed with.
Eigen::MatrixXd modalMass(const FlexBody& b) {
  Eigen::VectorXd m(6 * b.nodeCount());
  for (long k = 0; k < b.nodeCount(); ++k) {
    m.segment<3>(6 * k).setConstant(b.nodal_mass(k, 0));
    m.segment<3>(6 * k + 3) = b.nodal_mass.block<1, 3>(k, 1).transpose();
  }
  return b.shapes.transpose() * m.asDiagonal() * b.shapes;
}

TEST(BodyFile, PanelRigidPropertiesAreTheExactPlateValues) {
  const BuildResult r = runYaml(kPanel);
  const FlexBody b = roundTrip(r, "panel-rigid").body;
  const double rho = 1610, L = 2.0, W = 1.3, h = 0.002, m = rho * L * W * h;
  // Exact integration over flat triangles: only round-off remains.
  EXPECT_NEAR(b.mass / m, 1.0, 1e-12);
  EXPECT_NEAR(b.nodal_mass.col(0).sum() / m, 1.0, 1e-12);  // the lumped masses add up to it too
  EXPECT_LT(b.center_of_mass.norm(), 1e-12 * L);
  const Eigen::Vector3d Jexact(m * (W * W + h * h) / 12, m * (L * L + h * h) / 12, m * (L * L + W * W) / 12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(b.inertia_tensor(i, j), i == j ? Jexact(i) : 0.0, 1e-10 * Jexact.maxCoeff()) << i << "," << j;
  EXPECT_NEAR(r.body.frequencies_hz(0), b.frequencies_hz(0), 1e-12 * b.frequencies_hz(0));
}

TEST(BodyFile, ModesAreMassOrthonormal) {
  const FlexBody b = roundTrip(runYaml(kPanel), "panel-orth").body;
  const Eigen::MatrixXd G = modalMass(b);
  // SLEPc's converged vectors are M-orthogonal to its tolerance (1e-10 relative residual; the Gram matrix errors are of that order times the condition of the tightly spaced pairs, far below 1e-9).
  EXPECT_LT((G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(b.modeCount(), 8);
}

TEST(BodyFile, InterfacesSitOnTheirProjectionsAndMoveRigidlyWithTheNode) {
  const FlexBody b = roundTrip(runYaml(kPanel), "panel-if").body;
  ASSERT_EQ(b.interfaces.size(), 3u);
  for (const auto& it : b.interfaces) {
    // The projection on the mid-surface is a mesh node (forced into gmsh's mesh).
    const Eigen::Vector3d X = b.nodes.row(it.node).transpose();
    EXPECT_LT((X - Eigen::Vector3d(it.position.x(), it.position.y(), 0.0)).norm(), 1e-9) << it.name;
    const Eigen::Vector3d d = it.position - X;
    for (int j = 0; j < b.modeCount(); ++j) {
      const Eigen::Vector3d u = b.shapes.block<3, 1>(6 * it.node, j), th = b.shapes.block<3, 1>(6 * it.node + 3, j);
      const Eigen::Vector3d up = it.shapes.block<1, 3>(j, 0).transpose(), tp = it.shapes.block<1, 3>(j, 3).transpose();
      EXPECT_LT((up - (u + th.cross(d))).norm(), 1e-12 * (1 + u.norm())) << it.name << " mode " << j;
      EXPECT_LT((tp - th).norm(), 1e-12 * (1 + th.norm()));
    }
  }
}

TEST(BodyFile, ABracketCarriesAPointBeyondTheEdgeRigidlyOnItsPanelNode) {
  // A hinge pin 20 mm beyond the edge x = 1 and 0.0705 m off the mid-plane, carried by the node at the
  // edge point (1, 0.65): u_P = u_n + theta_n x d, theta_P = theta_n with d = P - X_n (the same rigid
  // offset as a point over the panel), and the node is exactly the bracket's panel point.
  std::string yaml = kPanel;
  yaml.replace(yaml.find("    inner:"), 0, "    pin: {point: [1.02, 0.65, -0.0705], bracket: [1.0, 0.65]}\n");
  const FlexBody b = roundTrip(runYaml(yaml), "panel-bracket").body;
  const FlexInterface& it = b.interface("pin");
  const Eigen::Vector3d X = b.nodes.row(it.node).transpose();
  EXPECT_LT((X - Eigen::Vector3d(1.0, 0.65, 0.0)).norm(), 1e-12);
  EXPECT_LT((it.position - Eigen::Vector3d(1.02, 0.65, -0.0705)).norm(), 1e-15);
  const Eigen::Vector3d d = it.position - X;
  double rotation = 0;
  for (int j = 0; j < b.modeCount(); ++j) {
    const Eigen::Vector3d u = b.shapes.block<3, 1>(6 * it.node, j), th = b.shapes.block<3, 1>(6 * it.node + 3, j);
    EXPECT_LT((it.shapes.block<1, 3>(j, 0).transpose() - (u + th.cross(d))).norm(), 1e-12 * (1 + u.norm())) << j;
    EXPECT_LT((it.shapes.block<1, 3>(j, 3).transpose() - th).norm(), 1e-12 * (1 + th.norm())) << j;
    rotation = std::max(rotation, th.norm());
  }
  EXPECT_GT(rotation, 1e-3);  // the offset matters: the corner node turns in these modes
}

TEST(BodyFile, APointOffThePanelWithoutABracketIsAnErrorNamingTheFix) {
  std::string yaml = kPanel;
  yaml.replace(yaml.find("    inner:"), 0, "    pin: [1.02, 0.65, -0.0705]\n");
  try {
    runYaml(yaml);
    ADD_FAILURE() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("needs a bracket"), std::string::npos) << e.what();
  }
  std::string outside = kPanel;
  outside.replace(outside.find("    inner:"), 0, "    pin: {point: [1.02, 0.65, 0.0], bracket: [1.01, 0.65]}\n");
  EXPECT_THROW(runYaml(outside), std::exception);
}

TEST(BodyFile, PinAtAnOffsetPointHoldsThePointNotTheNode) {
  // A pin 4 cm above the mid-surface: the point stays put in every mode while
  // its node moves (by -theta x d); with a clamped edge nothing rigid remains.
  std::string yaml = kPanel;
  yaml.replace(yaml.find("reference: free"), 15, "reference: {clamp: [edge_xmin], pin: [inner]}");
  const BuildResult r = runYaml(yaml);
  EXPECT_EQ(r.rigid_removed, 0);
  const FlexBody& b = r.body;
  const FlexInterface& it = b.interface("inner");
  double node_motion = 0;
  for (int j = 0; j < b.modeCount(); ++j) {
    EXPECT_LT((it.shapes.block<1, 3>(j, 0).norm()), 1e-12) << "mode " << j;
    node_motion = std::max(node_motion, b.shapes.block<3, 1>(6 * it.node, j).norm());
  }
  EXPECT_GT(node_motion, 1e-4);  // the node itself does move
}

TEST(BodyFile, ClampAtAnOffsetPointFixesItsRotationToo) {
  std::string yaml = kPanel;
  yaml.replace(yaml.find("reference: free"), 15, "reference: {clamp: [S2]}");
  const BuildResult r = runYaml(yaml);
  EXPECT_EQ(r.rigid_removed, 0);
  const FlexInterface& it = r.body.interface("S2");
  EXPECT_LT(it.shapes.cwiseAbs().maxCoeff(), 1e-12);
}

TEST(BodyFile, BeamRigidPropertiesAreExact) {
  const char* yaml = R"(
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  name: truss
  beam: {length: 1.24, elements: 2, section: {shape: solid_circle, diameter: 0.006, material: cfrp_iso}}
  interfaces: {S5: [-0.62, 0.0, 0.0], S2: [0.62, 0.0, 0.0], mid: [0.1, 0.0, 0.0]}
  reference: free
  modes: 2
)";
  const BuildResult r = runYaml(yaml);
  const FlexBody& b = r.body;
  const double L = 1.24, d = 0.006, m = 1610 * M_PI * d * d / 4 * L;
  EXPECT_EQ(b.nodeCount(), 4);  // the interface at x = 0.1 splits an element
  EXPECT_NEAR(b.mass / m, 1.0, 1e-12);
  EXPECT_LT(b.center_of_mass.norm(), 1e-12);
  // Solid rod about its centre: Ixx = m d^2 / 8, Iyy = Izz = m L^2 / 12 + m d^2 / 16.
  // Ixx = tr(E) - Exx cancels Exx ~ (L/d)^2 = 4e4 times larger: 1e-10 covers the round-off.
  EXPECT_NEAR(b.inertia_tensor(0, 0) / (m * d * d / 8), 1.0, 1e-10);
  EXPECT_NEAR(b.inertia_tensor(1, 1) / (m * L * L / 12 + m * d * d / 16), 1.0, 1e-12);
  EXPECT_NEAR(b.inertia_tensor(2, 2) / (m * L * L / 12 + m * d * d / 16), 1.0, 1e-12);
  EXPECT_EQ(r.rigid_removed, 6);
  // The two lowest elastic modes of a round rod are one degenerate bending pair.
  EXPECT_NEAR(b.frequencies_hz(1) / b.frequencies_hz(0), 1.0, 1e-8);
}

}  // namespace
}  // namespace fc::feprep::test

namespace fc::feprep::test {
namespace {

TEST(BodyFile, MomentLumpingMakesTheNodalInertiaExact) {
  // Row-sum lumping on this 300-triangle panel is ~2 % off in Ixx (8 % at the
  // paper's 86 triangles); lumped_moments must reproduce the exact tensor from
  // the nodal masses alone, keep every mass positive, and the modes stay
  // M-orthonormal with the masses written to the file.
  std::string yaml = kPanel;
  yaml.replace(yaml.find("modes: 8"), 8, "modes: 8\n  mass: lumped_moments");
  const BuildResult r = runYaml(yaml);
  ASSERT_TRUE(r.moment_lumping);
  EXPECT_GT(r.lumping_min_ratio, 0.1);
  const FlexBody b = roundTrip(r, "panel-moments").body;
  const InertiaInvariants inv = computeInertiaInvariants(b);
  const Eigen::Matrix3d lumped = inv.inertiaAboutOrigin();
  EXPECT_LT((lumped - b.inertia_tensor).cwiseAbs().maxCoeff(), 1e-10 * b.inertia_tensor.maxCoeff());
  EXPECT_NEAR(inv.mass, b.mass, 1e-12 * b.mass);
  EXPECT_LT((inv.centerOfMass() - b.center_of_mass).norm(), 1e-12);
  const Eigen::MatrixXd G = modalMass(b);
  EXPECT_LT((G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff(), 1e-9);

  EXPECT_FALSE(b.has_exact_inertia);  // nothing differs, so nothing is written beside it

  // Row-sum lumping, for contrast: the nodal second moments overestimate Ixx;
  // /inertia/ says so (it is the simulated body) and /inertia/exact/ holds the plate's.
  std::string lumped_yaml = kPanel;
  lumped_yaml.replace(lumped_yaml.find("modes: 8"), 8, "modes: 8\n  mass: lumped");
  const FlexBody plain = roundTrip(runYaml(lumped_yaml), "panel-rowsum").body;
  ASSERT_TRUE(plain.has_exact_inertia);
  EXPECT_GT(plain.inertia_tensor(0, 0), 1.01 * plain.exact_inertia_tensor(0, 0));
  EXPECT_LT((computeInertiaInvariants(plain).inertiaAboutOrigin() - plain.inertia_tensor).cwiseAbs().maxCoeff(),
            1e-12 * plain.inertia_tensor.maxCoeff());
  EXPECT_LT((b.inertia_tensor - plain.exact_inertia_tensor).cwiseAbs().maxCoeff(), 1e-10 * b.inertia_tensor.maxCoeff());
}

TEST(BodyFile, MomentLumpingOfTwoBeamElementsIsSimpsonsRule) {
  const char* yaml = R"(
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  beam: {length: 1.24, elements: 2, section: {shape: solid_circle, diameter: 0.006, material: cfrp_iso}}
  reference: free
  modes: 2
  mass: lumped_moments
)";
  const BuildResult r = runYaml(yaml);
  const double m = 1610 * M_PI * 0.006 * 0.006 / 4 * 1.24;
  ASSERT_EQ(r.body.nodeCount(), 3);
  EXPECT_NEAR(r.body.nodal_mass(0, 0), m / 6, 1e-12 * m);
  EXPECT_NEAR(r.body.nodal_mass(1, 0), 2 * m / 3, 1e-12 * m);
  EXPECT_NEAR(r.body.nodal_mass(2, 0), m / 6, 1e-12 * m);
}

}  // namespace
}  // namespace fc::feprep::test
