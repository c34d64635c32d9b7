// Honest inertia: /inertia/ holds the mass, centre and inertia of the
// body mbs-run simulates from the file, for every mass option. Reference nobody
// here wrote: a rigid pendulum whose properties are read from the file's
// /inertia/ must swing exactly as the (very stiff) flexible one, and the exact
// continuum values (rod: m L^2 / 12) must sit under /inertia/exact/ where the
// simulated ones differ.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "common/flexbody.h"
#include "common/input.h"
#include "feprep_test_support.h"
#include "mbs-run/scene/scene.h"
#include "mbs-run/run/simulation.h"

namespace fc::feprep::test {
namespace {

// A 1 m steel rod (d = 20 mm) with E x 100, so that its lowest free-free mode
// is ~900 Hz and its elastic deflection under its own swing is negligible.
std::string rodYaml(const std::string& mass_option) {
  return R"(
materials:
  stiff_steel: {type: isotropic, E: 210.0e11, nu: 0.3, rho: 7850}
body:
  name: rod
  beam: {length: 1.0, elements: 20, section: {shape: solid_circle, diameter: 0.02, material: stiff_steel}}
  interfaces: {pivot: [-0.5, 0.0, 0.0]}
  reference: free
  modes: 4
  mass: )" + mass_option + "\n";
}

// Released from horizontal about a revolute (z) at its end, gravity -y.
std::vector<double> swing(const std::string& body_block) {
  const std::string scene = R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: rod
)" + body_block + R"(
joints:
  - {name: pivot, type: revolute, bodies: [ground, rod], points: [[-0.5, 0, 0], [-0.5, 0, 0]], axes: [[0,0,1],[0,0,1]]}
forces:
  - {type: gravity, g: [0, -9.81, 0]}
simulation: {t_end: 2.0, output_step: 0.01, rtol: 1.0e-9}
)";
  const mbs::Results r = mbs::simulate(mbs::parseScene(InputNode::loadString(scene, "pendulum.yaml")), {true});
  EXPECT_EQ(r.status, "completed");
  return r.joint_angle.at(0);
}

std::string matrixYaml(const Eigen::Matrix3d& J) {
  char s[512];
  std::snprintf(s, sizeof s, "[[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g]]", J(0, 0), J(0, 1),
                J(0, 2), J(1, 0), J(1, 1), J(1, 2), J(2, 0), J(2, 1), J(2, 2));
  return s;
}

TEST(HonestInertia, RigidPendulumFromTheFilesInertiaSwingsAsTheFlexibleBody) {
  const double m_exact = 7850 * M_PI * 0.0001 * 1.0;
  for (const std::string option : {"lumped", "lumped_moments", "consistent"}) {
    const BuildResult built = runYaml(rodYaml(option), option + ".yaml");
    const std::string path = scratchDir("honest-" + option) + "/rod.h5";
    Provenance p;
    p.inputs_sha256 = std::string(64, '0');
    writeFlexBody(path, built.body, computeInertiaInvariants(built.body), p);
    const FlexBody b = readFlexBody(path).body;

    // /inertia/ is what the invariants imply, whatever the option.
    const InertiaInvariants inv = readFlexBody(path).invariants;
    EXPECT_NEAR(b.mass, inv.mass, 1e-12 * inv.mass) << option;
    EXPECT_LT((b.center_of_mass - inv.centerOfMass()).norm(), 1e-12) << option;
    EXPECT_LT((b.inertia_tensor - inv.inertiaAboutOrigin()).cwiseAbs().maxCoeff(), 1e-12 * b.inertia_tensor.maxCoeff())
        << option;
    // Row-sum lumping of 20 elements: Izz = m L^2/12 (1 + 1/(2 n^2))... the ends'
    // half masses give + m L^2 / (6 n^2) over the exact m L^2 / 12 (here +0.5 %),
    // and the exact value is written beside it; the default is exact.
    const double Izz_exact = m_exact * (1.0 / 12 + 0.0004 / 16);
    if (option == "lumped") {
      ASSERT_TRUE(b.has_exact_inertia);
      EXPECT_NEAR(b.exact_inertia_tensor(2, 2) / Izz_exact, 1.0, 1e-12);
      EXPECT_NEAR(b.inertia_tensor(2, 2) - Izz_exact, m_exact / (6.0 * 400.0), 1e-9 * Izz_exact);
    } else {
      EXPECT_FALSE(b.has_exact_inertia) << option;
      EXPECT_NEAR(b.inertia_tensor(2, 2) / Izz_exact, 1.0, 1e-10) << option;
    }

    const Eigen::Vector3d c = b.center_of_mass;
    const Eigen::Matrix3d Jc = b.inertia_tensor - b.mass * (c.dot(c) * Eigen::Matrix3d::Identity() - c * c.transpose());
    char rigid[1024];
    std::snprintf(rigid, sizeof rigid, "    rigid: {mass: %.17g, center_of_mass: [%.17g, %.17g, %.17g], inertia: %s}\n",
                  b.mass, c.x(), c.y(), c.z(), matrixYaml(Jc).c_str());
    const std::vector<double> a_rigid = swing(rigid);
    const std::vector<double> a_flex = swing("    flexible: {file: " + path + ", modes: 4, damping_ratio: 0.01}\n");
    ASSERT_EQ(a_rigid.size(), a_flex.size());
    double diff = 0;
    for (std::size_t k = 0; k < a_rigid.size(); ++k) diff = std::max(diff, std::abs(a_rigid[k] - a_flex[k]));
    std::printf("[   info   ] mass: %-15s Izz/exact - 1 = %+.2e, max |angle flexible - rigid from /inertia/| = %.2e rad\n",
                option.c_str(), b.inertia_tensor(2, 2) / Izz_exact - 1, diff);
    // Both runs at rtol 1e-9 over a swing of ~3 rad: the integrators agree to
    // ~1e-8; the elastic deflection of the E x 100 rod changes the angle by less
    // (1.2e-9 measured for all three options). 1e-6 leaves room for either.
    EXPECT_LT(diff, 1e-6) << option;
    if (option == "lumped") {
      // The discrimination: a rigid pendulum with the exact rod inertia (what
      // /inertia/ held before) is far off the lumped flexible one.
      const Eigen::Vector3d ce = b.exact_center_of_mass;
      const Eigen::Matrix3d Je =
          b.exact_inertia_tensor - b.exact_mass * (ce.dot(ce) * Eigen::Matrix3d::Identity() - ce * ce.transpose());
      std::snprintf(rigid, sizeof rigid, "    rigid: {mass: %.17g, center_of_mass: [%.17g, %.17g, %.17g], inertia: %s}\n",
                    b.exact_mass, ce.x(), ce.y(), ce.z(), matrixYaml(Je).c_str());
      const std::vector<double> a_exact = swing(rigid);
      double off = 0;
      for (std::size_t k = 0; k < a_exact.size(); ++k) off = std::max(off, std::abs(a_exact[k] - a_flex[k]));
      std::printf("[   info   ] mass: lumped vs a rigid pendulum with the exact rod inertia: %.2e rad\n", off);
      EXPECT_GT(off, 1e-3);
    }
  }
}

}  // namespace
}  // namespace fc::feprep::test
