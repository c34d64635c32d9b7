// what geometric stiffening costs per right-hand-side evaluation.
// A flexible body spun by a driven hub (revolute at its interface P0, constant
// rate), System::derivative at one state, with `geometric_stiffening` off and
// on, for 4, 14 and 56 modes. On: the six velocity cases from the state, then a
// second constrained solve for the acceleration and interface (joint
// reaction) cases. Figures in docs/benchmarks.md.
// (The body is synthetic: random mass-normalised modes and random symmetric
// geometric-stiffness matrices of the file's shapes; the cost depends on the
// sizes only.)
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

#include "common/input.h"
#include "mbs-run/scene/scene.h"
#include "mbs-run/constrained/system.h"
#include "rhs_benchmark.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

Eigen::MatrixXd randomSymmetric(int n, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < a.size(); ++i) a.data()[i] = u(gen);
  return 0.5 * (a + a.transpose());
}

struct BodyFile {
  std::string path;
  Eigen::Vector3d p0, p100;  // the interfaces' points, body frame
};

BodyFile bodyFile(int modes) {
  fc::FlexBody b = fc::testing::randomBody(200, modes, 7, 1.0, 5.0, 60.0);
  std::mt19937 gen(11);
  for (int c = 0; c < fc::kGeometricStiffnessCaseCount; ++c) b.geometric_stiffness.push_back(randomSymmetric(modes, gen));
  for (std::size_t k = 1; k < b.interfaces.size(); ++k)  // P0 is the hub's (held); the others carry load cases
    for (int c = 0; c < 6; ++c) b.interfaces[k].geometric_stiffness.push_back(randomSymmetric(modes, gen));
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("bench_stiffening_" + std::to_string(modes) + "_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  fc::Provenance prov;
  prov.inputs_sha256 = "bench";
  fc::writeFlexBody(path, b, fc::computeInertiaInvariants(b), prov);
  return {path, b.interfaces[0].position, b.interfaces[1].position};
}

std::string vec(const Eigen::Vector3d& v) {
  return "[" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " + std::to_string(v.z()) + "]";
}

// range(0): modes; range(1): 0 off, 1 on.
void StiffeningRightHandSide(benchmark::State& state) {
  const int modes = static_cast<int>(state.range(0));
  const bool on = state.range(1) != 0;
  const BodyFile f = bodyFile(modes);
  // The arm placed with P0 on the hub axis; the tip mass on P100; the modes excited.
  const Eigen::Vector3d r = -f.p0;
  std::string q = "[";
  for (int j = 0; j < modes; ++j) q += (j ? ", " : "") + std::string("1.0e-3");
  q += "]";
  const std::string scene =
      "bodies:\n"
      "  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n"
      "  - {name: arm, flexible: {file: " + f.path + ", modes: " + std::to_string(modes) +
      (on ? ", geometric_stiffening: true" : "") + "}, position: " + vec(r) +
      ", angular_velocity: [0, 0, 10.0], modal_coordinates: " + q + "}\n"
      "  - {name: tip, rigid: {mass: 0.5, inertia: [[1e-3,0,0],[0,1e-3,0],[0,0,1e-3]]}, position: " + vec(r + f.p100) +
      "}\n"
      "joints:\n"
      "  - {name: hub, type: revolute, bodies: [ground, arm], points: [[0, 0, 0], P0], axes: [[0, 0, 1], [0, 0, 1]],\n"
      "     drive: {angle0: 0.0, speed: 10.0}}\n"
      "  - {name: pin, type: spherical, bodies: [arm, tip], points: [P100, [0, 0, 0]]}\n"
      "simulation: {t_end: 1.0}\n";
  const fc::mbs::Model m = fc::mbs::parseScene(fc::InputNode::loadString(scene, "stiffening.yaml"));
  fc::mbs::bench::timeRightHandSide(state, m);
  std::filesystem::remove(f.path);
}
BENCHMARK(StiffeningRightHandSide)->ArgsProduct({{4, 14, 56}, {0, 1}})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
