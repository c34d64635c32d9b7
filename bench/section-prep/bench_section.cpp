// Timing of the cross-section analysis (assembly, factorisation, the two
// warping solves) from a few hundred to ~200 000 elements, on gmsh meshes of a
// laminated box (quadratic triangles) and on VABS's MH-104 blade section
// (21 213 linear triangles). Meshing is done once, outside the timed loop.
// Peak resident memory is reported as a counter (getrusage, whole process).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <map>
#include <string>

#include "common/input.h"
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

void BM_Box(benchmark::State& state) {
  const double h = 1e-5 * static_cast<double>(state.range(0));  // range in units of 10 um
  const SectionMesh& mesh = boxMesh(h);
  for (auto _ : state) {
    SectionProperties p = analyzeSection(mesh);
    benchmark::DoNotOptimize(p.timoshenko(0, 0));
  }
  state.counters["elements"] = static_cast<double>(mesh.elements.size());
  state.counters["nodes"] = static_cast<double>(mesh.nodes.size());
  state.counters["peak_rss_MB"] = peakRssMb();
}
BENCHMARK(BM_Box)->Arg(400)->Arg(200)->Arg(100)->Arg(50)->Arg(35)->Arg(25)->Arg(18)
    ->Unit(benchmark::kMillisecond);

void BM_MH104(benchmark::State& state) {
  static const VabsModel model =
      readVabsFile(std::string(FLEXCOMP_SHARED_DIR) + "/reference/vabs/mh104.sg");
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
