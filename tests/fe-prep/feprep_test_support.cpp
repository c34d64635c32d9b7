#include "feprep_test_support.h"

#include <slepcsys.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

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

std::string dataBodyYaml(const std::string& name, const std::vector<std::pair<std::string, std::string>>& set) {
  const std::string path = std::string(FLEXCOMP_DATA_DIR) + "/fe-prep/" + name;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("test data " + path + " not found");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (const auto& [key, value] : set) {
    const std::regex re("(\\b" + key + ": )[^,}\\n]+");
    std::smatch m;
    if (!std::regex_search(text, m, re)) throw std::runtime_error("test data " + path + " has no key " + key);
    text = m.prefix().str() + m[1].str() + value + m.suffix().str();
  }
  return text;
}

std::string feprepExecutable() { return std::string(FLEXCOMP_BINARY_DIR) + "/fe-prep/fe-prep"; }

std::string scratchDir(const std::string& test_name) {
  const auto dir = std::filesystem::temp_directory_path() / ("flexcomp-feprep-" + test_name + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace fc::feprep::test
