// Cost of the flexible-body inertia per right-hand-side evaluation, the inner loop
// of mbs-run's integrators, against the number of modes kept (the SAR panels keep
// 14, the trusses 2), and of reading a body file's first modes (hyperslab) versus
// all of it. Bodies are random lumped-mass bodies (tests/mbs-run/flexible/random_body.h).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "common/rotations.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/mechanics/flexible/geometric_stiffening.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

void BM_FlexibleInertia(benchmark::State& state) {
  const int nm = static_cast<int>(state.range(0));
  const fc::FlexBody body = fc::testing::randomBody(200, nm, 1);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const Eigen::Matrix3d A = fc::expRotation(Eigen::Vector3d(0.3, -0.2, 0.9));
  const Eigen::VectorXd w = 0.01 * Eigen::VectorXd::Ones(nm), wd = Eigen::VectorXd::Ones(nm);
  const Eigen::Vector3d om(0.1, 0.2, 0.3);
  for (auto _ : state) benchmark::DoNotOptimize(fc::mbs::flexibleInertia(inv, A, w, wd, om));
  state.SetLabel(std::to_string(nm) + " modes");
}
BENCHMARK(BM_FlexibleInertia)->Arg(0)->Arg(2)->Arg(6)->Arg(14)->Arg(28)->Arg(56);

void BM_FlexibleMassMatrix(benchmark::State& state) {
  const int nm = static_cast<int>(state.range(0));
  const fc::FlexBody body = fc::testing::randomBody(200, nm, 1);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const Eigen::VectorXd w = 0.01 * Eigen::VectorXd::Ones(nm);
  for (auto _ : state) benchmark::DoNotOptimize(fc::mbs::flexibleMassMatrix(inv, Eigen::Matrix3d::Identity(), w));
}
BENCHMARK(BM_FlexibleMassMatrix)->Arg(2)->Arg(14)->Arg(56);

// A body file of 20 000 nodes and 50 modes (~50 MB of shapes); mbs-run reads 14.
const std::string& bigFile() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() /
                           ("flexcomp_bench_flexbody_" + std::to_string(::getpid()) + ".h5")).string();
    const fc::FlexBody body = fc::testing::randomBody(20000, 50, 3);
    fc::writeFlexBody(p, body, fc::computeInertiaInvariants(body), fc::Provenance{});
    std::atexit([] { std::remove(bigFile().c_str()); });
    return p;
  }();
  return path;
}

void BM_ReadFlexBody(benchmark::State& state) {
  const auto parts = state.range(0) ? fc::FlexBodyParts::All : fc::FlexBodyParts::Dynamics;
  const std::string& path = bigFile();
  for (auto _ : state) benchmark::DoNotOptimize(fc::readFlexBody(path, 14, parts));
  state.SetLabel(state.range(0) ? "14 of 50 modes, with mesh and shapes" : "14 of 50 modes, dynamics only");
}
BENCHMARK(BM_ReadFlexBody)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

// Geometric stiffening: K_G(p) = sum of the 12 cases and its force
// K_G w, what System::derivative adds per stiffened body and evaluation (the
// velocity and the acceleration cases, the two passes together).
void BM_GeometricStiffeningForce(benchmark::State& state) {
  const int nm = static_cast<int>(state.range(0));
  fc::mbs::GeometricStiffening g;
  for (auto& k : g.K) {
    const Eigen::MatrixXd r = Eigen::MatrixXd::Random(nm, nm);
    k = r + r.transpose();
  }
  const Eigen::VectorXd w = Eigen::VectorXd::Random(nm);
  const fc::mbs::StiffeningParameters p =
      fc::mbs::stiffeningParameters(Eigen::Vector3d(0.1, 0.2, 3.0), Eigen::Vector3d(0.0, 0.0, 0.5), Eigen::Vector3d(-1.0, 0.2, 0.0));
  for (auto _ : state) {
    Eigen::VectorXd f = fc::mbs::stiffeningMatrix(g, p, true, false) * w;
    f += fc::mbs::stiffeningMatrix(g, p, false, true) * w;
    benchmark::DoNotOptimize(f.data());
  }
}
BENCHMARK(BM_GeometricStiffeningForce)->Arg(4)->Arg(14)->Arg(56);

BENCHMARK_MAIN();
