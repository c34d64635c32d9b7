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
// summary, datasets) and exits, whatever else the command line says.
void addInspectOption(CLI::App& app, const std::string& tool);

}  // namespace fc
