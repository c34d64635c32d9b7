// Reading mesh files at scale: a flat panel of n x n quadrilaterals written by
// make_big_meshes.py (this folder) as a Nastran deck (small fixed fields:
// GRID, CQUAD4, PSHELL, MAT1) and as gmsh .msh 4.1 and 2.2, read as fe-prep
// reads a body's mesh file:
//   BM_NastranRead  readNastranCards + nastranModel (the cards, then the mesh
//                   with its properties and material frames);
//   BM_Msh41Read, BM_Msh22Read  readRegionMesh (gmsh's reader through its API,
//                   then the regions; the quads split into triangles).
// Counters: elements, nodes, CPU seconds of the read, the growth of the
// process's peak resident memory over the stage (ru_maxrss after minus before:
// 0 when an earlier, larger stage set the peak; run one benchmark per process
// for the memory, as docs/benchmarks.md does). readRegionMesh opens its own
// gmsh session.
//   python3 make_big_meshes.py 1000 1000 /tmp/meshes
//   bench_mesh_read --meshes=/tmp/meshes --benchmark_filter=BM_NastranRead
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cstring>
#include <ctime>
#include <string>

#include "common/units.h"
#include "fe-prep/mesh_files/gmsh_regions.h"
#include "fe-prep/mesh_files/nastran.h"

namespace {

std::string g_dir = ".";

double peakMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

void BM_NastranRead(benchmark::State& state) {
  double cpu_cards = 0.0, cpu = 0.0, mb0 = peakMb(), mb_cards = 0.0;
  long elements = 0, nodes = 0;
  for (auto _ : state) {
    const double c0 = cpuSeconds();
    fc::feprep::NastranModel model;
    {
      const std::vector<fc::feprep::NastranCard> cards = fc::feprep::readNastranCards(g_dir + "/panel.bdf");
      cpu_cards = cpuSeconds() - c0;
      mb_cards = peakMb() - mb0;
      model = fc::feprep::nastranModel(cards, fc::unitSystem("m-kg-s"), {});
    }
    cpu = cpuSeconds() - c0;
    elements = static_cast<long>(model.mesh.triangles.size()) / 2;
    nodes = model.mesh.nodeCount();
  }
  state.counters["quads"] = static_cast<double>(elements);
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["cards_cpu_s"] = cpu_cards;
  state.counters["cards_MB"] = mb_cards;
  state.counters["read_cpu_s"] = cpu;
  state.counters["read_MB"] = peakMb() - mb0;
}
BENCHMARK(BM_NastranRead)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void mshRead(benchmark::State& state, const std::string& file) {
  double cpu = 0.0, mb0 = peakMb();
  long triangles = 0, nodes = 0;
  for (auto _ : state) {
    const double c0 = cpuSeconds();
    fc::feprep::RegionMeshRequest r;
    r.path = g_dir + "/" + file;
    r.max_triangles = 100000000;
    r.regions = {"skin"};
    fc::feprep::Mesh mesh;
    try {
      mesh = fc::feprep::readRegionMesh(r);
    } catch (const std::string& e) {  // gmsh's own errors
      state.SkipWithError(("gmsh: " + e).c_str());
      return;
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      return;
    }
    cpu = cpuSeconds() - c0;
    triangles = static_cast<long>(mesh.triangles.size());
    nodes = mesh.nodeCount();
  }
  state.counters["quads"] = static_cast<double>(triangles / 2);
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["read_cpu_s"] = cpu;
  state.counters["read_MB"] = peakMb() - mb0;
}
void BM_Msh41Read(benchmark::State& state) { mshRead(state, "panel41.msh"); }
void BM_Msh22Read(benchmark::State& state) { mshRead(state, "panel22.msh"); }
BENCHMARK(BM_Msh41Read)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_Msh22Read)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--meshes=", 9) == 0) {
      g_dir = argv[i] + 9;
      for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
      --argc;
      break;
    }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
