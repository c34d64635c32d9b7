// Imported matrices at scale (fe-prep/import/): a free brick-shaped lattice of
// n x n x n cells written by this program as Matrix Market files (K and M, one
// triangle), a "node dof" list and a "label x y z" table, then read by fe-prep:
//   BM_ImportRead   the import alone (importMatrices: parse, checks, spread to
//                   6 DOF per node, rigid-strain and mass checks), 1e4-1e6 DOF;
//   BM_ImportBody   the whole body (buildFlexBody, 10 free modes), 1e4-1e5 DOF:
//                   the import stage against assembly and the eigen-solve.
// The lattice: axial springs k = 1 / |d| between each node and its 26
// neighbours (the 27-point stencil of a trilinear brick mesh: ~81 non-zeros per
// row, as C3D8), unit diagonal masses. It is not an elasticity discretisation;
// the reader's cost depends on the non-zeros, not on what they model. The files
// are generated at run time in a scratch folder (removed afterwards), never
// committed. Counters: dof, nnz (stored entries of K), CPU seconds and the
// process's peak resident memory after the stage (sizes run in increasing
// order, so each peak is that size's; run one size per process, e.g.
// --benchmark_filter='BM_ImportSlab/407/1', for a size's own peak), and for
// BM_ImportSlab MUMPS's own factor memory per stage (*_factor_MB, INFOG(21)).
// docs/benchmarks.md holds the figures.
//   bench_import [--benchmark_filter=BM_ImportRead]
#include <benchmark/benchmark.h>
#include <slepcsys.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>

#include "common/flexbody.h"
#include "common/input.h"
#include "fe-prep/body_spec.h"
#include "fe-prep/build_body.h"
#include "fe-prep/import/imported_body.h"

namespace {

double peakMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Lattice {
  std::string dir;
  long dof = 0, nnz = 0;
};

// Writes the lattice of n^3 cells (cell 0.01 m) into a fresh folder; with
// `layers` > 0, a slab of n x n x layers cells (a shell-like matrix: its
// factorisation fills in as a plate's), whose node table is an .inp with two
// node sets of 10 nodes each at opposite corners of its edges x = 0 and x = n
// (PADA, PADB: the distributing interfaces of BM_ImportSlab).
Lattice writeLattice(int n, int layers = 0) {
  Lattice L;
  L.dir = (std::filesystem::temp_directory_path() /
           ("flexcomp_bench_import_" + std::to_string(n) + "_" + std::to_string(layers))).string();
  std::filesystem::remove_all(L.dir);
  std::filesystem::create_directories(L.dir);
  const int m = n + 1, mz = layers > 0 ? layers + 1 : m;
  const long nodes = static_cast<long>(m) * m * mz;
  L.dof = 3 * nodes;
  auto id = [&](int i, int j, int k) { return (static_cast<long>(k) * m + j) * m + i; };
  const double h = 0.01;
  {
    FILE* t = std::fopen((L.dir + (layers > 0 ? "/nodes.inp" : "/nodes.txt")).c_str(), "w");
    FILE* d = std::fopen((L.dir + "/dofs.txt").c_str(), "w");
    if (layers > 0) std::fprintf(t, "*NODE\n");
    for (int k = 0; k < mz; ++k)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const long a = id(i, j, k) + 1;
          std::fprintf(t, layers > 0 ? "%ld, %.17g, %.17g, %.17g\n" : "%ld %.17g %.17g %.17g\n", a, h * i, h * j, h * k);
          std::fprintf(d, "%ld 1\n%ld 2\n%ld 3\n", a, a, a);
        }
    if (layers > 0)
      for (int side = 0; side < 2; ++side) {
        std::fprintf(t, "*NSET, NSET=%s\n", side == 0 ? "PADA" : "PADB");
        for (int k = 0; k < mz; ++k)
          for (int jj = 0; jj < 5; ++jj) {
            const int i = side == 0 ? 0 : m - 1, j = side == 0 ? jj : m - 1 - jj;
            std::fprintf(t, "%ld\n", id(i, j, k) + 1);
          }
      }
    std::fclose(t);
    std::fclose(d);
  }
  // K's lower triangle: node a's 3x3 diagonal block (sum of its springs) and
  // the blocks -k e e^T to each neighbour b < a. Two passes: count, then write.
  for (int pass = 0; pass < 2; ++pass) {
    FILE* f = nullptr;
    if (pass == 1) {
      f = std::fopen((L.dir + "/k.mtx").c_str(), "w");
      std::fprintf(f, "%%%%MatrixMarket matrix coordinate real symmetric\n%ld %ld %ld\n", L.dof, L.dof, L.nnz);
    }
    long count = 0;
    for (int k = 0; k < mz; ++k)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const long a = id(i, j, k);
          double D[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) {
                if (!di && !dj && !dk) continue;
                const int i2 = i + di, j2 = j + dj, k2 = k + dk;
                if (i2 < 0 || j2 < 0 || k2 < 0 || i2 >= m || j2 >= m || k2 >= mz) continue;
                const double len = h * std::sqrt(static_cast<double>(di * di + dj * dj + dk * dk));
                const double e[3] = {h * di / len, h * dj / len, h * dk / len};
                const double kk = 1e6 * h / len;
                for (int r = 0; r < 3; ++r)
                  for (int c = 0; c < 3; ++c) D[r][c] += kk * e[r] * e[c];
                const long b = id(i2, j2, k2);
                if (b >= a) continue;
                for (int r = 0; r < 3; ++r)
                  for (int c = 0; c < 3; ++c) {
                    ++count;
                    if (f) std::fprintf(f, "%ld %ld %.17g\n", 3 * a + r + 1, 3 * b + c + 1, -kk * e[r] * e[c]);
                  }
              }
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c <= r; ++c) {
              ++count;
              if (f) std::fprintf(f, "%ld %ld %.17g\n", 3 * a + r + 1, 3 * a + c + 1, D[r][c]);
            }
        }
    L.nnz = count;
    if (f) std::fclose(f);
  }
  FILE* f = std::fopen((L.dir + "/m.mtx").c_str(), "w");
  std::fprintf(f, "%%%%MatrixMarket matrix coordinate real symmetric\n%ld %ld %ld\n", L.dof, L.dof, L.dof);
  for (long r = 1; r <= L.dof; ++r) std::fprintf(f, "%ld %ld 0.001\n", r, r);
  std::fclose(f);
  return L;
}

std::string yaml(const Lattice& L, bool slab = false) {
  return "body:\n  name: lattice\n  matrices: {format: matrix_market, stiffness: " + L.dir + "/k.mtx, mass: " + L.dir +
         "/m.mtx, dofs: " + L.dir + (slab ? "/dofs.txt, model: " + L.dir + "/nodes.inp}" : "/dofs.txt, model: " + L.dir + "/nodes.txt}") +
         "\n  units: m-kg-s\n  modes: 10\n";
}

void BM_ImportRead(benchmark::State& state) {
  const Lattice L = writeLattice(static_cast<int>(state.range(0)));
  const fc::feprep::BodySpec spec = fc::feprep::parseBodySpec(fc::InputNode::loadString(yaml(L), "bench"));
  double cpu = 0.0;
  long nodes = 0;
  for (auto _ : state) {
    const double c0 = cpuSeconds();
    const fc::feprep::ImportedModel im = fc::feprep::importMatrices(*spec.matrices);
    cpu = cpuSeconds() - c0;
    nodes = im.mesh.nodeCount();
  }
  state.counters["dof"] = static_cast<double>(L.dof);
  state.counters["nnz"] = static_cast<double>(L.nnz);
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["read_cpu_s"] = cpu;
  state.counters["peak_MB"] = peakMb();
  std::filesystem::remove_all(L.dir);
}
// n = 15, 32, 46, 69: 1.2e4, 1.1e5, 3.1e5, 1.0e6 DOF.
BENCHMARK(BM_ImportRead)->Arg(15)->Arg(32)->Arg(46)->Arg(69)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void BM_ImportBody(benchmark::State& state) {
  const Lattice L = writeLattice(static_cast<int>(state.range(0)));
  const fc::feprep::BodySpec spec = fc::feprep::parseBodySpec(fc::InputNode::loadString(yaml(L), "bench"));
  fc::feprep::BuildOptions opt;
  opt.quiet = true;
  fc::feprep::BuildResult r;
  for (auto _ : state) r = fc::feprep::buildFlexBody(PETSC_COMM_WORLD, spec, opt);
  state.counters["dof"] = static_cast<double>(L.dof);
  state.counters["nnz"] = static_cast<double>(L.nnz);
  for (const auto& s : r.stages) {
    state.counters[s.stage + "_cpu_s"] = s.cpu_seconds;
    state.counters[s.stage + "_MB"] = s.peak_rss_mb;
  }
  std::filesystem::remove_all(L.dir);
}
// n = 15, 21, 32: 1.2e4, 3.2e4, 1.1e5 DOF.
BENCHMARK(BM_ImportBody)->Arg(15)->Arg(21)->Arg(32)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The slab's whole body, free (10 modes) and by Craig-Bampton with two
// distributing interfaces (PADA, PADB, clamped; 10 fixed-interface modes):
// the 1e6-DOF imported pair read and reduced end to end. Arguments: cells
// along x and y (one layer through the thickness), then 0 free, 1 Craig-Bampton.
void BM_ImportSlab(benchmark::State& state) {
  const bool cb = state.range(1) != 0;
  const Lattice L = writeLattice(static_cast<int>(state.range(0)), 1);
  std::string y = yaml(L, true);
  if (cb)
    y += "  interfaces:\n    a: {point: [0, 0, 0], coupling: distributing, nodes: {edge: PADA}}\n"
         "    b: {point: [" + std::to_string(0.01 * static_cast<double>(state.range(0))) + ", " +
         std::to_string(0.01 * static_cast<double>(state.range(0))) + ", 0], coupling: distributing, nodes: {edge: PADB}}\n"
         "  reference: {clamp: [a, b]}\n  reduction: craig_bampton\n";
  const fc::feprep::BodySpec spec = fc::feprep::parseBodySpec(fc::InputNode::loadString(y, "bench"));
  fc::feprep::BuildOptions opt;
  opt.quiet = true;
  fc::feprep::BuildResult r;
  double write_cpu = 0.0;
  for (auto _ : state) {
    r = fc::feprep::buildFlexBody(PETSC_COMM_WORLD, spec, opt);
    const double c0 = cpuSeconds();
    fc::writeFlexBody(L.dir + "/slab.h5", r.body, fc::computeInertiaInvariants(r.body), fc::Provenance{});
    write_cpu = cpuSeconds() - c0;
  }
  state.counters["dof"] = static_cast<double>(L.dof);
  state.counters["nnz"] = static_cast<double>(L.nnz);
  for (const auto& s : r.stages) {
    state.counters[s.stage + "_cpu_s"] = s.cpu_seconds;
    state.counters[s.stage + "_MB"] = s.peak_rss_mb;
    if (s.factorisation_mb > 0) state.counters[s.stage + "_factor_MB"] = s.factorisation_mb;
  }
  state.counters["write_cpu_s"] = write_cpu;
  state.counters["write_MB"] = peakMb();
  std::filesystem::remove_all(L.dir);
}
// 57, 129, 235, 407 cells: 2.0e4, 1.0e5, 3.3e5, 1.0e6 DOF; free, then Craig-Bampton.
BENCHMARK(BM_ImportSlab)
    ->Args({57, 0})->Args({57, 1})->Args({129, 0})->Args({129, 1})->Args({235, 0})->Args({235, 1})
    ->Args({407, 0})->Args({407, 1})
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
