#include "fe-prep/import/matrix_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

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

long toLong(const std::string& s, const std::string& file, int line, const std::string& what) {
  try {
    std::size_t used = 0;
    const long v = std::stol(s, &used);
    if (used == s.size()) return v;
  } catch (const std::exception&) {
  }
  fail(file, line, "expected " + what + " (an integer), got '" + s + "'");
}

double toDouble(const std::string& s, const std::string& file, int line, const std::string& what) {
  std::string t = s;
  // Fortran exponents (1.0D+03) as some codes write them.
  for (char& c : t)
    if (c == 'd' || c == 'D') c = 'e';
  try {
    std::size_t used = 0;
    const double v = std::stod(t, &used);
    if (used == t.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  fail(file, line, "expected " + what + " (a finite number), got '" + s + "'");
}

bool blankOrComment(const std::string& t) { return t.empty() || t[0] == '#' || t[0] == '%' || t.rfind("**", 0) == 0; }

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
  while (std::getline(in, raw)) {
    ++line;
    const std::string s = trim(raw);
    if (s.empty() || s[0] == '%') continue;
    const auto f = fields(s);
    if (declared < 0) {
      if (f.size() != 3) fail(path, line, "expected the size line 'rows columns entries'");
      const long r = toLong(f[0], path, line, "a row count"), c = toLong(f[1], path, line, "a column count");
      declared = toLong(f[2], path, line, "an entry count");
      if (r != c || r <= 0) fail(path, line, "expected a square matrix, got " + f[0] + " x " + f[1]);
      if (declared < 0) fail(path, line, "expected a non-negative entry count");
      m.size = r;
      // Reserved up to a bound: the count is checked against the entries read, not trusted for memory.
      m.entries.reserve(static_cast<std::size_t>(std::min<long>(declared, 10000000)));
      continue;
    }
    if (f.size() != 3) fail(path, line, "expected an entry 'row column value'");
    MatrixEntry e{toLong(f[0], path, line, "a row index") - 1, toLong(f[1], path, line, "a column index") - 1,
                  toDouble(f[2], path, line, "a value"), line};
    if (e.row < 0 || e.col < 0) fail(path, line, "Matrix Market indices are one-based; found an index 0 or below");
    if (e.row >= m.size || e.col >= m.size)
      fail(path, line, "index beyond the " + std::to_string(m.size) + " rows the size line states");
    if (m.declared_symmetric && e.col > e.row)
      fail(path, line, "a 'symmetric' Matrix Market file stores the lower triangle; this entry is above the diagonal");
    m.entries.push_back(e);
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
  std::string raw;
  int line = 0, lo_line = 0, hi_line = 0;
  long lo = std::numeric_limits<long>::max(), hi = std::numeric_limits<long>::min();
  while (std::getline(in, raw)) {
    ++line;
    const std::string s = trim(raw);
    if (blankOrComment(s)) continue;
    const auto f = fields(s);
    if (f.size() != 3) fail(path, line, "expected an entry 'row col value', got " + std::to_string(f.size()) + " fields");
    MatrixEntry e{toLong(f[0], path, line, "a row index"), toLong(f[1], path, line, "a column index"),
                  toDouble(f[2], path, line, "a value"), line};
    if (std::min(e.row, e.col) < lo) lo = std::min(e.row, e.col), lo_line = line;
    if (std::max(e.row, e.col) > hi) hi = std::max(e.row, e.col), hi_line = line;
    m.entries.push_back(e);
  }
  decideBase(m, dof_count, lo, hi, lo_line, hi_line);
  return m;
}

AbaqusMatrix readAbaqusMatrix(const std::string& path, long dof_count) {
  std::ifstream in = openText(path);
  AbaqusMatrix out;
  StoredMatrix& m = out.matrix;
  m.file = path;
  struct Raw {
    long n1, d1, n2, d2;
    double v;
    int line;
  };
  std::vector<Raw> five;
  std::string raw;
  int line = 0, lo_line = 0, hi_line = 0;
  long lo = std::numeric_limits<long>::max(), hi = std::numeric_limits<long>::min();
  int width = 0;
  while (std::getline(in, raw)) {
    ++line;
    const std::string s = trim(raw);
    if (s.empty() || s[0] == '*' || s[0] == '#') continue;
    const auto f = fields(s);
    if (width == 0) {
      if (f.size() != 5 && f.size() != 3)
        fail(path, line, "expected 'node, dof, node, dof, value' or 'row, column, value', got " + std::to_string(f.size()) + " fields");
      width = static_cast<int>(f.size());
    } else if (static_cast<int>(f.size()) != width) {
      fail(path, line, "expected " + std::to_string(width) + " fields as on the first entry line, got " + std::to_string(f.size()));
    }
    if (width == 5) {
      Raw r{toLong(f[0], path, line, "a node label"), toLong(f[1], path, line, "a DOF 1..6"),
            toLong(f[2], path, line, "a node label"), toLong(f[3], path, line, "a DOF 1..6"),
            toDouble(f[4], path, line, "a value"), line};
      for (long n : {r.n1, r.n2})
        if (n <= 0)
          fail(path, line, "node label " + std::to_string(n) + ": Abaqus writes its internal nodes (the Lagrange "
                           "multipliers of constraints: MPCs, couplings, connectors) with labels below 1; they are not "
                           "structural DOF and are not imported (export the model without those constraints and give them "
                           "as fe-prep interfaces or reference conditions)");
      for (long d : {r.d1, r.d2})
        if (d < 1 || d > 6)
          fail(path, line, "DOF " + std::to_string(d) + " is not a structural DOF 1..6 (Lagrange multipliers, "
                           "temperatures and internal DOF are not imported)");
      five.push_back(r);
    } else {
      MatrixEntry e{toLong(f[0], path, line, "a row index"), toLong(f[1], path, line, "a column index"),
                    toDouble(f[2], path, line, "a value"), line};
      if (std::min(e.row, e.col) < lo) lo = std::min(e.row, e.col), lo_line = line;
      if (std::max(e.row, e.col) > hi) hi = std::max(e.row, e.col), hi_line = line;
      m.entries.push_back(e);
    }
  }
  if (width == 3) {
    if (dof_count <= 0) fail(path, lo_line, "a 'row, column, value' matrix needs a dofs: file naming each row's node and DOF");
    decideBase(m, dof_count, lo, hi, lo_line, hi_line);
    return out;
  }
  if (five.empty()) fail(path, line, "no matrix entries found");
  // The DOF list: every (node, dof) the entries name, ascending.
  std::map<std::pair<long, long>, long> index;
  std::map<std::pair<long, long>, int> first_line;
  for (const Raw& r : five) {
    index[{r.n1, r.d1}] = 0, index[{r.n2, r.d2}] = 0;
    first_line.emplace(std::make_pair(r.n1, r.d1), r.line);
    first_line.emplace(std::make_pair(r.n2, r.d2), r.line);
  }
  long k = 0;
  out.dofs.file = path;
  for (auto& [key, i] : index) {
    i = k++;
    out.dofs.dofs.push_back({key.first, static_cast<int>(key.second), first_line[key]});
  }
  m.size = k;
  m.indexing = "node and DOF labels";
  for (const Raw& r : five) m.entries.push_back({index[{r.n1, r.d1}], index[{r.n2, r.d2}], r.v, r.line});
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

Eigen::SparseMatrix<double> symmetricMatrix(const StoredMatrix& m, long n, const std::string& name,
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
  for (const auto& e : m.entries)
    if (e.row < 0 || e.col < 0 || e.row >= n || e.col >= n)
      fail(m.file, e.line, "index outside the " + std::to_string(n) + " rows of the DOF list " + dofs.file);
  // Sorted copies by position: duplicates are adjacent, mirrors found by search.
  std::vector<const MatrixEntry*> by(m.entries.size());
  for (std::size_t k = 0; k < by.size(); ++k) by[k] = &m.entries[k];
  auto less = [](const MatrixEntry* a, const MatrixEntry* b) { return a->row != b->row ? a->row < b->row : a->col < b->col; };
  std::sort(by.begin(), by.end(), less);
  for (std::size_t k = 1; k < by.size(); ++k)
    if (by[k]->row == by[k - 1]->row && by[k]->col == by[k - 1]->col)
      fail(m.file, std::max(by[k]->line, by[k - 1]->line),
           "entry (" + std::to_string(by[k]->row + 1) + ", " + std::to_string(by[k]->col + 1) + ") given twice (lines " +
               std::to_string(std::min(by[k]->line, by[k - 1]->line)) + " and " + std::to_string(std::max(by[k]->line, by[k - 1]->line)) +
               "): duplicated entries are refused, not summed");
  long upper_n = 0, lower_n = 0;
  Eigen::VectorXd diag = Eigen::VectorXd::Zero(n);
  std::vector<char> has_diag(static_cast<std::size_t>(n), 0), has_row(static_cast<std::size_t>(n), 0);
  for (const auto& e : m.entries) {
    if (e.row < e.col) ++upper_n;
    if (e.row > e.col) ++lower_n;
    if (e.row == e.col) diag(e.row) = e.value, has_diag[static_cast<std::size_t>(e.row)] = 1;
    if (e.value != 0.0) has_row[static_cast<std::size_t>(e.row)] = has_row[static_cast<std::size_t>(e.col)] = 1;
  }
  const bool both = upper_n > 0 && lower_n > 0;
  if (storage) *storage = both ? "both triangles" : upper_n > 0 ? "upper triangle" : lower_n > 0 ? "lower triangle" : "diagonal";
  for (long i = 0; i < n; ++i) {
    if (has_diag[static_cast<std::size_t>(i)]) continue;
    const bool rotation = dofs.dofs[static_cast<std::size_t>(i)].dof > 3;
    if (name == "mass" && rotation && !has_row[static_cast<std::size_t>(i)]) continue;  // a massless rotation
    fail(m.file, 0, "the " + name + " matrix has no diagonal entry for " + dofName(i) +
                        (name == "mass" ? " (a translation, or a rotation coupled to others, needs its diagonal)" : ""));
  }
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(2 * m.entries.size());
  for (const auto& e : m.entries) {
    if (both) {
      if (e.row > e.col) {
        const MatrixEntry key{e.col, e.row, 0.0, 0};
        auto it = std::lower_bound(by.begin(), by.end(), &key, less);
        const double mirror = (it != by.end() && (*it)->row == e.col && (*it)->col == e.row) ? (*it)->value : 0.0;
        const double scale = std::sqrt(std::abs(diag(e.row) * diag(e.col)));
        if (std::abs(mirror - e.value) > 1e-9 * std::max({scale, std::abs(e.value), std::abs(mirror)}))
          fail(m.file, e.line, "the " + name + " matrix is not symmetric: entry (" + std::to_string(e.row + 1) + ", " +
                                   std::to_string(e.col + 1) + ") = " + std::to_string(e.value) + " but (" +
                                   std::to_string(e.col + 1) + ", " + std::to_string(e.row + 1) + ") = " +
                                   std::to_string(mirror) + (it != by.end() && (*it)->row == e.col && (*it)->col == e.row
                                                                 ? " (line " + std::to_string((*it)->line) + ")"
                                                                 : " (not given)"));
      }
      t.emplace_back(e.row, e.col, e.value);
    } else {
      t.emplace_back(e.row, e.col, e.value);
      if (e.row != e.col) t.emplace_back(e.col, e.row, e.value);
    }
  }
  if (both) {
    // Upper entries whose lower mirror is absent are asymmetric too.
    for (const auto& e : m.entries) {
      if (e.row >= e.col || e.value == 0.0) continue;
      const MatrixEntry key{e.col, e.row, 0.0, 0};
      auto it = std::lower_bound(by.begin(), by.end(), &key, less);
      if (it == by.end() || (*it)->row != e.col || (*it)->col != e.row)
        fail(m.file, e.line, "the " + name + " matrix is not symmetric: entry (" + std::to_string(e.row + 1) + ", " +
                                 std::to_string(e.col + 1) + ") has no mirror (" + std::to_string(e.col + 1) + ", " +
                                 std::to_string(e.row + 1) + ") though the file stores both triangles");
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.prune(0.0);
  return A;
}

}  // namespace fc::feprep
