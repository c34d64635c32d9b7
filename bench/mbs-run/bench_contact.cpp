// the contact monitor's cost per output row on meshes of the SAR
// panels' size (2.0 x 1.3 m, element size h = 0.1 .. 0.0125 m, 2 triangles per
// h x h cell, 30 smooth modes with ~5 mm deflection), against a truss (two
// beam elements, 0.6 m) in three places: 5 mm above and parallel to the panel
// (the chord bars near contact), 60 mm above (the stays), and through it.
// Brute force (every segment against every triangle, every node placed:
// geometryDistance on placedVertices, what the monitor did before) against
// the broad phase (bounding_volume_tree.h: the tree built once, vertices placed on
// demand). Figures in docs/benchmarks.md, "Contact monitor".
#include <benchmark/benchmark.h>

#include <cmath>

#include "mbs-run/monitors/bounding_volume_tree.h"
#include "mbs-run/monitors/distance.h"

namespace {

using fc::mbs::BodyGeometry;
using Eigen::Vector3d;

constexpr int kModes = 30;

BodyGeometry panel(double h) {
  const double L = 2.0, W = 1.3;
  const int nx = int(std::lround(L / h)), ny = int(std::lround(W / h));
  BodyGeometry g;
  g.vertices.resize(3, (nx + 1) * (ny + 1));
  g.modal_displacement.setZero(3 * g.vertices.cols(), kModes);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const int k = j * (nx + 1) + i;
      const double x = L * i / nx - L / 2, y = W * j / ny - W / 2;
      g.vertices.col(k) = Vector3d(x, y, 0);
      for (int m = 0; m < kModes; ++m)
        g.modal_displacement(3 * k + 2, m) = std::cos((m % 6 + 1) * x) * std::cos((m / 6 + 1) * y);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      g.triangles.push_back({a, b, c});
      g.triangles.push_back({a, c, d});
    }
  return g;
}

BodyGeometry truss() {
  BodyGeometry g;
  g.vertices.resize(3, 3);
  g.vertices << -0.3, 0, 0.3, 0, 0, 0, 0, 0, 0;
  g.segments = {{0, 1}, {1, 2}};
  return g;
}

struct Case {
  BodyGeometry p, t;
  fc::mbs::BoundingTree tp, tt;
  Eigen::VectorXd w;
  Vector3d rt;
  Eigen::Matrix3d At;
  Case(double h, double height) : p(panel(h)), t(truss()) {
    tp = fc::mbs::buildBoundingTree(p);
    tt = fc::mbs::buildBoundingTree(t);
    w = Eigen::VectorXd::Constant(kModes, 1e-3 / kModes);
    // The truss diagonal over the panel, tilted by 0.05 rad (through: 0.5 rad).
    const double tilt = height < 0 ? 0.5 : 0.05;
    At = Eigen::AngleAxisd(0.6, Vector3d::UnitZ()).toRotationMatrix() * Eigen::AngleAxisd(tilt, Vector3d::UnitY());
    rt = Vector3d(0.3, 0.2, height < 0 ? 0.0 : height + 0.3 * std::sin(tilt));
  }
};

double height(int which) { return which == 0 ? 0.005 : which == 1 ? 0.06 : -1.0; }

void BM_ContactBruteForce(benchmark::State& st) {
  Case c(1.0 / st.range(0), height(int(st.range(1))));
  const Eigen::VectorXd none;
  for (auto _ : st)
    benchmark::DoNotOptimize(fc::mbs::geometryDistance(
        c.p, fc::mbs::placedVertices(c.p, Vector3d::Zero(), Eigen::Matrix3d::Identity(), c.w), c.t,
        fc::mbs::placedVertices(c.t, c.rt, c.At, none)));
  st.counters["triangles"] = double(c.p.triangles.size());
}

void BM_ContactTree(benchmark::State& st) {
  Case c(1.0 / st.range(0), height(int(st.range(1))));
  const Eigen::VectorXd none;
  for (auto _ : st) {
    fc::mbs::PlacedGeometry a(c.p, c.tp, Vector3d::Zero(), Eigen::Matrix3d::Identity(), c.w), b(c.t, c.tt, c.rt, c.At, none);
    benchmark::DoNotOptimize(fc::mbs::treeDistance(b, a));
  }
  st.counters["triangles"] = double(c.p.triangles.size());
}

// Args: 1/h (10, 20, 40, 80), place (0: 5 mm above, 1: 60 mm above, 2: through).
void sizes(benchmark::internal::Benchmark* b) {
  for (int place : {0, 1, 2})
    for (int inv_h : {10, 20, 40, 80}) b->Args({inv_h, place});
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK(BM_ContactBruteForce)->Apply(sizes);
BENCHMARK(BM_ContactTree)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
