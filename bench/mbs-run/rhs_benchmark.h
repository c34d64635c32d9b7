#pragma once
// Shared by the mbs-run benchmarks that time one right-hand-side evaluation
// (bench_mbs SarRightHandSide, bench_stiffening): System::derivative at the
// model's initial state made consistent first, so the timed call is the one an
// integrator step makes.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>

#include "mbs-run/constrained/system.h"

namespace fc::mbs::bench {

// Times System::derivative(0, y) for model m, y its initial state with the
// joints initialised, projected onto the constraints and the joints
// initialised again at the projected state.
inline void timeRightHandSide(benchmark::State& state, const Model& m) {
  System sys(m);
  Eigen::VectorXd y = sys.initialState(), yd;
  sys.initializeJoints(y);
  sys.project(0.0, y);
  sys.initializeJoints(y);
  for (auto _ : state) {
    sys.derivative(0.0, y, yd);
    benchmark::DoNotOptimize(yd.data());
  }
}

}  // namespace fc::mbs::bench
