// section-prep: composite beam cross-section stiffness and inertia.
//   section-prep SECTION.yaml -o SECTION.h5
//   section-prep CASE.sg -o CASE.h5        (a VABS input file)
#include <CLI/CLI.hpp>

#include <chrono>
#include <iostream>
#include <optional>
#include <vector>

#include "common/cli.h"
#include "common/inspect.h"
#include "common/files.h"
#include "common/input.h"
#include "common/memory.h"
#include "common/progress.h"
#include "common/termination.h"
#include "common/version.h"
#include "section-prep/cross_section.h"
#include "section-prep/section_mesher.h"
#include "section-prep/section_output.h"
#include "section-prep/section_spec.h"
#include "section-prep/vabs_reader.h"

namespace {

bool isYaml(const std::string& path) {
  auto ends = [&](const std::string& s) {
    return path.size() >= s.size() && path.compare(path.size() - s.size(), s.size(), s) == 0;
  };
  return ends(".yaml") || ends(".yml");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"section-prep: stiffness and mass matrices of a composite beam cross-section "
               "(variational-asymptotic method, as VABS)"};
  std::string input, output;
  bool quiet = false;
  std::vector<double> recover;
  app.add_option("input", input, "SECTION.yaml, or a VABS input file (CASE.sg)")->required();
  app.add_option("-o,--output", output, "the HDF5 file to write (format section/1)")->required();
  app.add_option("--recover", recover,
                 "F1 F2 F3 M1 M2 M3: also recover the section's stresses, strains and ply failure "
                 "indices for these resultants (N, N m; /stiffness/timoshenko order), print them per "
                 "element and write them under /recovered/")
      ->expected(6);
  app.add_flag("-q,--quiet", quiet, "no summary on stdout, no progress on stderr");
  app.set_version_flag("--version", std::string("section-prep ") + fc::version());
  fc::addInspectOption(app, "section-prep", fc::inspectFile);
  fc::addInputReferenceFooter(app);
  CLI11_PARSE(app, argc, argv);
  // A signal removes the temporary being written and exits: no partial output.
  fc::installTerminationHandlers("section-prep", fc::TerminationPolicy::ExitNow);

  return fc::guardedMain("section-prep", [&]() {
    // Refuse a bad output path before any computing, not after.
    fc::checkOutputIsNotAnInput(output, {input});
    fc::checkOutputWritable(output);
    using namespace fc::section;
    SectionMesh mesh;
    AnalysisOptions opt;
    std::vector<std::string> inputs{input};
    // Each stage is named for an out-of-memory message (common/memory.h).
    std::optional<fc::StageScope> stage(std::in_place, "reading the input");
    if (isYaml(input)) {
      const fc::InputNode root = fc::InputNode::loadFile(input);
      const SectionSpec spec = readSectionSpec(root);
      if (!spec.mesh_file.empty()) inputs.push_back(spec.mesh_file);
      fc::checkOutputIsNotAnInput(output, inputs);
      if (!quiet) std::cerr << "section-prep: meshing with gmsh\n";
      // Errors are located at the key that chose the geometry: the mesh file or the section.
      const fc::InputNode sec = root["section"];
      const fc::InputNode where = sec.has("file") ? sec["file"] : sec;
      stage.emplace("meshing");
      try {
        // gmsh may throw inside its OpenMP meshing loop, where no catch reaches:
        // the terminate handler then reports it with this location.
        const fc::FatalErrorContext context(
            fc::InputError(where.file(), where.line(), where.column(), where.path(),
                           "cannot mesh this section: ").what());
        mesh = meshSection(spec);
      } catch (const fc::InputError& e) {
        // Located in the mesh file (a .geo line): as it is. About the whole file (its
        // kind, unreadable): at the key that named it.
        if (e.line() > 0) throw;
        where.fail(std::string("cannot mesh this section: ") + e.file() + ": " + e.message());
      } catch (const std::bad_alloc&) {
        throw;  // out of memory is no input error
      } catch (const std::exception& e) {
        where.fail(std::string("cannot mesh this section: ") + e.what());
      }
    } else {
      VabsModel m = readVabsFile(input);
      mesh = std::move(m.mesh);
      opt.timoshenko = true;  // always: the Timoshenko matrix is part of the output contract
    }
    // Every file read so far (includes, mesh files) is an input the output must not replace.
    fc::checkOutputIsNotAnInput(output, fc::inputFilesRead());
    stage.emplace("section analysis");
    fc::Progress progress("section-prep", 1.0, quiet);
    opt.progress = [&](const std::string& phase, double f) { progress.update(f, phase); };
    const auto t0 = std::chrono::steady_clock::now();
    const SectionProperties p = analyzeSection(mesh, opt);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress.finish();
    std::optional<RecoveryRun> run;
    if (!recover.empty()) {
      stage.emplace("stress recovery");
      run.emplace();
      for (int i = 0; i < 6; ++i) run->resultants(i) = recover[i];
      std::vector<int> element_material;
      for (const auto& e : mesh.elements) element_material.push_back(e.material);
      std::vector<std::optional<fc::PlyStrength>> strengths;
      for (const auto& m : mesh.materials) strengths.push_back(m.strength);
      run->elements = recoverStresses(p.recovery, element_material, strengths, run->resultants);
    }
    stage.emplace("writing " + output);
    writeSectionFile(output, p, fc::sha256Files(inputs), input, mesh, run ? &*run : nullptr);
    if (!quiet) {
      printSummary(std::cout, p);
      if (run) printRecovery(std::cout, mesh, p, *run);
      std::cout << "\nSolved in " << secs << " s; wrote " << output << "\n";
    }
    return 0;
  });
}
