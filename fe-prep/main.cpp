// fe-prep BODY.yaml -o BODY.h5: a panel or a truss to a reduced flexible body.
// One source, two programs (fe-prep/CMakeLists.txt): fe-prep, the serial
// backend, which hands a run it does not build to fe-prep-mpi, the PETSc
// backend, with the same arguments (backend_choice.h); each is this main()
// over its own la_backend.h.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <iostream>

#include "common/cli.h"
#include "common/files.h"
#include "common/input.h"
#include "common/memory.h"
#include "common/flexbody.h"
#include "common/termination.h"
#include "common/version.h"
#include "fe-prep/body_spec.h"
#include "fe-prep/build_body.h"
#include "fe-prep/io/file_io.h"
#include "fe-prep/backend_choice.h"
#include "fe-prep/xdmf_writer.h"

namespace {

void printSummary(const fc::feprep::BodySpec& spec, const fc::feprep::BuildResult& r, const std::string& out) {
  const auto& b = r.body;
  std::printf("fe-prep %s: body '%s' -> %s\n", fc::version(), b.name.c_str(), out.c_str());
  std::string elements;
  if (b.elements.count("triangles")) elements = std::to_string(b.elements.at("triangles").rows()) + " triangles";
  if (b.elements.count("beams"))
    elements += (elements.empty() ? "" : ", ") + std::to_string(b.elements.at("beams").rows()) + " beam elements";
  std::printf("  mesh: %ld nodes, %s; %ld DOF, %ld after the reference conditions, %ld rigid modes removed\n",
              b.nodeCount(), elements.empty() ? "imported matrices" : elements.c_str(), r.dofs, r.reduced_dofs,
              r.rigid_removed);
  // Mesh-file bodies: what each region became.
  if (spec.general)
    for (const auto& line : r.regions) std::printf("  region %s\n", line.c_str());
  std::printf("  mass %.6g kg, centre of mass [%.6g, %.6g, %.6g] m\n", b.mass, b.center_of_mass.x(),
              b.center_of_mass.y(), b.center_of_mass.z());
  std::printf("  %-6s %14s\n", "mode", "frequency [Hz]");
  for (long i = 0; i < b.frequencies_hz.size(); ++i) std::printf("  %-6ld %14.6f\n", i + 1, b.frequencies_hz(i));
  for (const auto& it : b.interfaces) {
    if (it.static_error.size() != 6) continue;
    std::printf("  interface %-10s static truncation error (share of the static deflection the %d modes miss):\n"
                "    force x y z %.2e %.2e %.2e, moment x y z %.2e %.2e %.2e (0: held)\n",
                it.name.c_str(), b.modeCount(), it.static_error(0), it.static_error(1), it.static_error(2),
                it.static_error(3), it.static_error(4), it.static_error(5));
  }
  if (!b.reduction.empty()) std::printf("  basis: %s\n", b.reduction.c_str());
  // Which program built it, and why when the serial one handed it over.
  const char* why = std::getenv(fc::feprep::kHandOverVariable);
  std::printf("  solver: %s%s%s\n", fc::feprep::backendName(), why && *why ? "; " : "", why && *why ? why : "");
  for (const auto& s : r.stages) {
    std::printf("  %-11s %8.3f s  (CPU %.3f s, peak RSS %.0f MB)", s.stage.c_str(), s.seconds, s.cpu_seconds, s.peak_rss_mb);
    // The factorisation's own figure (MUMPS's, or CHOLMOD's in the serial program): the share of the peak that is the factor.
    if (s.factorisation_mb > 0) std::printf(" %s factor %.0f MB", s.factor_library.c_str(), s.factorisation_mb);
    std::printf("\n");
  }
  // The body file's write (the shapes transposed and stress data) can set the peak of its own.
  std::printf("  %-11s peak RSS %.0f MB\n", "write", fc::feprep::peakRssMb());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fe-prep: laminated shell and beam models to reduced flexible bodies (flexbody/1 HDF5 files)"};
  std::string input, output;
  bool quiet = false;
  std::string backend = "auto";
  app.add_option("body", input, "body YAML file (keys: see the input reference below)")->required();
  app.add_option("-o,--output", output, "flexible body file to write (HDF5)")->required();
  app.add_flag("-q,--quiet", quiet, "no progress lines on stderr");
  app.add_option("--backend", backend,
                 "linear algebra: auto (the serial program for a body it builds, else fe-prep-mpi), serial "
                 "(one process: MUMPS, ARPACK; no gmsh meshing), petsc (fe-prep-mpi: PETSc/SLEPc, MPI, gmsh)")
      ->check(CLI::IsMember({"auto", "serial", "petsc"}));
  app.set_version_flag("--version", std::string("fe-prep ") + fc::version());
  fc::addInspectOption(app, "fe-prep", [](const std::string& path) { return fc::feprep::fileIO().inspect(path); });
  fc::addInputReferenceFooter(app);
  CLI11_PARSE(app, argc, argv);

  // The serial program hands the run to fe-prep-mpi here when it has more
  // than one rank or --backend petsc asks; the PETSc one starts PETSc/SLEPc.
  fc::feprep::LinearAlgebraRuntime la(argc, argv, backend);
  if (la.failed()) return la.failed();
  // A termination signal removes the temporary being written and exits, on
  // every rank (after PETSc, which installs its own handlers). No partial output.
  fc::installTerminationHandlers("fe-prep", fc::TerminationPolicy::ExitNow);
  const fc::feprep::Comm comm = la.world();
  const int rank = fc::feprep::commRank(comm);
  auto run = [&] {
    // Refuse a bad output path before any computing, not after.
    fc::checkOutputIsNotAnInput(output, {input});
    if (rank == 0) fc::checkOutputWritable(output);
    fc::feprep::requireFileIO();
    // Each stage is named for an out-of-memory message (common/memory.h);
    // buildFlexBody's progress bars name its own (meshing, assembly, eigen-solve).
    std::optional<fc::StageScope> stage(std::in_place, "reading the input");
    const fc::feprep::BodySpec spec = fc::feprep::readBodySpec(input);
    // A body the serial program does not build goes to fe-prep-mpi now, before any work.
    la.handOverIfNeeded(spec);
    fc::checkOutputIsNotAnInput(output, spec.input_files);
    fc::checkOutputIsNotAnInput(output, fc::inputFilesRead());
    fc::feprep::BuildOptions opt;
    opt.quiet = quiet;
    stage.emplace("building the body");
    const fc::feprep::BuildResult r = fc::feprep::buildFlexBody(comm, spec, opt);
    stage.emplace("writing " + output);
    if (rank == 0) {
      fc::Provenance prov;
      prov.inputs_sha256 = fc::sha256Files(spec.input_files);
      // The ParaView view is staged first and renamed after the .h5: a full
      // disk leaves the previous pair, never a new .h5 beside an old view.
      fc::StagedFile view(fc::feprep::xdmfPathFor(output), fc::feprep::bodyXdmf(output, r.body));
      // The serial program loads HDF5 only now, with the factorisations freed.
      fc::feprep::loadFileIOForWrite();
      fc::feprep::fileIO().write_body(output, r.body, fc::computeInertiaInvariants(r.body), prov);
      view.commit();
      printSummary(spec, r, output);
    }
    return 0;
  };
  // Every rank reads the same input and fails the same way: only rank 0 speaks,
  // so that a bad input gives one message under mpirun too.
  int rc;
  if (rank == 0) {
    rc = fc::guardedMain("fe-prep", run);
  } else {
    try {
      rc = run();
    } catch (const fc::InputError&) {
      rc = 2;
    } catch (const std::exception&) {
      rc = 1;
    }
  }
  return rc;
}
