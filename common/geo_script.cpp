#include "common/geo_script.h"

#include <algorithm>
#include <cctype>
#include <exception>
#include <stdexcept>

#include "common/files.h"
#include "common/input.h"

namespace fc {

const std::vector<std::string>& refusedGeoCommands() {
  static const std::vector<std::string> list = {
      // shell and process control
      "System", "SystemCall", "NonBlockingSystemCall", "Exit", "Abort", "Sleep", "OnelabRun",
      // other files: read, write, rename, delete
      "Include", "Merge", "MergeWithBoundingBox", "Save", "Print", "Printf", "CreateDir",
      "DeleteFile", "RenameFile", "Plugin", "Draw", "SetChanged"};
  return list;
}

void checkGmshInput(const std::string& path) {
  auto endsWith = [&](const char* s) {
    const std::string e(s);
    return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
  };
  if (endsWith(".msh")) return;
  if (!endsWith(".geo"))
    throw InputError(path, 0, 0, "", "expected a gmsh .geo or .msh file (other formats are not read)");
  std::string text;
  try {
    text = readTextFile(path);
  } catch (const std::exception& e) {
    throw InputError(path, 0, 0, "", std::string("cannot read the file (") + e.what() + ")");
  }
  const auto& refused = refusedGeoCommands();
  int line = 1, col = 1;
  std::size_t i = 0;
  auto advance = [&]() {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
    ++i;
  };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      while (i < text.size() && text[i] != '\n') advance();
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      advance();
      advance();
      while (i < text.size() && !(text[i] == '*' && i + 1 < text.size() && text[i + 1] == '/')) advance();
      if (i < text.size()) {
        advance();
        advance();
      }
    } else if (c == '"') {
      advance();
      while (i < text.size() && text[i] != '"') {
        if (text[i] == '\\' && i + 1 < text.size()) advance();
        advance();
      }
      if (i < text.size()) advance();
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const int l0 = line, c0 = col;
      std::string word;
      while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) {
        word += text[i];
        advance();
      }
      if (std::find(refused.begin(), refused.end(), word) != refused.end())
        throw InputError(path, l0, c0, "",
                         "the .geo command '" + word +
                             "' is not allowed: flexcomp reads geometry only (shell, file, "
                             "plugin and exit commands are refused); remove it");
    } else {
      advance();
    }
  }
}

}  // namespace fc
