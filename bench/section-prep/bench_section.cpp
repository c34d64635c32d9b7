// Timing of the cross-section analysis (assembly, factorisation, the two
// warping solves) from a few hundred to ~100 000 elements, on gmsh meshes of a
// laminated box (quadratic triangles) and on VABS's MH-104 blade section
// (21 213 linear triangles). Meshing is done once, outside the timed loop.
// Peak resident memory is reported as a counter (getrusage, whole process).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <map>
#include <string>

#include "common/input.h"
#include "common/materials.h"
#include "section-prep/cross_section.h"
#include "section-prep/section_mesher.h"
#include "section-prep/section_spec.h"
#include "section-prep/vabs_reader.h"

namespace {

using namespace fc::section;

double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

// A 4-ply [0/45/-45/90] box 0.2 x 0.1 m with 2 mm plies, meshed at h.
const SectionMesh& boxMesh(double h) {
  static std::map<double, SectionMesh> cache;
  auto it = cache.find(h);
  if (it != cache.end()) return it->second;
  const std::string yaml =
      "materials:\n"
      "  ud: {type: orthotropic, E1: 140e9, E2: 9e9, E3: 9e9, G12: 5e9, G13: 5e9, G23: 3e9,\n"
      "       nu12: 0.3, nu13: 0.3, nu23: 0.5, rho: 1550}\n"
      "section:\n"
      "  shape: box\n  width: 0.2\n  height: 0.1\n  mesh_size: " + std::to_string(h) + "\n"
      "  wall: {plies: [{material: ud, thickness: 0.002, angle_deg: 0},\n"
      "                 {material: ud, thickness: 0.002, angle_deg: 45},\n"
      "                 {material: ud, thickness: 0.002, angle_deg: -45},\n"
      "                 {material: ud, thickness: 0.002, angle_deg: 90}]}\n";
  return cache[h] = meshSection(readSectionSpec(fc::InputNode::loadString(yaml)));
}

// Times analyzeSection on `mesh` and reports the phases, the size and the
// peak memory as counters.
void analyzeAndReport(benchmark::State& state, const SectionMesh& mesh) {
  SectionProperties p;
  for (auto _ : state) {
    p = analyzeSection(mesh);
    benchmark::DoNotOptimize(p.timoshenko(0, 0));
  }
  state.counters["cpu_assembly_s"] = p.cpu_assembly;
  state.counters["cpu_factor_s"] = p.cpu_factorisation;
  state.counters["cpu_solves_s"] = p.cpu_solves;
  state.counters["elements"] = static_cast<double>(mesh.elements.size());
  state.counters["nodes"] = static_cast<double>(mesh.nodes.size());
  state.counters["peak_rss_MB"] = peakRssMb();
}

void BM_Box(benchmark::State& state) {
  const double h = 1e-5 * static_cast<double>(state.range(0));  // range in units of 10 um
  const SectionMesh& mesh = boxMesh(h);
  analyzeAndReport(state, mesh);
}
BENCHMARK(BM_Box)->Arg(400)->Arg(200)->Arg(100)->Arg(50)->Arg(35)
    ->Unit(benchmark::kMillisecond);

// A structured mesh of a 0.1 x 0.02 m two-ply [30/-30] strip, linear
// triangles (as VABS users' meshes, e.g. MH-104) or quadratic ones.
SectionMesh gridMesh(int nx, int ny, bool quadratic) {
  SectionMesh m;
  const fc::Material ud = fc::makeOrthotropic("ud", 140e9, 9e9, 9e9, 5e9, 5e9, 3e9, 0.3, 0.3, 0.5, 1550);
  m.materials.push_back({"ud", ud.C, ud.rho, std::nullopt});
  const int px = quadratic ? 2 * nx + 1 : nx + 1, py = quadratic ? 2 * ny + 1 : ny + 1;
  for (int j = 0; j < py; ++j)
    for (int i = 0; i < px; ++i)
      m.nodes.emplace_back(0.1 * i / (px - 1) - 0.05, 0.02 * j / (py - 1) - 0.01);
  auto id = [&](int i, int j) { return j * px + i; };
  const int s = quadratic ? 2 : 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int i0 = s * i, j0 = s * j;
      for (int t = 0; t < 2; ++t) {
        SectionElement e;
        e.shape = ElementShape::Triangle;
        e.theta3_deg = (j < ny / 2) ? 30 : -30;
        if (t == 0) {
          e.nodes[0] = id(i0, j0); e.nodes[1] = id(i0 + s, j0); e.nodes[2] = id(i0 + s, j0 + s);
          if (quadratic) { e.nodes[4] = id(i0 + 1, j0); e.nodes[5] = id(i0 + 2, j0 + 1); e.nodes[6] = id(i0 + 1, j0 + 1); }
        } else {
          e.nodes[0] = id(i0, j0); e.nodes[1] = id(i0 + s, j0 + s); e.nodes[2] = id(i0, j0 + s);
          if (quadratic) { e.nodes[4] = id(i0 + 1, j0 + 1); e.nodes[5] = id(i0 + 1, j0 + 2); e.nodes[6] = id(i0, j0 + 1); }
        }
        m.elements.push_back(e);
      }
    }
  return m;
}

void BM_Grid(benchmark::State& state) {
  const int nx = static_cast<int>(state.range(0));
  const bool quadratic = state.range(1) != 0;
  const SectionMesh mesh = gridMesh(nx, nx / 5, quadratic);
  analyzeAndReport(state, mesh);
}
// (nx, quadratic): 2 nx^2 / 5 triangles: 640, 10 240, 40 960, 100 000.
BENCHMARK(BM_Grid)->Args({40, 0})->Args({160, 0})->Args({320, 0})->Args({500, 0})
    ->Args({40, 1})->Args({160, 1})->Args({320, 1})->Unit(benchmark::kMillisecond);

void BM_MH104(benchmark::State& state) {
  static const VabsModel model =
      readVabsFile(std::string(FLEXCOMP_DATA_DIR) + "/vabs/mh104.sg");
  for (auto _ : state) {
    SectionProperties p = analyzeSection(model.mesh);
    benchmark::DoNotOptimize(p.timoshenko(0, 0));
  }
  state.counters["elements"] = static_cast<double>(model.mesh.elements.size());
  state.counters["peak_rss_MB"] = peakRssMb();
}
BENCHMARK(BM_MH104)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
