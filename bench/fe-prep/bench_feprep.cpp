// fe-prep stage timings: a free-free SAR-size panel (2.0 x 1.3 m, 2 mm,
// isotropic, DST, lumped mass, 20 elastic modes) from ~1e3 to ~5e5 DOF.
// Counters per size: DOF, meshing / assembly / eigensolve wall seconds and the
// peak resident memory after each stage. One iteration per size: a run is
// seconds to minutes, and the stages are deterministic.
//   bench_feprep [--benchmark_filter=...]      (serial)
// Parallel scaling: bench/fe-prep/scaling.sh runs the executable under mpirun.
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

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (SlepcInitialize(nullptr, nullptr, nullptr, nullptr)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  SlepcFinalize();
  return 0;
}
