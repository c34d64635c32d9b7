// Cost of the element matrices fe-prep assembles: one shell triangle (DKT, DST,
// coupled laminate; K, consistent M and lumped mass) and one coupled
// Timoshenko beam. The 5e5-DOF panel of bench/fe-prep has ~1.7e5 triangles, so
// the element time per triangle bounds that stage's cost.
#include <benchmark/benchmark.h>

#include "fe-prep/elements/beam_element.h"
#include "fe-prep/elements/shell_triangle.h"

namespace {

fc::LaminateStiffness laminate() {
  fc::LaminateStiffness s;
  s.A << 3e8, 5e7, 1e6, 5e7, 1e8, 2e6, 1e6, 2e6, 4e7;
  s.B << 1e4, 0, 2e3, 0, -1e4, 1e3, 2e3, 1e3, 0;
  s.D << 100, 20, 3, 20, 50, 2, 3, 2, 25;
  s.As << 8e6, 1e5, 1e5, 6e6;
  s.thickness = 0.002;
  s.mass_per_area = 3.2;
  s.rotary_per_area = 1.1e-6;
  return s;
}

void BM_ShellTriangle(benchmark::State& state) {
  const fc::LaminateStiffness lam = laminate();
  const auto kind = state.range(0) == 0 ? fc::fe::ShellKind::DKT : fc::fe::ShellKind::DST;
  Eigen::Matrix3d xyz;
  xyz << 0, 0, 0, 0.05, 0.004, 0.001, 0.02, 0.045, -0.002;
  for (auto _ : state) {
    fc::fe::ShellMatrices m = fc::fe::shellTriangle(xyz, lam, kind, Eigen::Vector3d::UnitX());
    benchmark::DoNotOptimize(m);
  }
  state.SetLabel(state.range(0) == 0 ? "DKT" : "DST");
}
BENCHMARK(BM_ShellTriangle)->Arg(0)->Arg(1);

void BM_TimoshenkoBeam(benchmark::State& state) {
  fc::Matrix6d K = fc::Matrix6d::Identity();
  K.diagonal() << 1e7, 3e6, 3e6, 40, 60, 60;
  K(0, 3) = K(3, 0) = 1e3;
  fc::Matrix6d M = fc::Matrix6d::Identity() * 0.05;
  for (auto _ : state) {
    fc::fe::BeamMatrices b = fc::fe::timoshenkoBeam(
        Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.62, 0, 0), Eigen::Vector3d(0, 1, 0), K, M);
    benchmark::DoNotOptimize(b);
  }
}
BENCHMARK(BM_TimoshenkoBeam);

}  // namespace

BENCHMARK_MAIN();
