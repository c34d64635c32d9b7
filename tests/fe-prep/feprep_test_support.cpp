#include "feprep_test_support.h"

#include <slepcsys.h>

#include <filesystem>

namespace fc::feprep::test {
namespace {

class SlepcEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { ASSERT_EQ(SlepcInitialize(nullptr, nullptr, nullptr, nullptr), 0); }
  void TearDown() override { SlepcFinalize(); }
};

[[maybe_unused]] ::testing::Environment* const kEnv = ::testing::AddGlobalTestEnvironment(new SlepcEnvironment);

}  // namespace

BuildResult runYaml(const std::string& yaml, const std::string& name) {
  const BodySpec spec = parseBodySpec(InputNode::loadString(yaml, name));
  BuildOptions opt;
  opt.quiet = true;
  return buildFlexBody(PETSC_COMM_WORLD, spec, opt);
}

std::string feprepExecutable() { return std::string(FLEXCOMP_BINARY_DIR) + "/fe-prep/fe-prep"; }

std::string scratchDir(const std::string& test_name) {
  const auto dir = std::filesystem::temp_directory_path() / ("flexcomp-feprep-" + test_name + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace fc::feprep::test
