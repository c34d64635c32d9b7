// fe-prep stage timings: a free-free SAR-size panel (2.0 x 1.3 m, 2 mm,
// isotropic, DST, lumped mass, 20 elastic modes) from ~1e3 to ~5e5 DOF.
// Counters per size: DOF, meshing / assembly / eigensolve wall seconds and the
// peak resident memory after each stage. One iteration per size: a run is
// seconds to minutes, and the stages are deterministic.
//   bench_feprep [--benchmark_filter=...]      (serial)
// Parallel scaling: bench/fe-prep/scaling.sh runs the executable under mpirun.
// BM_CraigBamptonPanel: the same panel reduced by Craig-Bampton, with MUMPS's
// factor figures (the memory table: bench/fe-prep/cb_memory.sh).
#include <benchmark/benchmark.h>
#include <slepcsys.h>

#include <cmath>
#include <sstream>

#include "fe-prep/body_spec.h"
#include "fe-prep/build_body.h"
#include "fe-prep/panel_mesher.h"

namespace {

std::string panelYaml(double size) {
  std::ostringstream os;
  os << "materials:\n  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}\n"
     << "body:\n  name: bench\n  shell:\n    rectangle: {length: 2.0, width: 1.3}\n"
     << "    material: cfrp_iso\n    thickness: 0.002\n    element: dst\n    mesh: {size: " << size << "}\n"
     << "  reference: free\n  modes: 20\n";
  return os.str();
}

void BM_FreeFreePanel(benchmark::State& state) {
  // A triangle mesh has about half as many nodes as triangles: DOF ~ 3 triangles.
  const double target_dof = static_cast<double>(state.range(0));
  const double size = fc::feprep::sizeForTriangleCount(2.0 * 1.3, static_cast<long>(target_dof / 3));
  const fc::feprep::BodySpec spec = fc::feprep::parseBodySpec(fc::InputNode::loadString(panelYaml(size), "bench"));
  fc::feprep::BuildOptions opt;
  opt.quiet = true;
  fc::feprep::BuildResult r;
  for (auto _ : state) r = fc::feprep::buildFlexBody(PETSC_COMM_WORLD, spec, opt);
  state.counters["dof"] = static_cast<double>(r.dofs);
  for (const auto& s : r.stages) {
    state.counters[s.stage + "_s"] = s.seconds;
    state.counters[s.stage + "_cpu_s"] = s.cpu_seconds;
    state.counters[s.stage + "_MB"] = s.peak_rss_mb;
  }
  state.counters["f1_hz"] = r.body.frequencies_hz(0);
  state.counters["f20_hz"] = r.body.frequencies_hz(19);
}
BENCHMARK(BM_FreeFreePanel)
    ->Arg(1000)->Arg(4000)->Arg(16000)->Arg(64000)->Arg(256000)->Arg(500000)
    ->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// Craig-Bampton on the same panel: 8 distributing interfaces (nodes within
// 0.05 m) pinned, 8 fixed-interface modes. Counters add MUMPS's own factor
// figure per stage (_factor_MB) and the basis' block 8 N (b + k) bytes. The
// peaks are this process's (getrusage): run one size per process
// (--benchmark_filter=CraigBamptonPanel/100000/) or bench/fe-prep/cb_memory.sh, which
// does, for the memory table of docs/benchmarks.md.
void BM_CraigBamptonPanel(benchmark::State& state) {
  const double target_dof = static_cast<double>(state.range(0));
  const double size = fc::feprep::sizeForTriangleCount(2.0 * 1.3, static_cast<long>(target_dof / 3));
  std::ostringstream os;
  os << "materials:\n  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}\n"
     << "body:\n  name: bench\n  shell:\n    rectangle: {length: 2.0, width: 1.3}\n"
     << "    material: cfrp_iso\n    thickness: 0.002\n    element: dst\n    mesh: {size: " << size
     << ", max_triangles: 5000000}\n  interfaces:\n";
  int k = 0;
  for (double x : {-0.9, -0.3, 0.3, 0.9})
    for (double y : {-0.55, 0.55})
      os << "    P" << k++ << ": {point: [" << x << ", " << y << ", 0.0], coupling: distributing, nodes: {within: 0.05}}\n";
  os << "  reference: {pin: [P0, P1, P2, P3, P4, P5, P6, P7]}\n  reduction: craig_bampton\n  modes: 8\n";
  const fc::feprep::BodySpec spec = fc::feprep::parseBodySpec(fc::InputNode::loadString(os.str(), "bench"));
  fc::feprep::BuildOptions opt;
  opt.quiet = true;
  fc::feprep::BuildResult r;
  for (auto _ : state) r = fc::feprep::buildFlexBody(PETSC_COMM_WORLD, spec, opt);
  state.counters["dof"] = static_cast<double>(r.dofs);
  for (const auto& s : r.stages) {
    state.counters[s.stage + "_cpu_s"] = s.cpu_seconds;
    state.counters[s.stage + "_MB"] = s.peak_rss_mb;
    if (s.factorisation_mb > 0) state.counters[s.stage + "_factor_MB"] = s.factorisation_mb;
  }
  state.counters["basis_block_MB"] =
      8.0 * static_cast<double>(r.dofs) * static_cast<double>(r.constraint_modes + r.normal_modes) / (1024.0 * 1024.0);
  state.counters["shapes"] = static_cast<double>(r.body.eigenvalues.size());
}
BENCHMARK(BM_CraigBamptonPanel)
    ->Arg(10000)->Arg(100000)->Arg(300000)
    ->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (SlepcInitialize(nullptr, nullptr, nullptr, nullptr)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  SlepcFinalize();
  return 0;
}
