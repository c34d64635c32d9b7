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

std::string steelCantileverYaml(const std::string& modes) {
  return R"(
materials:
  steel: {type: isotropic, E: 210.0e9, nu: 0.3, rho: 7850}
body:
  name: cantilever
  beam: {length: 2.0, elements: 40, section: {shape: solid_circle, diameter: 0.02, material: steel}}
  interfaces: {root: [-1.0, 0, 0], tip: [1.0, 0, 0]}
  reference: {clamp: [root]}
  modes: )" + modes + "\n";
}

std::string raisedPinsPanelYaml(const std::string& t_coupling, const std::string& modes) {
  return R"(
materials:
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
body:
  name: panel
  shell: {rectangle: {length: 1.0, width: 0.65}, material: cfrp_iso, thickness: 0.002, mesh: {size: 0.01}}
  interfaces:
    H1: {point: [-0.5, -0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}
    H2: {point: [-0.5, 0.2, 0.07], coupling: distributing, nodes: {within: 0.1}}
    T: {point: [0.5, 0.0, 0.07], coupling: )" + t_coupling + R"(, nodes: {within: 0.1}}
  reference: {clamp: [H1, H2]}
  modes: )" + modes + "\n";
}

std::map<std::string, std::vector<double>> raisedPinsPanelCalculix() {
  const std::string path = std::string(FLEXCOMP_DATA_DIR) + "/calculix/raised_pins_panel/ccx_results.txt";
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::map<std::string, std::vector<double>> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string key, nx;
    s >> key >> nx;
    std::vector<double> v;
    for (double x; s >> x;) v.push_back(x);
    EXPECT_EQ(v.size(), 6u) << line;
    out[key + " " + nx] = v;
  }
  return out;
}

std::string feprepExecutable() { return std::string(FLEXCOMP_BINARY_DIR) + "/fe-prep/fe-prep"; }

std::string scratchDir(const std::string& test_name) {
  const auto dir = std::filesystem::temp_directory_path() / ("flexcomp-feprep-" + test_name + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace fc::feprep::test
