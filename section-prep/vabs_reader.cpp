#include "section-prep/vabs_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>

#include "common/input.h"
#include "common/materials.h"

namespace fc::section {

namespace {

// Numbers with their line numbers; comments removed.
class TokenStream {
 public:
  TokenStream(const std::string& text, std::string name) : name_(std::move(name)) {
    std::istringstream in(text);
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      const auto bang = line.find('!');
      if (bang != std::string::npos) line.erase(bang);
      std::istringstream ls(line);
      std::string tok;
      std::vector<std::string> toks;
      while (ls >> tok) toks.push_back(tok);
      if (!toks.empty()) lines_.push_back({n, std::move(toks)});
    }
  }

  bool atEnd() const { return li_ >= lines_.size(); }
  // Numbers from the current position to the end of the file.
  double numbersLeft() const {
    double n = 0;
    for (std::size_t i = li_; i < lines_.size(); ++i) n += static_cast<double>(lines_[i].tokens.size());
    return atEnd() ? 0 : n - static_cast<double>(ti_);
  }
  int line() const { return atEnd() ? (lines_.empty() ? 0 : lines_.back().number) : lines_[li_].number; }

  // Reads the next `count` tokens; `what` names them in errors.
  std::vector<double> numbers(int count, const std::string& what) {
    std::vector<double> out;
    while (static_cast<int>(out.size()) < count) {
      if (atEnd()) fail(what, "the file ends early; expected " + std::to_string(count) + " numbers");
      const auto& L = lines_[li_];
      const std::string& t = L.tokens[ti_];
      out.push_back(toDouble(t, what));
      if (++ti_ >= L.tokens.size()) { ti_ = 0; ++li_; }
    }
    return out;
  }
  // Whole line of numbers (element and orientation records have a fixed count
  // per line, so records are read line by line).
  std::vector<double> lineNumbers(const std::string& what) {
    if (atEnd()) fail(what, "the file ends early");
    if (ti_ != 0) fail(what, "unexpected extra numbers on the previous line");
    const auto& L = lines_[li_];
    std::vector<double> out;
    for (const auto& t : L.tokens) out.push_back(toDouble(t, what));
    ++li_;
    return out;
  }
  long integer(const std::string& what) {
    const double v = numbers(1, what)[0];
    if (v != std::floor(v)) fail(what, "expected an integer");
    return static_cast<long>(v);
  }
  int lastLine() const { return last_line_; }

  [[noreturn]] void fail(const std::string& what, const std::string& msg) const {
    throw InputError(name_, line(), 0, what, msg);
  }
  [[noreturn]] void failAt(int line, const std::string& what, const std::string& msg) const {
    throw InputError(name_, line, 0, what, msg);
  }

 private:
  double toDouble(std::string t, const std::string& what) {
    last_line_ = lines_[li_].number;
    for (char& c : t)
      if (c == 'd' || c == 'D') c = 'e';
    try {
      std::size_t used = 0;
      const double v = std::stod(t, &used);
      if (used != t.size() || !std::isfinite(v)) throw std::invalid_argument(t);
      return v;
    } catch (const std::exception&) {
      fail(what, "expected a number, got '" + t + "'");
    }
  }

  struct Line {
    int number;
    std::vector<std::string> tokens;
  };
  std::string name_;
  std::vector<Line> lines_;
  std::size_t li_ = 0, ti_ = 0;
  int last_line_ = 0;
};

Matrix6d upperTriangle(const std::vector<double>& c) {
  Matrix6d C;
  int k = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) C(i, j) = C(j, i) = c[k++];
  return C;
}

// Two nodes at one place, both used by elements: the elements meeting there are not
// joined (a crack), which silently softens the section. Unused nodes cannot matter.
// "One place": within 1e-9 of the section's size (the decks use m, mm or inches).
void checkCoincidentNodes(const TokenStream& ts, const SectionMesh& mesh,
                          const std::vector<long>& node_id, const std::vector<int>& node_line) {
  std::vector<char> used(mesh.nodes.size(), 0);
  for (const SectionElement& e : mesh.elements)
    for (int n : e.nodes)
      if (n >= 0) used[n] = 1;
  std::vector<long> order;
  Eigen::AlignedBox2d box;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    if (used[i]) {
      order.push_back(static_cast<long>(i));
      box.extend(mesh.nodes[i]);
    }
  if (order.empty()) return;
  const double tol = 1e-9 * box.sizes().maxCoeff();
  std::sort(order.begin(), order.end(), [&](long a, long b) { return mesh.nodes[a].x() < mesh.nodes[b].x(); });
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && mesh.nodes[order[j]].x() - mesh.nodes[order[i]].x() <= tol; ++j) {
      if (std::abs(mesh.nodes[order[j]].y() - mesh.nodes[order[i]].y()) > tol) continue;
      const long first = std::min(order[i], order[j]), second = std::max(order[i], order[j]);
      ts.failAt(node_line[second], "node " + std::to_string(node_id[second]),
                "is at the same place as node " + std::to_string(node_id[first]) + " (line " +
                    std::to_string(node_line[first]) +
                    "), and elements use both: they are not joined there; expected one node per "
                    "place (merge them, or leave a gap to model a slit)");
    }
}

}  // namespace

Matrix6d orthotropicStiffness(double E1, double E2, double E3, double G12, double G13,
                              double G23, double nu12, double nu13, double nu23) {
  return fc::orthotropicCompliance(E1, E2, E3, G12, G13, G23, nu12, nu13, nu23).inverse();
}

// One function, read top to bottom as the file is: the records come in the
// file's own order and each is checked where it is read (a sequential reader,
// allowed its length in tests/docs/function_length.py).
VabsModel parseVabs(const std::string& text, const std::string& name) {
  TokenStream ts(text, name);
  VabsModel model;
  const long format_flag = ts.integer("format_flag");
  const long nlayer = ts.integer("nlayer");
  if (format_flag != 0 && format_flag != 1)
    ts.failAt(ts.lastLine(), "format_flag", "expected 0 (old format) or 1 (new format)");
  const long timo = ts.integer("Timoshenko_flag");
  const long damping = ts.integer("damping_flag");
  const long thermal = ts.integer("thermal_flag");
  model.timoshenko = timo != 0;
  if (thermal != 0)
    ts.failAt(ts.lastLine(), "thermal_flag", "thermal analysis is not supported; expected 0");
  const long curve = ts.integer("curve_flag");
  const long oblique = ts.integer("oblique_flag");
  ts.integer("trapeze_flag");
  ts.integer("Vlasov_flag");
  if (curve != 0) {
    // Accepted only as the straight beam it then describes: k1 = k2 = k3 = 0.
    const auto k = ts.numbers(3, "k1 k2 k3");
    if (k[0] != 0 || k[1] != 0 || k[2] != 0)
      ts.failAt(ts.lastLine(), "k1 k2 k3",
                "initially twisted or curved beams are not supported; expected 0 0 0");
  }
  if (oblique != 0) {
    const auto c = ts.numbers(2, "cos11 cos21");
    if (c[0] != 1 || c[1] != 0)
      ts.failAt(ts.lastLine(), "cos11 cos21", "oblique sections are not supported; expected 1 0");
  }
  const long nnode = ts.integer("nnode");
  const long nelem = ts.integer("nelem");
  const long nmate = ts.integer("nmate");
  if (nnode < 3 || nelem < 1 || nmate < 1)
    ts.failAt(ts.lastLine(), "nnode nelem nmate", "expected positive counts");
  // Nodes take 3 numbers, elements 10 and an orientation record of 3 at least, materials
  // 4 at least: counts beyond what the file holds are an error here, not an
  // allocation of 2^31 elements.
  const double needed = 3.0 * nnode + 13.0 * nelem + 4.0 * nmate, left = ts.numbersLeft();
  if (needed > left)
    ts.failAt(ts.lastLine(), "nnode nelem nmate",
              std::to_string(nnode) + " nodes, " + std::to_string(nelem) + " elements and " +
                  std::to_string(nmate) + " materials need at least " + std::to_string(static_cast<long>(needed)) +
                  " numbers, but the file holds " + std::to_string(static_cast<long>(left)) +
                  " more; expected the counts of the records that follow");

  SectionMesh& mesh = model.mesh;
  mesh.source_file = name;
  mesh.nodes.resize(nnode);
  std::map<long, long> node_index;
  std::vector<long> node_id(nnode);
  std::vector<int> node_line(nnode);
  for (long i = 0; i < nnode; ++i) {
    const auto v = ts.numbers(3, "node " + std::to_string(i + 1));
    node_line[i] = ts.lastLine();
    const long id = static_cast<long>(v[0]);
    if (!node_index.emplace(id, i).second)
      ts.failAt(ts.lastLine(), "node " + std::to_string(id), "node number used twice");
    // Any length unit (VABS decks use m, mm or inches), but within 1e4 units of the
    // origin: a 1e30 coordinate made every stiffness NaN.
    if (std::abs(v[1]) > 1e4 || std::abs(v[2]) > 1e4)
      ts.failAt(ts.lastLine(), "node " + std::to_string(id),
                "coordinates beyond 1e4 length units from the origin; expected the section's "
                "own coordinates");
    mesh.nodes[i] = Eigen::Vector2d(v[1], v[2]);
    node_id[i] = id;
  }

  std::map<long, long> elem_index;
  mesh.elements.resize(nelem);
  for (long e = 0; e < nelem; ++e) {
    const std::string what = "element record " + std::to_string(e + 1);
    const int line = ts.line();
    const auto v = ts.lineNumbers(what);
    if (v.size() != 10)
      ts.failAt(line, what, "expected the element number and 9 node numbers (0 for absent nodes), got " +
                                std::to_string(v.size()) + " numbers");
    SectionElement& el = mesh.elements[e];
    el.user_id = static_cast<int>(v[0]);
    el.source_line = line;
    if (!elem_index.emplace(el.user_id, e).second)
      ts.failAt(line, "element " + std::to_string(el.user_id), "element number used twice");
    // VABS: a triangle has node slot 4 zero (slots 5-7 its mid-sides).
    el.shape = v[4] == 0 ? ElementShape::Triangle : ElementShape::Quadrilateral;
    for (int k = 0; k < 9; ++k) {
      const long id = static_cast<long>(v[k + 1]);
      if (id == 0) continue;
      for (int j = 0; j < k; ++j)
        if (static_cast<long>(v[j + 1]) == id)
          ts.failAt(line, "element " + std::to_string(el.user_id),
                    "node " + std::to_string(id) + " appears twice; expected distinct nodes (a "
                    "quadrilateral collapsed to a triangle is given as a triangle, 4th node 0)");
      auto it = node_index.find(id);
      if (it == node_index.end())
        ts.failAt(line, "element " + std::to_string(el.user_id),
                  "node " + std::to_string(id) + " is not defined");
      el.nodes[k] = static_cast<int>(it->second);
    }
    if (el.shape == ElementShape::Triangle && (v[8] != 0 || v[9] != 0))
      ts.failAt(line, "element " + std::to_string(el.user_id),
                "a triangle (4th node 0) may have mid-side nodes in positions 5-7 only");
  }

  checkCoincidentNodes(ts, mesh, node_id, node_line);

  // Orientation records. Material references are checked once materials are read.
  std::vector<long> layer_of(nelem, 0), material_id(nelem, 0);
  std::vector<int> orient_line(nelem, 0);
  std::vector<char> seen(nelem, 0);
  for (long r = 0; r < nelem; ++r) {
    const std::string what = "orientation record " + std::to_string(r + 1);
    const int line = ts.line();
    const auto v = ts.lineNumbers(what);
    const std::size_t expect = format_flag == 1 ? 3 : 12;
    if (v.size() != expect)
      ts.failAt(line, what,
                format_flag == 1 ? "expected 'element layer theta1' (3 numbers)"
                                 : "expected 'element material theta3 theta1(1..9)' (12 numbers)");
    auto it = elem_index.find(static_cast<long>(v[0]));
    if (it == elem_index.end())
      ts.failAt(line, what, "element " + std::to_string(static_cast<long>(v[0])) + " is not defined");
    const long e = it->second;
    if (seen[e]) ts.failAt(line, what, "element " + std::to_string(static_cast<long>(v[0])) + " oriented twice");
    seen[e] = 1;
    orient_line[e] = line;
    SectionElement& el = mesh.elements[e];
    if (format_flag == 1) {
      layer_of[e] = static_cast<long>(v[1]);
      if (v[2] == 540)
        ts.failAt(line, what, "theta1 = 540 (orientation from a reference point) is not supported; "
                              "give theta1 in degrees");
      el.theta1_deg[0] = v[2];
    } else {
      material_id[e] = static_cast<long>(v[1]);
      el.theta3_deg = v[2];
      if (v[4] == 540) {
        el.theta1_deg[0] = v[3];
      } else {
        el.theta1_nodal = true;
        for (int k = 0; k < 9; ++k) el.theta1_deg[k] = v[3 + k];
      }
    }
  }

  std::map<long, std::pair<long, double>> layers;
  if (format_flag == 1) {
    for (long l = 0; l < nlayer; ++l) {
      const auto v = ts.numbers(3, "layer " + std::to_string(l + 1));
      layers[static_cast<long>(v[0])] = {static_cast<long>(v[1]), v[2]};
    }
  }

  std::map<long, int> mat_index;
  for (long m = 0; m < nmate; ++m) {
    const std::string what = "material " + std::to_string(m + 1);
    const long id = ts.integer(what + " id");
    const long orth = ts.integer(what + " orth");
    SectionMaterial mat;
    mat.name = "vabs_material_" + std::to_string(id);
    const std::string wm = "material " + std::to_string(id);
    if (orth == 0) {
      const auto c = ts.numbers(2, wm + " (E nu)");
      const double E = c[0], nu = c[1], G = E / (2 * (1 + nu));
      mat.C = orthotropicStiffness(E, E, E, G, G, G, nu, nu, nu);
    } else if (orth == 1) {
      const auto c = ts.numbers(9, wm + " (E1 E2 E3 G12 G13 G23 nu12 nu13 nu23)");
      mat.C = orthotropicStiffness(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]);
    } else if (orth == 2) {
      mat.C = upperTriangle(ts.numbers(21, wm + " (21 stiffness constants)"));
    } else {
      ts.failAt(ts.lastLine(), wm + " orth", "expected 0 (isotropic), 1 (orthotropic) or 2 (anisotropic)");
    }
    if (!mat.C.allFinite() || mat.C.llt().info() != Eigen::Success)
      ts.failAt(ts.lastLine(), wm, "the stiffness matrix is not positive definite");
    if (const std::string why = materialProblem(mat); !why.empty()) ts.failAt(ts.lastLine(), wm, why);
    if (damping != 0) ts.numbers(1, wm + " damping coefficient");
    mat.rho = ts.numbers(1, wm + " density")[0];
    if (mat.rho < 0) ts.failAt(ts.lastLine(), wm + " density", "expected a non-negative density");
    mat_index[id] = static_cast<int>(mesh.materials.size());
    mesh.materials.push_back(mat);
  }
  // Numbers after the last material mean the records before were misread (a line
  // given twice made a modulus the density and left the rest unread).
  if (!ts.atEnd())
    ts.fail("end of file", "unexpected numbers after the last material; expected " + std::to_string(nmate) +
                               " material records and nothing after them");

  for (long e = 0; e < nelem; ++e) {
    SectionElement& el = mesh.elements[e];
    if (!seen[e])
      ts.failAt(el.source_line, "element " + std::to_string(el.user_id), "has no orientation record");
    long mid = material_id[e];
    if (format_flag == 1) {
      auto it = layers.find(layer_of[e]);
      if (it == layers.end())
        ts.failAt(orient_line[e], "element " + std::to_string(el.user_id),
                  "layer " + std::to_string(layer_of[e]) + " is not defined");
      mid = it->second.first;
      el.theta3_deg = it->second.second;
    }
    auto it = mat_index.find(mid);
    if (it == mat_index.end())
      ts.failAt(orient_line[e], "element " + std::to_string(el.user_id),
                "material " + std::to_string(mid) + " is not defined");
    el.material = it->second;
  }
  return model;
}

VabsModel readVabsFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, 0, "", "cannot open the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseVabs(ss.str(), path);
}

}  // namespace fc::section
