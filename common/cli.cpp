#include "common/cli.h"

#include <filesystem>
#include <iostream>

#include "common/termination.h"
#include "common/files.h"
#include "common/h5error.h"
#include "common/input.h"
#include "common/memory.h"

namespace fc {

int guardedMain(const std::string& tool, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << tool << ": error: " << e.what() << "\n";
    return 2;
  } catch (const H5Error& e) {
    std::cerr << tool << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc& e) {
    // Before anything else: a message that needs no more than a few kB.
    std::cerr << tool << ": error: " << outOfMemoryMessage(e, tool) << "\n";
    return 1;
  } catch (...) {
    // Anything else (std::exception, gmsh's std::string...) is one line, never an abort.
    std::cerr << tool << ": error: " << currentExceptionMessage() << "\n";
    return 1;
  }
}

}  // namespace fc

namespace fc {

void addInspectOption(CLI::App& app, const std::string& tool,
                      std::function<std::string(const std::string&)> inspect) {
  app.add_option_function<std::string>(
         "--inspect",
         [tool, inspect](const std::string& path) {
           const int rc = guardedMain(tool, [&]() {
             std::cout << inspect(path);
             return 0;
           });
           if (rc != 0) throw CLI::RuntimeError(rc);
           throw CLI::Success();
         },
         "print what a flexcomp HDF5 file (section, body or results) holds, and exit")
      ->trigger_on_parse();
}

}  // namespace fc

namespace fc {

std::string inputReferencePath() {
  namespace fs = std::filesystem;
  std::error_code ec;
  // PREFIX/bin/TOOL: the prefix is its directory's parent.
  if (const std::string bin = programDirectory(); !bin.empty()) {
    const fs::path installed = fs::path(bin).parent_path().parent_path() / "share/doc/flexcomp/input-reference.md";
    if (fs::exists(installed, ec)) return installed.lexically_normal().string();
  }
  const fs::path source = fs::path(FLEXCOMP_SOURCE_DIR) / "docs/input-reference.md";
  if (fs::exists(source, ec)) return source.string();
  return "share/doc/flexcomp/input-reference.md of the installation";
}

void addInputReferenceFooter(CLI::App& app) {
  app.footer("Every input key, with its meaning, unit and default: " + inputReferencePath());
}

}  // namespace fc
