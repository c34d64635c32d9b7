// CPU time per simulated second of the rigid SAR antenna (shared reference
// scene, phases 1 and 2, 20 s) at several tolerances and with both
// integrators; counters report steps, rejected steps, right-hand-side
// evaluations and the energy balance error so speed is never read without
// accuracy. Also the cost of one right-hand-side evaluation (the assembled,
// factorised augmented Lagrangian solve).
#include <benchmark/benchmark.h>

#include <string>

#include "mbs-run/scene.h"
#include "mbs-run/simulation.h"
#include "mbs-run/system.h"

namespace {

fc::mbs::Model sar() {
  return fc::mbs::loadScene(std::string(FLEXCOMP_SOURCE_DIR) + "/examples/sar-antenna/sar-rigid.yaml");
}

void SarRun(benchmark::State& state, fc::mbs::IntegratorKind kind) {
  fc::mbs::Model m = sar();
  m.settings.rtol = std::pow(10.0, -double(state.range(0)));
  m.settings.integrator = kind;
  fc::mbs::Results r;
  for (auto _ : state) {
    r = fc::mbs::simulate(m, {true});
    benchmark::DoNotOptimize(r.steps);
  }
  state.counters["cpu_s_per_sim_s"] = r.cpu_seconds / r.t_reached;
  state.counters["steps"] = double(r.steps);
  state.counters["rejected"] = double(r.rejected_steps);
  state.counters["rhs_evals"] = double(r.evaluations);
  state.counters["energy_err_J"] = r.energy_balance_error;
  state.counters["violation"] = r.max_violation;
  state.counters["completed"] = r.status == "completed" ? 1 : 0;
}

void SarDopri5(benchmark::State& s) { SarRun(s, fc::mbs::IntegratorKind::DormandPrince); }
void SarTrBdf2(benchmark::State& s) { SarRun(s, fc::mbs::IntegratorKind::Bdf); }
BENCHMARK(SarDopri5)->DenseRange(4, 8, 1)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(SarTrBdf2)->DenseRange(4, 6, 1)->Unit(benchmark::kMillisecond)->Iterations(1);

void SarRightHandSide(benchmark::State& state) {
  const fc::mbs::Model m = sar();
  fc::mbs::System sys(m);
  Eigen::VectorXd y = sys.initialState(), yd;
  sys.initializeJoints(y);
  sys.project(0.0, y);
  sys.initializeJoints(y);
  for (auto _ : state) {
    sys.derivative(0.0, y, yd);
    benchmark::DoNotOptimize(yd.data());
  }
}
BENCHMARK(SarRightHandSide)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
