#include "common/geo_script.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <set>
#include <stdexcept>
#include <utility>

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
  if (endsWith(".msh")) return checkMshStructure(path);
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

namespace {

// The lines of an ASCII .msh with their numbers, and a cursor over them.
class MshLines {
 public:
  MshLines(const std::string& path, const std::string& text) : path_(path) {
    std::size_t at = 0;
    int n = 0;
    while (at <= text.size()) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      std::string l = text.substr(at, end - at);
      ++n;
      if (!l.empty() && l.back() == '\r') l.pop_back();
      const auto first = l.find_first_not_of(" \t");
      if (first != std::string::npos) lines_.push_back({n, l.substr(first)});
      if (end == text.size()) break;
      at = end + 1;
    }
  }
  bool done() const { return i_ >= lines_.size(); }
  const std::string& peek() const { return lines_[i_].second; }
  int line() const { return done() ? (lines_.empty() ? 1 : lines_.back().first) : lines_[i_].first; }
  std::string next() {
    if (done()) fail("the file ends early");
    return lines_[i_++].second;
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, line(), 0, "", what); }
  [[noreturn]] void failAt(int line, const std::string& what) const { throw InputError(path_, line, 0, "", what); }

  // The numbers of the next line (at least `want`, at most `most`; -1: any).
  std::vector<double> numbers(std::size_t want, long most, const char* what) {
    const int at = line();
    const std::string l = next();
    std::vector<double> out;
    std::size_t p = 0;
    while (p < l.size()) {
      while (p < l.size() && (l[p] == ' ' || l[p] == '\t')) ++p;
      if (p >= l.size()) break;
      std::size_t q = p;
      while (q < l.size() && l[q] != ' ' && l[q] != '\t') ++q;
      const std::string tok = l.substr(p, q - p);
      char* end = nullptr;
      const double v = std::strtod(tok.c_str(), &end);
      if (end != tok.c_str() + tok.size() || !std::isfinite(v))
        failAt(at, std::string("expected ") + what + ", got '" + tok + "'");
      out.push_back(v);
      p = q;
    }
    if (out.size() < want || (most >= 0 && static_cast<long>(out.size()) > most))
      failAt(at, std::string("expected ") + what + " (" + std::to_string(want) +
                     (most == static_cast<long>(want) ? "" : most < 0 ? " or more" : " to " + std::to_string(most)) +
                     " numbers), got '" + l + "'");
    return out;
  }

 private:
  std::string path_;
  std::vector<std::pair<int, std::string>> lines_;
  std::size_t i_ = 0;
};

long asCount(MshLines& m, double v, int line, const char* what) {
  if (v < 0 || v != std::floor(v) || v > 2e9) m.failAt(line, std::string("expected ") + what + " (a count), got " + std::to_string(v));
  return static_cast<long>(v);
}

// Nodes per element of the types flexcomp's readers meet (gmsh numbering); other
// types: the line's length is not checked here (gmsh and the region reader name them).
int nodesOfType(long type) {
  switch (type) {
    case 1: return 2;   // line
    case 2: return 3;   // triangle
    case 3: return 4;   // quadrangle
    case 4: return 4;   // tetrahedron
    case 5: return 8;   // hexahedron
    case 6: return 6;   // prism
    case 7: return 5;   // pyramid
    case 8: return 3;   // line 3
    case 9: return 6;   // triangle 6
    case 10: return 9;  // quadrangle 9
    case 11: return 10; // tetrahedron 10
    case 15: return 1;  // point
    case 16: return 8;  // quadrangle 8
    default: return -1;
  }
}

}  // namespace

void checkMshStructure(const std::string& path) {
  const std::string text = readTextFile(path);
  MshLines m(path, text);
  if (m.done() || m.peek() != "$MeshFormat") m.fail("expected a gmsh .msh file starting with $MeshFormat");
  m.next();
  const int vline = m.line();
  const std::vector<double> fmt = m.numbers(3, 3, "'version file-type data-size'");
  const double version = fmt[0];
  if (!(version >= 2.0 && version < 3.0) && !(version >= 4.0 && version < 5.0))
    m.failAt(vline, "MSH version " + std::to_string(version).substr(0, 3) + ": gmsh files of version 2.x or 4.x are read");
  if (fmt[1] != 0) return;  // binary: gmsh checks its own blocks
  if (m.next() != "$EndMeshFormat") m.fail("expected $EndMeshFormat");
  std::set<long> nodes;
  bool seen_nodes = false;
  while (!m.done()) {
    const int start = m.line();
    const std::string head = m.next();
    if (head.empty() || head[0] != '$') m.failAt(start, "expected a section ($Nodes, $Elements, ...), got '" + head + "'");
    const std::string name = head.substr(1);
    const std::string end = "$End" + name;
    if (name == "Nodes") {
      seen_nodes = true;
      if (version < 4.0) {
        const long n = asCount(m, m.numbers(1, 1, "the node count")[0], start + 1, "the node count");
        for (long k = 0; k < n; ++k) {
          if (!m.done() && m.peek() == end) m.fail("$Nodes declares " + std::to_string(n) + " nodes, the section holds " + std::to_string(k));
          const int at = m.line();
          const std::vector<double> v = m.numbers(4, 4, "a node line 'number x y z'");
          if (!nodes.insert(static_cast<long>(v[0])).second) m.failAt(at, "node " + std::to_string(static_cast<long>(v[0])) + " given twice");
        }
      } else {
        const int hl = m.line();
        const std::vector<double> h = m.numbers(4, 4, "the $Nodes header 'blocks nodes min-tag max-tag'");
        const long blocks = asCount(m, h[0], hl, "the block count"), total = asCount(m, h[1], hl, "the node count");
        long count = 0;
        for (long b = 0; b < blocks; ++b) {
          const int bl = m.line();
          const std::vector<double> bh = m.numbers(4, 4, "a node block header 'dim entity parametric count'");
          const long n = asCount(m, bh[3], bl, "the block's node count");
          const std::size_t coords = 3 + (bh[2] != 0 ? static_cast<std::size_t>(std::max(0.0, bh[0])) : 0);
          std::vector<int> tag_lines;
          for (long k = 0; k < n; ++k) {
            const int at = m.line();
            const double t = m.numbers(1, 1, "a node number")[0];
            if (!nodes.insert(static_cast<long>(t)).second) m.failAt(at, "node " + std::to_string(static_cast<long>(t)) + " given twice");
          }
          for (long k = 0; k < n; ++k) m.numbers(coords, static_cast<long>(coords), "a node's coordinates 'x y z'");
          count += n;
        }
        if (count != total) m.failAt(hl, "$Nodes declares " + std::to_string(total) + " nodes, its blocks hold " + std::to_string(count));
      }
    } else if (name == "Elements") {
      std::set<long> elements;
      auto element = [&](const std::vector<double>& v, std::size_t first_node, long type, int at) {
        if (!elements.insert(static_cast<long>(v[0])).second)
          m.failAt(at, "element " + std::to_string(static_cast<long>(v[0])) + " given twice");
        const int want = nodesOfType(type);
        if (want > 0 && v.size() - first_node != static_cast<std::size_t>(want))
          m.failAt(at, "element " + std::to_string(static_cast<long>(v[0])) + " of type " + std::to_string(type) + " needs " +
                           std::to_string(want) + " nodes, the line gives " + std::to_string(v.size() - first_node));
        for (std::size_t j = first_node; seen_nodes && j < v.size(); ++j)
          if (!nodes.count(static_cast<long>(v[j])))
            m.failAt(at, "element " + std::to_string(static_cast<long>(v[0])) + " names node " +
                             std::to_string(static_cast<long>(v[j])) + ", which $Nodes does not define");
      };
      if (version < 4.0) {
        const long n = asCount(m, m.numbers(1, 1, "the element count")[0], start + 1, "the element count");
        for (long k = 0; k < n; ++k) {
          if (!m.done() && m.peek() == end)
            m.fail("$Elements declares " + std::to_string(n) + " elements, the section holds " + std::to_string(k));
          const int at = m.line();
          const std::vector<double> v = m.numbers(3, -1, "an element line 'number type tags... nodes...'");
          const long ntags = asCount(m, v[2], at, "the tag count");
          if (v.size() < 3 + static_cast<std::size_t>(ntags) + 1) m.failAt(at, "an element line without nodes");
          element(v, 3 + static_cast<std::size_t>(ntags), static_cast<long>(v[1]), at);
        }
      } else {
        const int hl = m.line();
        const std::vector<double> h = m.numbers(4, 4, "the $Elements header 'blocks elements min-tag max-tag'");
        const long blocks = asCount(m, h[0], hl, "the block count"), total = asCount(m, h[1], hl, "the element count");
        long count = 0;
        for (long b = 0; b < blocks; ++b) {
          const int bl = m.line();
          const std::vector<double> bh = m.numbers(4, 4, "an element block header 'dim entity type count'");
          const long n = asCount(m, bh[3], bl, "the block's element count");
          for (long k = 0; k < n; ++k) {
            const int at = m.line();
            element(m.numbers(2, -1, "an element line 'number nodes...'"), 1, static_cast<long>(bh[2]), at);
          }
          count += n;
        }
        if (count != total) m.failAt(hl, "$Elements declares " + std::to_string(total) + " elements, its blocks hold " + std::to_string(count));
      }
    } else {
      // Other sections ($PhysicalNames, $Entities, $Periodic, ...): read by gmsh; here only their end.
      while (!m.done() && m.peek() != end) {
        if (m.peek().rfind("$End", 0) == 0 || (m.peek()[0] == '$' && m.peek() != head))
          m.fail("expected " + end + " (the " + head + " section begun at line " + std::to_string(start) + " has no end)");
        m.next();
      }
      if (m.done()) m.failAt(start, "the " + head + " section has no " + end);
      m.next();
      continue;
    }
    if (m.done() || m.peek() != end)
      m.fail("expected " + end + (m.done() ? " (the file ends early)" : ", got '" + m.peek() + "': a count that does not match the lines"));
    m.next();
  }
}

}  // namespace fc
