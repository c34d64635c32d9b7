#include "fe-prep/import/matrix_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>

#include "common/files.h"
#include "common/input.h"

namespace fc::feprep {
namespace {

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  throw InputError(file, line, 0, "", what);
}

std::ifstream openText(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, 0, "cannot open the file");
  return in;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// Fields separated by blanks and/or commas.
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',' || c == ' ' || c == '\t' || c == '\r') {
      if (!cur.empty()) out.push_back(cur), cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

// Comma-separated fields, empty ones kept (Abaqus data lines).
std::vector<std::string> commaFields(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',') out.push_back(trim(cur)), cur.clear();
    else cur += c;
  }
  out.push_back(trim(cur));
  while (!out.empty() && out.back().empty()) out.pop_back();  // a trailing comma continues nothing here
  return out;
}

std::string_view trimView(std::string_view s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string_view::npos) return {};
  const auto b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

// Fields separated by blanks and/or commas, as views into `line` (no copies:
// the matrix readers split ~4e7 lines at 1e6 DOF). Stores the first `cap`,
// returns how many there are.
std::size_t splitFields(std::string_view line, std::string_view* out, std::size_t cap) {
  std::size_t count = 0, i = 0;
  const std::size_t n = line.size();
  auto sep = [](char c) { return c == ',' || c == ' ' || c == '\t' || c == '\r'; };
  while (i < n) {
    while (i < n && sep(line[i])) ++i;
    if (i == n) break;
    const std::size_t a = i;
    while (i < n && !sep(line[i])) ++i;
    if (count < cap) out[count] = line.substr(a, i - a);
    ++count;
  }
  return count;
}

long toLong(std::string_view s, const std::string& file, int line, const std::string& what) {
  std::string_view t = s;
  if (t.size() > 1 && t[0] == '+') t.remove_prefix(1);
  long v = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec == std::errc() && r.ptr == t.data() + t.size() && !t.empty()) return v;
  fail(file, line, "expected " + what + " (an integer), got '" + std::string(s) + "'");
}

double toDouble(std::string_view s, const std::string& file, int line, const std::string& what) {
  std::string_view t = s;
  if (t.size() > 1 && t[0] == '+') t.remove_prefix(1);
  // Fortran exponents (1.0D+03) as some codes write them.
  std::string fortran;
  if (t.find_first_of("dD") != std::string_view::npos) {
    fortran.assign(t);
    for (char& c : fortran)
      if (c == 'd' || c == 'D') c = 'e';
    t = fortran;
  }
  double v = 0.0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec == std::errc() && r.ptr == t.data() + t.size() && !t.empty() && std::isfinite(v)) return v;
  fail(file, line, "expected " + what + " (a finite number), got '" + std::string(s) + "'");
}

// An index as the 32-bit one the sparse matrices store.
int toIndex(long v, const std::string& file, int line) {
  if (v > std::numeric_limits<int>::max() || v < std::numeric_limits<int>::min())
    fail(file, line, "index " + std::to_string(v) + " beyond the 2^31 rows a matrix may have here");
  return static_cast<int>(v);
}

// Lines in a file: a bound on its entries, so that they are reserved once
// (a growing vector would hold twice their size while it moves them).
std::size_t countLines(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return 0;
  std::vector<char> buf(1 << 20);
  std::size_t lines = 1, got = 0;
  while ((got = std::fread(buf.data(), 1, buf.size(), f)) > 0) lines += static_cast<std::size_t>(std::count(buf.begin(), buf.begin() + static_cast<long>(got), '\n'));
  std::fclose(f);
  return lines;
}

bool blankOrComment(std::string_view t) { return t.empty() || t[0] == '#' || t[0] == '%' || t.rfind("**", 0) == 0; }

// Base of triplet indices from their range and the DOF count (see readTripletMatrix).
void decideBase(StoredMatrix& m, long dof_count, long lo, long hi, int lo_line, int hi_line) {
  if (m.entries.empty()) fail(m.file, 0, "expected matrix entries \"row col value\", found none");
  if (lo < 0) fail(m.file, lo_line, "negative index " + std::to_string(lo));
  const bool zero = lo == 0, one = hi == dof_count;
  if (zero && one)
    fail(m.file, hi_line, "indices run from 0 to " + std::to_string(hi) + ": " + std::to_string(hi + 1) +
                              " rows, but the DOF list has " + std::to_string(dof_count));
  if (hi > dof_count)
    fail(m.file, hi_line, "index " + std::to_string(hi) + " beyond the " + std::to_string(dof_count) +
                              " rows of the DOF list (a DOF list that does not match the matrix)");
  if (!zero && !one)
    fail(m.file, lo_line, "indices run from " + std::to_string(lo) + " to " + std::to_string(hi) + " for " +
                              std::to_string(dof_count) + " DOF: neither the first (0-based) nor the last (1-based) "
                              "row is present, so the base cannot be told; every diagonal entry must be given");
  m.indexing = zero ? "zero-based" : "one-based";
  if (one)
    for (auto& e : m.entries) --e.row, --e.col;
}

// *KEYWORD, PARAM=VALUE, ... -> keyword (upper case) and parameters.
std::string keywordOf(const std::string& t, std::map<std::string, std::string>& params) {
  const std::vector<std::string> parts = commaFields(t.substr(1));
  params.clear();
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const auto eq = parts[i].find('=');
    if (eq == std::string::npos) params[upper(trim(parts[i]))] = "";
    else params[upper(trim(parts[i].substr(0, eq)))] = trim(parts[i].substr(eq + 1));
  }
  return parts.empty() ? std::string() : upper(trim(parts[0]));
}

// Nodes per element of the continuum (3-DOF) and structural (6-DOF) types an .inp may hold.
int solidNodeCount(const std::string& type) {
  static const std::map<std::string, int> n = {{"C3D4", 4},   {"C3D10", 10}, {"C3D10T", 10}, {"C3D6", 6},
                                               {"C3D15", 15}, {"C3D8", 8},   {"C3D8R", 8},   {"C3D8I", 8},
                                               {"C3D20", 20}, {"C3D20R", 20}};
  auto it = n.find(type);
  return it == n.end() ? 0 : it->second;
}
int structuralNodeCount(const std::string& type) {
  static const std::map<std::string, int> n = {{"S3", 3}, {"S3R", 3}, {"S4", 4}, {"S4R", 4}, {"S6", 6},
                                               {"S8", 8}, {"S8R", 8}, {"B31", 2}, {"B32", 3}, {"B32R", 3},
                                               {"B31R", 2}};
  auto it = n.find(type);
  return it == n.end() ? 0 : it->second;
}

void readInp(const std::string& path, NodeTable& t, std::set<std::string>& visited) {
  if (!visited.insert(path).second) fail(path, 0, "is included twice (an *INCLUDE cycle?)");
  std::ifstream in = openText(path);
  enum class Block { None, Node, Element, Nset, NsetGenerate, Skip } block = Block::None;
  std::string set_name, elem_type;
  int elem_nodes = 0;
  bool elem_solid = false;
  std::vector<long> pending;  // element labels across continuation lines
  int pending_line = 0;
  std::string raw;
  int line = 0;
  std::map<std::string, std::string> params;
  auto flushElement = [&]() {
    if (pending.empty()) return;
    if (static_cast<int>(pending.size()) != elem_nodes + 1)
      fail(path, pending_line, "a " + elem_type + " element needs its label and " + std::to_string(elem_nodes) +
                                   " nodes, got " + std::to_string(pending.size()) + " numbers");
    auto& dst = elem_solid ? t.solid_nodes : t.structural_nodes;
    dst.insert(dst.end(), pending.begin() + 1, pending.end());
    if (elem_solid) t.solid_elements.push_back({elem_type, std::vector<long>(pending.begin() + 1, pending.end())});
    ++t.element_counts[elem_type];
    pending.clear();
  };
  while (std::getline(in, raw)) {
    ++line;
    const std::string s = trim(raw);
    if (s.empty() || s.rfind("**", 0) == 0) continue;
    if (s[0] == '*') {
      flushElement();
      const std::string kw = keywordOf(s, params);
      block = Block::Skip;
      if (kw == "NODE") {
        block = Block::Node;
        set_name = params.count("NSET") ? upper(params["NSET"]) : "";
      } else if (kw == "ELEMENT") {
        elem_type = upper(params["TYPE"]);
        elem_nodes = solidNodeCount(elem_type);
        elem_solid = elem_nodes > 0;
        if (!elem_solid) elem_nodes = structuralNodeCount(elem_type);
        if (elem_nodes == 0)
          fail(path, line, "element type '" + elem_type + "' is not one the import knows: expected a solid (C3D4, C3D6, C3D8, C3D8R, "
                           "C3D8I, C3D10, C3D15, C3D20, C3D20R) or a shell/beam (S3, S4, S4R, S6, S8, S8R, B31, B32)");
        block = Block::Element;
      } else if (kw == "NSET") {
        set_name = upper(params["NSET"]);
        if (set_name.empty()) fail(path, line, "*NSET without NSET=NAME");
        block = params.count("GENERATE") ? Block::NsetGenerate : Block::Nset;
        t.sets[set_name];
      } else if (kw == "INCLUDE") {
        const std::string inc = params["INPUT"];
        if (inc.empty()) fail(path, line, "*INCLUDE without INPUT=FILE");
        readInp(resolveRelativeTo(path, inc), t, visited);
      }
      continue;
    }
    switch (block) {
      case Block::Node: {
        const auto f = commaFields(s);
        if (f.size() < 3 || f.size() > 4) fail(path, line, "expected a node line 'label, x, y, z'");
        const long id = toLong(f[0], path, line, "a node label");
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (std::size_t k = 1; k < f.size(); ++k) x(static_cast<long>(k) - 1) = toDouble(f[k], path, line, "a coordinate");
        if (t.coordinates.count(id)) fail(path, line, "node " + std::to_string(id) + " defined again (first at line " + std::to_string(t.line[id]) + ")");
        t.coordinates[id] = x;
        t.line[id] = line;
        if (!set_name.empty()) t.sets[set_name].push_back(id);
        break;
      }
      case Block::Element: {
        if (pending.empty()) pending_line = line;
        for (const auto& f : commaFields(s)) pending.push_back(toLong(f, path, line, "an element or node label"));
        // Abaqus continues an element on the next line when the line ends with a comma.
        if (s.back() != ',') flushElement();
        break;
      }
      case Block::Nset:
        for (const auto& f : commaFields(s)) {
          if (f.empty()) continue;
          if (!std::isdigit(static_cast<unsigned char>(f[0])) && f[0] != '-') {
            auto it = t.sets.find(upper(f));
            if (it == t.sets.end()) fail(path, line, "set '" + f + "' used before it is defined");
            auto copy = it->second;
            t.sets[set_name].insert(t.sets[set_name].end(), copy.begin(), copy.end());
          } else {
            t.sets[set_name].push_back(toLong(f, path, line, "a node label"));
          }
        }
        break;
      case Block::NsetGenerate: {
        const auto f = commaFields(s);
        if (f.size() < 2 || f.size() > 3) fail(path, line, "expected 'first, last[, step]' after *NSET, GENERATE");
        const long a = toLong(f[0], path, line, "a first label"), b = toLong(f[1], path, line, "a last label");
        const long step = f.size() == 3 ? toLong(f[2], path, line, "a step") : 1;
        if (step <= 0 || b < a) fail(path, line, "expected first <= last and a positive step");
        for (long k = a; k <= b; k += step) t.sets[set_name].push_back(k);
        break;
      }
      default:
        break;
    }
  }
  flushElement();
}

}  // namespace

StoredMatrix readMatrixMarket(const std::string& path) {
  std::ifstream in = openText(path);
  StoredMatrix m;
  m.file = path;
  m.indexing = "one-based";
  std::string raw;
  int line = 0;
  if (!std::getline(in, raw)) fail(path, 1, "empty file; expected a %%MatrixMarket header");
  ++line;
  const std::vector<std::string> h = fields(raw);
  if (h.size() != 5 || h[0] != "%%MatrixMarket")
    fail(path, 1, "expected the header '%%MatrixMarket matrix coordinate real general|symmetric'");
  if (upper(h[1]) != "MATRIX" || upper(h[2]) != "COORDINATE")
    fail(path, 1, "expected a sparse 'matrix coordinate' file, got '" + h[1] + " " + h[2] + "'");
  if (upper(h[3]) != "REAL" && upper(h[3]) != "DOUBLE" && upper(h[3]) != "INTEGER")
    fail(path, 1, "expected real entries, got '" + h[3] + "'");
  const std::string sym = upper(h[4]);
  if (sym == "SYMMETRIC") m.declared_symmetric = true;
  else if (sym != "GENERAL") fail(path, 1, "expected general or symmetric storage, got '" + h[4] + "'");
  long declared = -1;
  std::string_view f[4];
  while (std::getline(in, raw)) {
    ++line;
    const std::string_view s = trimView(raw);
    if (s.empty() || s[0] == '%') continue;
    const std::size_t nf = splitFields(s, f, 4);
    if (declared < 0) {
      if (nf != 3) fail(path, line, "expected the size line 'rows columns entries'");
      const long r = toLong(f[0], path, line, "a row count"), c = toLong(f[1], path, line, "a column count");
      declared = toLong(f[2], path, line, "an entry count");
      if (r != c || r <= 0) fail(path, line, "expected a square matrix, got " + std::string(f[0]) + " x " + std::string(f[1]));
      if (declared < 0) fail(path, line, "expected a non-negative entry count");
      m.size = r;
      // Reserved once, up to the file's lines: the count is checked against the entries read, not trusted for memory.
      m.entries.reserve(std::min(static_cast<std::size_t>(declared), countLines(path)));
      continue;
    }
    if (nf != 3) fail(path, line, "expected an entry 'row column value'");
    const long r = toLong(f[0], path, line, "a row index") - 1, c = toLong(f[1], path, line, "a column index") - 1;
    const double v = toDouble(f[2], path, line, "a value");
    if (r < 0 || c < 0) fail(path, line, "Matrix Market indices are one-based; found an index 0 or below");
    if (r >= m.size || c >= m.size)
      fail(path, line, "index beyond the " + std::to_string(m.size) + " rows the size line states");
    if (m.declared_symmetric && c > r)
      fail(path, line, "a 'symmetric' Matrix Market file stores the lower triangle; this entry is above the diagonal");
    m.add({toIndex(r, path, line), toIndex(c, path, line), v}, line);
  }
  if (declared < 0) fail(path, line, "missing the size line 'rows columns entries'");
  if (static_cast<long>(m.entries.size()) != declared)
    fail(path, line, "the size line states " + std::to_string(declared) + " entries, the file holds " +
                         std::to_string(m.entries.size()) + " (truncated?)");
  return m;
}

StoredMatrix readTripletMatrix(const std::string& path, long dof_count) {
  std::ifstream in = openText(path);
  StoredMatrix m;
  m.file = path;
  m.entries.reserve(countLines(path));
  std::string raw;
  int line = 0, lo_line = 0, hi_line = 0;
  long lo = std::numeric_limits<long>::max(), hi = std::numeric_limits<long>::min();
  std::string_view f[4];
  while (std::getline(in, raw)) {
    ++line;
    const std::string_view s = trimView(raw);
    if (blankOrComment(s)) continue;
    const std::size_t nf = splitFields(s, f, 4);
    if (nf != 3) fail(path, line, "expected an entry 'row col value', got " + std::to_string(nf) + " fields");
    const long r = toLong(f[0], path, line, "a row index"), c = toLong(f[1], path, line, "a column index");
    const double v = toDouble(f[2], path, line, "a value");
    if (std::min(r, c) < lo) lo = std::min(r, c), lo_line = line;
    if (std::max(r, c) > hi) hi = std::max(r, c), hi_line = line;
    m.add({toIndex(r, path, line), toIndex(c, path, line), v}, line);
  }
  decideBase(m, dof_count, lo, hi, lo_line, hi_line);
  return m;
}

AbaqusMatrix readAbaqusMatrix(const std::string& path, long dof_count) {
  std::ifstream in = openText(path);
  AbaqusMatrix out;
  StoredMatrix& m = out.matrix;
  m.file = path;
  // The five-column form names DOF by (node, dof): a key node * 8 + dof per
  // end, numbered once all are known.
  struct Raw {
    long a = 0, b = 0;  // node * 8 + dof
    double v = 0.0;
  };
  std::vector<Raw> five;
  std::vector<int> five_line;
  std::string raw;
  int line = 0, lo_line = 0, hi_line = 0;
  long lo = std::numeric_limits<long>::max(), hi = std::numeric_limits<long>::min();
  int width = 0;
  std::string_view f[6];
  while (std::getline(in, raw)) {
    ++line;
    const std::string_view s = trimView(raw);
    if (s.empty() || s[0] == '*' || s[0] == '#') continue;
    const std::size_t nf = splitFields(s, f, 6);
    if (width == 0) {
      if (nf != 5 && nf != 3)
        fail(path, line, "expected 'node, dof, node, dof, value' or 'row, column, value', got " + std::to_string(nf) + " fields");
      width = static_cast<int>(nf);
      if (width == 5) {
        five.reserve(countLines(path));
        five_line.reserve(five.capacity());
      } else {
        m.entries.reserve(countLines(path));
      }
    } else if (static_cast<int>(nf) != width) {
      fail(path, line, "expected " + std::to_string(width) + " fields as on the first entry line, got " + std::to_string(nf));
    }
    if (width == 5) {
      const long n1 = toLong(f[0], path, line, "a node label"), d1 = toLong(f[1], path, line, "a DOF 1..6");
      const long n2 = toLong(f[2], path, line, "a node label"), d2 = toLong(f[3], path, line, "a DOF 1..6");
      const double v = toDouble(f[4], path, line, "a value");
      for (long n : {n1, n2})
        if (n <= 0)
          fail(path, line, "node label " + std::to_string(n) + ": Abaqus writes its internal nodes (the Lagrange "
                           "multipliers of constraints: MPCs, couplings, connectors) with labels below 1; they are not "
                           "structural DOF and are not imported (export the model without those constraints and give them "
                           "as fe-prep interfaces or reference conditions)");
      for (long d : {d1, d2})
        if (d < 1 || d > 6)
          fail(path, line, "DOF " + std::to_string(d) + " is not a structural DOF 1..6 (Lagrange multipliers, "
                           "temperatures and internal DOF are not imported)");
      five.push_back({8 * n1 + d1, 8 * n2 + d2, v});
      five_line.push_back(line);
    } else {
      const long r = toLong(f[0], path, line, "a row index"), c = toLong(f[1], path, line, "a column index");
      const double v = toDouble(f[2], path, line, "a value");
      if (std::min(r, c) < lo) lo = std::min(r, c), lo_line = line;
      if (std::max(r, c) > hi) hi = std::max(r, c), hi_line = line;
      m.add({toIndex(r, path, line), toIndex(c, path, line), v}, line);
    }
  }
  if (width == 3) {
    if (dof_count <= 0) fail(path, lo_line, "a 'row, column, value' matrix needs a dofs: file naming each row's node and DOF");
    decideBase(m, dof_count, lo, hi, lo_line, hi_line);
    return out;
  }
  if (five.empty()) fail(path, line, "no matrix entries found");
  // The DOF list: every (node, dof) the entries name, ascending; each at the first line naming it.
  std::vector<long> keys;
  keys.reserve(2 * five.size());
  for (const Raw& r : five) keys.push_back(r.a), keys.push_back(r.b);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  keys.shrink_to_fit();
  auto indexOf = [&](long key) { return static_cast<long>(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin()); };
  std::vector<int> first_line(keys.size(), 0);
  m.entries.reserve(five.size());
  for (std::size_t k = 0; k < five.size(); ++k) {
    const long i = indexOf(five[k].a), j = indexOf(five[k].b);
    for (long x : {i, j})
      if (!first_line[static_cast<std::size_t>(x)]) first_line[static_cast<std::size_t>(x)] = five_line[k];
    m.add({toIndex(i, path, five_line[k]), toIndex(j, path, five_line[k]), five[k].v}, five_line[k]);
  }
  out.dofs.file = path;
  out.dofs.dofs.reserve(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i)
    out.dofs.dofs.push_back({keys[i] / 8, static_cast<int>(keys[i] % 8), first_line[i]});
  m.size = static_cast<long>(keys.size());
  m.indexing = "node and DOF labels";
  return out;
}

DofList readDofList(const std::string& path) {
  std::ifstream in = openText(path);
  DofList out;
  out.file = path;
  std::string raw;
  int line = 0;
  std::map<std::pair<long, int>, int> seen;
  while (std::getline(in, raw)) {
    ++line;
    std::string s = trim(raw);
    if (blankOrComment(s)) continue;
    std::vector<std::string> f = fields(s);
    if (f.size() == 1) {  // CalculiX: node.dof
      const auto dot = f[0].find('.');
      if (dot == std::string::npos) fail(path, line, "expected 'node dof' or 'node.dof', got '" + s + "'");
      f = {f[0].substr(0, dot), f[0].substr(dot + 1)};
    }
    if (f.size() != 2) fail(path, line, "expected 'node dof' or 'node.dof', got '" + s + "'");
    NodeDof d{toLong(f[0], path, line, "a node label"), static_cast<int>(toLong(f[1], path, line, "a DOF 1..6")), line};
    if (d.dof == 0 || d.dof > 6)
      fail(path, line, "DOF " + f[1] + " is not a structural DOF 1..6 (CalculiX writes 0 for temperatures, "
                       "above 6 for other fields; not imported)");
    if (d.dof < 0) fail(path, line, "DOF " + f[1] + " is negative");
    auto [it, fresh] = seen.emplace(std::make_pair(d.node, d.dof), line);
    if (!fresh)
      fail(path, line, "node " + std::to_string(d.node) + " DOF " + std::to_string(d.dof) + " listed again (first at line " +
                           std::to_string(it->second) + "); CalculiX writes this for beam and shell elements (B31, B32, "
                           "S3..S8), which it expands into bricks: it names every brick node by its parent node, so the "
                           "rows have no coordinates and are not imported (docs/file-formats.md, \"Imported matrices\")");
    out.dofs.push_back(d);
  }
  if (out.dofs.empty()) fail(path, line, "no DOF lines found; expected 'node dof' per matrix row");
  return out;
}

NodeTable readNodeTable(const std::string& path) {
  NodeTable t;
  t.file = path;
  std::ifstream in = openText(path);
  std::string raw;
  bool keywords = false;
  while (std::getline(in, raw)) {
    const std::string s = trim(raw);
    if (!s.empty() && s[0] == '*') {
      keywords = true;
      break;
    }
  }
  if (keywords) {
    std::set<std::string> visited;
    readInp(path, t, visited);
    if (t.coordinates.empty()) fail(path, 0, "no *NODE block found");
  } else {
    in.clear();
    in.seekg(0);
    int line = 0;
    while (std::getline(in, raw)) {
      ++line;
      const std::string s = trim(raw);
      if (blankOrComment(s)) continue;
      const auto f = fields(s);
      if (f.size() != 4) fail(path, line, "expected a node line 'label x y z'");
      const long id = toLong(f[0], path, line, "a node label");
      if (t.coordinates.count(id)) fail(path, line, "node " + std::to_string(id) + " defined again (first at line " + std::to_string(t.line[id]) + ")");
      t.coordinates[id] = Eigen::Vector3d(toDouble(f[1], path, line, "x"), toDouble(f[2], path, line, "y"),
                                          toDouble(f[3], path, line, "z"));
      t.line[id] = line;
    }
    if (t.coordinates.empty()) fail(path, line, "no node lines 'label x y z' found");
  }
  for (auto* v : {&t.solid_nodes, &t.structural_nodes}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  return t;
}

int StoredMatrix::lineOf(long k) const {
  auto it = std::upper_bound(line_runs.begin(), line_runs.end(), k,
                             [](long v, const std::pair<long, int>& r) { return v < r.first; });
  if (it == line_runs.begin()) return 0;
  --it;
  return it->second + static_cast<int>(k - it->first);
}

void StoredMatrix::add(const MatrixEntry& e, int line) {
  const long k = static_cast<long>(entries.size());
  if (line_runs.empty() || line_runs.back().second + (k - line_runs.back().first) != line) line_runs.emplace_back(k, line);
  entries.push_back(e);
}

Eigen::SparseMatrix<double> symmetricLowerTriangle(const StoredMatrix& m, long n, const std::string& name,
                                                   const DofList& dofs, std::string* storage) {
  auto dofName = [&](long i) {
    if (i >= 0 && i < static_cast<long>(dofs.dofs.size()))
      return "row " + std::to_string(i + 1) + " (node " + std::to_string(dofs.dofs[static_cast<std::size_t>(i)].node) +
             " DOF " + std::to_string(dofs.dofs[static_cast<std::size_t>(i)].dof) + ")";
    return "row " + std::to_string(i + 1);
  };
  if (m.size >= 0 && m.size != n)
    fail(m.file, 0, "the " + name + " matrix has " + std::to_string(m.size) + " rows but the DOF list " + dofs.file +
                        " has " + std::to_string(n) + " (a DOF list that does not match the matrix)");
  const long ne = static_cast<long>(m.entries.size());
  if (ne >= std::numeric_limits<int>::max())
    fail(m.file, 0, "the " + name + " matrix stores " + std::to_string(ne) + " entries; at most 2^31 - 1 are supported");
  // The storage, the diagonal and which rows carry anything, in one pass.
  long upper_n = 0, lower_n = 0;
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(n);
  std::vector<char> has_diag(static_cast<std::size_t>(n), 0), has_row(static_cast<std::size_t>(n), 0);
  for (long k = 0; k < ne; ++k) {
    const MatrixEntry& e = m.entries[static_cast<std::size_t>(k)];
    if (e.row < 0 || e.col < 0 || e.row >= n || e.col >= n)
      fail(m.file, m.lineOf(k), "index outside the " + std::to_string(n) + " rows of the DOF list " + dofs.file);
    if (e.row < e.col) ++upper_n;
    if (e.row > e.col) ++lower_n;
    if (e.row == e.col) diag(e.row) = e.value, has_diag[static_cast<std::size_t>(e.row)] = 1;
    if (e.value != 0.0) has_row[static_cast<std::size_t>(e.row)] = has_row[static_cast<std::size_t>(e.col)] = 1;
  }
  const bool both = upper_n > 0 && lower_n > 0;
  if (storage) *storage = both ? "both triangles" : upper_n > 0 ? "upper triangle" : lower_n > 0 ? "lower triangle" : "diagonal";
  // The lines of the entries at (r, c), for messages (a scan, on the way to an error only).
  auto linesOf = [&](long r, long c) {
    std::vector<int> lines;
    for (long k = 0; k < ne; ++k)
      if (m.entries[static_cast<std::size_t>(k)].row == r && m.entries[static_cast<std::size_t>(k)].col == c)
        lines.push_back(m.lineOf(k));
    return lines;
  };

  // The compressed matrix, filled in place: column j of the lower triangle is
  // row j of the upper one, so one triangle's entries go to column min(r, c)
  // at row max(r, c). With both triangles stored, each entry goes to its own
  // row r (column r, row c: the transpose) until the mirrors are compared, and
  // the upper triangle's copies are dropped afterwards.
  auto outerOf = [&](const MatrixEntry& e) { return both ? e.row : std::min(e.row, e.col); };
  auto innerOf = [&](const MatrixEntry& e) { return both ? e.col : std::max(e.row, e.col); };
  Eigen::SparseMatrix<double> A(n, n);
  A.resizeNonZeros(ne);
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* val = A.valuePtr();
  std::fill(outer, outer + n + 1, 0);
  for (const MatrixEntry& e : m.entries) ++outer[outerOf(e) + 1];
  for (long j = 0; j < n; ++j) outer[j + 1] += outer[j];
  {
    std::vector<int> next(outer, outer + n);
    for (const MatrixEntry& e : m.entries) {
      const int p = next[static_cast<std::size_t>(outerOf(e))]++;
      inner[p] = innerOf(e);
      val[p] = e.value;
    }
  }
  std::vector<std::pair<int, double>> work;
  for (long j = 0; j < n; ++j) {
    const int a = outer[j], b = outer[j + 1];
    if (std::is_sorted(inner + a, inner + b)) continue;
    work.clear();
    for (int p = a; p < b; ++p) work.emplace_back(inner[p], val[p]);
    std::stable_sort(work.begin(), work.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (int p = a; p < b; ++p) inner[p] = work[static_cast<std::size_t>(p - a)].first, val[p] = work[static_cast<std::size_t>(p - a)].second;
  }
  // Duplicates are neighbours now.
  for (long j = 0; j < n; ++j)
    for (int p = outer[j] + 1; p < outer[j + 1]; ++p) {
      if (inner[p] != inner[p - 1]) continue;
      // The entry as the file wrote it: (j, inner) or, one triangle stored, possibly its transpose.
      long r = j, c = inner[p];
      std::vector<int> lines = linesOf(r, c);
      if (lines.size() < 2 && r != c) std::swap(r, c), lines = linesOf(r, c);
      const int l1 = lines.size() > 0 ? lines[0] : 0, l2 = lines.size() > 1 ? lines[1] : 0;
      fail(m.file, l2,
           "entry (" + std::to_string(r + 1) + ", " + std::to_string(c + 1) + ") given twice (lines " + std::to_string(l1) +
               " and " + std::to_string(l2) + "): duplicated entries are refused, not summed");
    }
  for (long i = 0; i < n; ++i) {
    if (has_diag[static_cast<std::size_t>(i)]) continue;
    const bool rotation = dofs.dofs[static_cast<std::size_t>(i)].dof > 3;
    if (name == "mass" && rotation && !has_row[static_cast<std::size_t>(i)]) continue;  // a massless rotation
    fail(m.file, 0, "the " + name + " matrix has no diagonal entry for " + dofName(i) +
                        (name == "mass" ? " (a translation, or a rotation coupled to others, needs its diagonal)" : ""));
  }
  if (both) {
    // Row r's entry at column c, or nullptr.
    auto find = [&](long r, long c) -> const double* {
      const int* first = inner + outer[r];
      const int* last = inner + outer[r + 1];
      const int* it = std::lower_bound(first, last, static_cast<int>(c));
      return it != last && *it == c ? val + (it - inner) : nullptr;
    };
    for (long r = 0; r < n; ++r)
      for (int p = outer[r]; p < outer[r + 1] && inner[p] < r; ++p) {
        const long c = inner[p];
        const double* mirror = find(c, r);
        const double mv = mirror ? *mirror : 0.0;
        const double scale = std::sqrt(std::abs(diag(r) * diag(c)));
        if (std::abs(mv - val[p]) > 1e-9 * std::max({scale, std::abs(val[p]), std::abs(mv)})) {
          const std::vector<int> here = linesOf(r, c);
          fail(m.file, here.empty() ? 0 : here[0],
               "the " + name + " matrix is not symmetric: entry (" + std::to_string(r + 1) + ", " + std::to_string(c + 1) +
                   ") = " + std::to_string(val[p]) + " but (" + std::to_string(c + 1) + ", " + std::to_string(r + 1) +
                   ") = " + std::to_string(mv) +
                   (mirror ? " (line " + std::to_string(linesOf(c, r).front()) + ")" : " (not given)"));
        }
      }
    // Upper entries whose lower mirror is absent are asymmetric too.
    for (long r = 0; r < n; ++r)
      for (int p = outer[r]; p < outer[r + 1]; ++p) {
        const long c = inner[p];
        if (c <= r || val[p] == 0.0 || find(c, r)) continue;
        const std::vector<int> here = linesOf(r, c);
        fail(m.file, here.empty() ? 0 : here[0],
             "the " + name + " matrix is not symmetric: entry (" + std::to_string(r + 1) + ", " + std::to_string(c + 1) +
                 ") has no mirror (" + std::to_string(c + 1) + ", " + std::to_string(r + 1) +
                 ") though the file stores both triangles");
      }
    // Keep one triangle: row r's entries at columns c >= r (column r of the lower triangle).
    int w = 0, start = outer[0];
    for (long r = 0; r < n; ++r) {
      const int end = outer[r + 1];
      outer[r] = w;
      for (int p = start; p < end; ++p)
        if (inner[p] >= r) inner[w] = inner[p], val[w] = val[p], ++w;
      start = end;
    }
    outer[n] = w;
    A.data().resize(w);
    A.data().squeeze();
  }
  A.prune(0.0);
  return A;
}

Eigen::SparseMatrix<double> symmetricMatrix(const StoredMatrix& m, long n, const std::string& name,
                                            const DofList& dofs, std::string* storage) {
  const Eigen::SparseMatrix<double> lower = symmetricLowerTriangle(m, n, name, dofs, storage);
  Eigen::SparseMatrix<double> full(n, n);
  full = lower.selfadjointView<Eigen::Lower>();
  return full;
}

}  // namespace fc::feprep
