#pragma once
// The common shell of the three executables: uniform error reporting and exit
// codes. Input errors exit 2 with the one-line message; other failures exit 1.
#include <functional>
#include <string>

namespace fc {

// Runs body(), turning exceptions into "TOOL: error: message" on stderr.
int guardedMain(const std::string& tool, const std::function<int()>& body);

}  // namespace fc
