// What the trusses' ply stress recovery costs a SAR-like run: nine truss
// bodies of the SAR's composite models (2 beam elements, 2 modes, the solid
// d = 20 mm IM6 rod's section basis of 757 section elements, strengths), each
// moving freely with its modes excited, 2 s at the SAR's output_step 0.01 s,
// streamed to a results file as the executable does. Three runs: trusses not
// named in outputs.stresses; named, with section files without a recovery
// basis (section forces only); named with the basis (ply stresses, Tsai-Wu,
// Hashin at 3 stations per element). And the kernel alone for one truss per
// output row. Figures in docs/benchmarks.md, "Truss ply stress recovery".
// (The bodies are synthetic, random mass-normalised modes, resultants and
// basis of the SAR's sizes: the cost depends on the sizes only.)
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>

#include "common/input.h"
#include "mbs-run/monitors/stress_recovery.h"
#include "mbs-run/output/results.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/scene/scene.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

constexpr int kTrusses = 9, kModes = 2, kElements = 2, kSectionElements = 757;

fc::StressRecoveryData trussData(bool basis) {
  fc::StressRecoveryData d;
  d.centroids = Eigen::MatrixXd::Random(kElements, 3);
  d.beam_resultants = 1e2 * Eigen::MatrixXd::Random(6 * kElements, kModes);
  if (!basis) return d;
  fc::SectionStressBasis& s = d.section;
  s.ply_stress = 1e6 * Eigen::MatrixXd::Random(3 * kSectionElements, 6);
  s.centroids = 0.01 * Eigen::MatrixXd::Random(kSectionElements, 2);
  s.material.assign(kSectionElements, "im6_sc1081");
  s.has_plies.assign(kSectionElements, 1);
  s.strength.resize(kSectionElements, 5);
  for (int k = 0; k < kSectionElements; ++k) s.strength.row(k) << 3.5e9, 1.54e9, 56e6, 150e6, 98e6;
  d.beam_lengths = Eigen::VectorXd::Constant(kElements, 0.15);
  d.beam_stations = Eigen::MatrixXd::Random(3 * kElements, 3);
  return d;
}

std::string trussFile(bool basis) {
  static std::string path[2];
  std::string& p = path[basis ? 1 : 0];
  if (!p.empty()) return p;
  fc::FlexBody b = fc::testing::randomBody(kElements + 1, kModes, 5, 0.15, 20.0, 60.0);
  b.elements.clear();
  b.elements["beams"].resize(kElements, 2);
  for (int e = 0; e < kElements; ++e) b.elements["beams"].row(e) << e, e + 1;
  b.stress = trussData(basis);
  p = (std::filesystem::temp_directory_path() /
       ("bench_truss_" + std::to_string(::getpid()) + (basis ? "_basis" : "_forces") + ".h5")).string();
  fc::Provenance prov;
  prov.inputs_sha256 = "bench";
  fc::writeFlexBody(p, b, fc::computeInertiaInvariants(b), prov);
  return p;
}

// stresses: 0 not named, 1 named without basis, 2 named with basis.
void Run(benchmark::State& state, int stresses) {
  std::string yaml = "bodies:\n", names;
  for (int k = 0; k < kTrusses; ++k) {
    const std::string n = "B" + std::to_string(k + 4);
    yaml += "  - {name: " + n + ", flexible: {file: " + trussFile(stresses == 2) +
            ", damping_ratio: 0.01}, position: [" + std::to_string(k) + ", 0, 0], modal_velocities: [0.05, -0.03]}\n";
    names += (k ? ", " : "") + n;
  }
  yaml += "simulation: {t_end: 2.0, output_step: 0.01, rtol: 1.0e-6}\n";
  if (stresses) yaml += "outputs: {stresses: [" + names + "]}\n";
  const fc::mbs::Model m = fc::mbs::parseScene(fc::InputNode::loadString(yaml, "bench.yaml"));
  const std::string out = trussFile(true) + ".run" + std::to_string(stresses) + ".h5";
  double cpu = 0;
  long rows = 0;
  for (auto _ : state) {
    const std::clock_t c0 = std::clock();
    fc::mbs::ResultsFileWriter w(out, m, 201);
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
void TrussesNotNamed(benchmark::State& s) { Run(s, 0); }
void TrussesSectionForcesOnly(benchmark::State& s) { Run(s, 1); }
void TrussesPlyStresses(benchmark::State& s) { Run(s, 2); }
BENCHMARK(TrussesNotNamed)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(TrussesSectionForcesOnly)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(TrussesPlyStresses)->Unit(benchmark::kMillisecond)->Iterations(3);

// The kernel alone: one output row of one truss (section forces, ply stresses
// at 6 stations x 757 section elements, Tsai-Wu and Hashin).
void RecoverOneTrussRow(benchmark::State& state) {
  const auto r = fc::mbs::beamStressRecovery(trussData(true));
  const Eigen::VectorXd q = Eigen::VectorXd::Random(kModes);
  std::vector<Eigen::VectorXd> f;
  for (auto _ : state) {
    r->recover(q, f);
    benchmark::DoNotOptimize(f[2].data());
  }
}
BENCHMARK(RecoverOneTrussRow)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
