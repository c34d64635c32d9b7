#pragma once
// The common shell of the three executables: uniform error reporting and exit
// codes, and the options every tool shares. Input errors exit 2 with the
// one-line message; other failures exit 1.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace fc {

// Runs body(), turning exceptions into "TOOL: error: message" on stderr.
int guardedMain(const std::string& tool, const std::function<int()>& body);

// `--inspect FILE`: prints what a flexcomp HDF5 file holds (format, provenance,
// summary, datasets) and exits, whatever else the command line says. INSPECT is
// the description (fc::inspectFile, common/inspect.h; fe-prep's serial program
// reaches it through its HDF5 module): passed in, so that this file links no HDF5.
void addInspectOption(CLI::App& app, const std::string& tool,
                      std::function<std::string(const std::string&)> inspect);

// Where the input reference (every YAML key with meaning, unit and default) is:
// P/share/doc/flexcomp/input-reference.md beside an installed tool (P/bin/TOOL),
// docs/input-reference.md of the source tree for a tool run from its build tree.
std::string inputReferencePath();
// `--help` ends naming that page.
void addInputReferenceFooter(CLI::App& app);

}  // namespace fc
