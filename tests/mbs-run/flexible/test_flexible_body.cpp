// Loading a scene's `flexible:` block: the right modes, damping and interfaces, and
// errors that point at the scene's key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

namespace fs = std::filesystem;

class FlexibleScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("flexcomp_flexible_body_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    body = fc::testing::randomBody(7, 5, 8);
    fc::writeFlexBody((dir / "panel.h5").string(), body, fc::computeInertiaInvariants(body), fc::Provenance{});
  }
  void TearDown() override { fs::remove_all(dir); }

  // The block as it appears in a scene file beside the body file.
  fc::InputNode block(const std::string& yaml) {
    const fs::path scene = dir / "scene.yaml";
    std::ofstream(scene) << "bodies:\n  - name: panel\n    flexible: " << yaml << "\n";
    return fc::InputNode::loadFile(scene.string())["bodies"].at(0)["flexible"];
  }
  std::string errorOf(const std::string& yaml) {
    try {
      fc::mbs::loadFlexibleBody(block(yaml));
    } catch (const fc::InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir;
  fc::FlexBody body;
};

TEST_F(FlexibleScene, LoadsTheFirstModesRelativeToTheScene) {
  const auto b = fc::mbs::loadFlexibleBody(block("{file: panel.h5, modes: 3, damping_ratio: 0.02}"));
  EXPECT_EQ(b.modes, 3);
  EXPECT_EQ(b.inertia.n_modes, 3);
  EXPECT_EQ(b.modal.stiffness, body.eigenvalues.head(3));
  EXPECT_NEAR(b.modal.damping(2), 2 * 0.02 * std::sqrt(body.eigenvalues(2)), 1e-12);
  const fc::mbs::Marker m = b.marker("P3");
  EXPECT_EQ(m.Psi, body.interfaces[1].shapes.topLeftCorner(3, 3).transpose());
  EXPECT_THROW(b.marker("S9"), std::out_of_range);
  // Defaults: all modes, no damping; modes: 0 is the rigid body.
  EXPECT_EQ(fc::mbs::loadFlexibleBody(block("{file: panel.h5}")).modes, 5);
  EXPECT_EQ(fc::mbs::loadFlexibleBody(block("{file: panel.h5, modes: 0}")).inertia.n_modes, 0);
}

TEST_F(FlexibleScene, ErrorsNameTheSceneKey) {
  std::string e = errorOf("{file: panel.h5, modes: 9}");
  EXPECT_NE(e.find("scene.yaml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("bodies[0].flexible.modes"), std::string::npos) << e;
  EXPECT_NE(e.find("holds 5 modes, 9 asked"), std::string::npos) << e;
  e = errorOf("{file: missing.h5, modes: 2}");
  EXPECT_NE(e.find("bodies[0].flexible.file"), std::string::npos) << e;
  EXPECT_NE(e.find("missing.h5"), std::string::npos) << e;
  e = errorOf("{file: panel.h5, mode: 2}");
  EXPECT_NE(e.find("mode"), std::string::npos) << e;
  EXPECT_NE(errorOf("{file: panel.h5, damping_ratio: -0.1}").find("damping_ratio"), std::string::npos);
  EXPECT_NE(errorOf("{file: panel.h5, modes: -1}").find("modes"), std::string::npos);
}

}  // namespace
