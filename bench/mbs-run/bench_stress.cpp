// what stress recovery costs. One composite panel of the SAR's size
// (14 modes, 1 000 triangles, 4 plies) moving freely with its modes excited,
// 2 s at output_step 1 ms (2 001 rows), streamed to a results file as the
// executable does: the run without `outputs.stresses`, with it, and the
// recovery kernel alone per output row. Figures in docs/benchmarks.md.
// (The body is synthetic, random mass-normalised modes and strain modes of
// realistic size: the cost depends on the sizes only.)
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "common/input.h"
#include "mbs-run/output/results.h"
#include "mbs-run/scene/scene.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/monitors/stress_recovery.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

constexpr int kModes = 14, kElements = 1000, kPlies = 4;

fc::StressRecoveryData panelData() {
  fc::StressRecoveryData d;
  d.centroids = Eigen::MatrixXd::Random(kElements, 3);
  d.shell_strains = 1e-3 * Eigen::MatrixXd::Random(6 * kElements, kModes);
  const Eigen::Matrix3d Q = (Eigen::Matrix3d() << 178e9, 2.9e9, 0, 2.9e9, 10.9e9, 0, 0, 0, 7.6e9).finished();
  for (int k = 0; k < kPlies; ++k) {
    d.plies.stiffness.push_back(Q);
  }
  d.plies.z_mid = Eigen::Vector4d(-0.75e-3, -0.25e-3, 0.25e-3, 0.75e-3);
  d.plies.angle_deg = Eigen::Vector4d(0, 90, 90, 0);
  d.plies.strength = Eigen::MatrixXd(kPlies, 5);
  for (int k = 0; k < kPlies; ++k) d.plies.strength.row(k) << 2.0e9, 1.2e9, 50e6, 200e6, 80e6;
  return d;
}

std::string panelFile() {
  static std::string path;
  if (!path.empty()) return path;
  fc::FlexBody b = fc::testing::randomBody(kElements / 2 + 2, kModes, 3, 1.0, 5.0, 60.0);
  b.elements["triangles"].resize(kElements, 3);
  for (int e = 0; e < kElements; ++e) b.elements["triangles"].row(e) << e / 2, e / 2 + 1, e / 2 + 2;
  b.stress = panelData();
  path = (std::filesystem::temp_directory_path() / ("bench_stress_" + std::to_string(::getpid()) + ".h5")).string();
  fc::Provenance prov;
  prov.inputs_sha256 = "bench";
  fc::writeFlexBody(path, b, fc::computeInertiaInvariants(b), prov);
  return path;
}

void Run(benchmark::State& state, bool stresses) {
  std::string yaml = "bodies:\n  - {name: panel, flexible: {file: " + panelFile() +
                     ", damping_ratio: 0.01}, modal_velocities: [0.05, -0.03, 0.02, 0.01, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]}\n"
                     "simulation: {t_end: 2.0, output_step: 0.001, rtol: 1.0e-6}\n";
  if (stresses) yaml += "outputs: {stresses: [panel]}\n";
  const fc::mbs::Model m = fc::mbs::parseScene(fc::InputNode::loadString(yaml, "bench.yaml"));
  const std::string out = panelFile() + (stresses ? ".with.h5" : ".without.h5");
  double cpu = 0;
  long rows = 0;
  for (auto _ : state) {
    const std::clock_t c0 = std::clock();
    fc::mbs::ResultsFileWriter w(out, m, 2001);
    const fc::mbs::RunSummary r = fc::mbs::simulate(m, {true}, w);
    w.finish(m, r, "bench");
    cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    rows = r.samples;
  }
  state.counters["cpu_s"] = cpu;
  state.counters["rows"] = double(rows);
  state.counters["file_MB"] = double(std::filesystem::file_size(out)) / 1e6;
  std::remove(out.c_str());
}
void RunWithoutStresses(benchmark::State& s) { Run(s, false); }
void RunWithStresses(benchmark::State& s) { Run(s, true); }
BENCHMARK(RunWithoutStresses)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(RunWithStresses)->Unit(benchmark::kMillisecond)->Iterations(3);

// The kernel alone: one output row of one panel (strains, ply stresses, Tsai-Wu).
void RecoverOneRow(benchmark::State& state) {
  const auto r = fc::mbs::shellStressRecovery(panelData());
  const Eigen::VectorXd q = Eigen::VectorXd::Random(kModes);
  std::vector<Eigen::VectorXd> f;
  for (auto _ : state) {
    r->recover(q, f);
    benchmark::DoNotOptimize(f[1].data());
  }
}
BENCHMARK(RecoverOneRow)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
