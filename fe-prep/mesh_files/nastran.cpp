#include "fe-prep/mesh_files/nastran.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <sstream>

#include "common/files.h"
#include "common/input.h"
#include "common/laminate.h"
#include "common/stress_data.h"
#include "fe-prep/element_properties.h"
#include "fe-prep/elements/shell_frame.h"

namespace fc::feprep {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

[[noreturn]] void failAt(const std::string& file, int line, const std::string& what, const std::string& message) {
  throw InputError(file, line, 0, what, message);
}

// Tabs to the next multiple of 8, as Nastran reads fixed-field lines.
std::string expandTabs(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\t') {
      do out += ' ';
      while (out.size() % 8 != 0);
    } else {
      out += c;
    }
  }
  return out;
}

struct Reader {
  std::vector<NastranCard> cards;
  bool done = false;   // ENDDATA seen
  int pending_large = 0;  // large-field half rows of the current card since its last full row

  void addRow(const std::string& file, int line, const std::vector<std::string>& data, bool large) {
    NastranCard& c = cards.back();
    if (file != (c.other_files.empty() ? c.file : c.other_files.back().second))
      c.other_files.emplace_back(c.fields.size(), file);
    if (!large && pending_large % 2 == 1) {
      // A small-field continuation after an unpaired large line: the row's other half is blank.
      for (int k = 0; k < 4; ++k) c.fields.push_back({"", line});
      pending_large = 0;
    }
    for (const auto& d : data) c.fields.push_back({upper(trim(d)), line});
    if (large) ++pending_large;
  }

  void read(const std::string& path, const std::string& from_file, int from_line, int depth) {
    if (depth > 20) failAt(from_file, from_line, "INCLUDE", "INCLUDE nested deeper than 20 files (a file including itself?)");
    std::ifstream in(path);
    if (!in) {
      if (from_file.empty()) throw InputError(path, 0, 0, "", "cannot read the Nastran deck '" + path + "'");
      failAt(from_file, from_line, "INCLUDE", "cannot read the included file '" + path + "'");
    }
    // A deck with an executive and case control section starts its bulk data
    // after BEGIN BULK: found by a first pass, the lines are then read one at a
    // time (never the whole file held).
    int start = 0;
    std::string l;
    if (depth == 0) {
      int ln = 0;
      while (std::getline(in, l)) {
        ++ln;
        std::string u = upper(trim(l));
        u.erase(std::remove(u.begin(), u.end(), ' '), u.end());
        if (u.rfind("BEGINBULK", 0) == 0) {
          start = ln;
          break;
        }
      }
      in.clear();
      in.seekg(0);
    }
    std::vector<std::string> data;
    for (int ln = 1; !done && std::getline(in, l); ++ln) {
      if (ln <= start) continue;
      if (!l.empty() && l.back() == '\r') l.pop_back();
      const auto dollar = l.find('$');
      if (dollar != std::string::npos) l.resize(dollar);
      if (l.find_first_not_of(" \t\r\n") == std::string::npos) continue;
      const std::string head = upper(trim(l));
      if (head.rfind("ENDDATA", 0) == 0) {
        done = true;
        break;
      }
      if (head.rfind("INCLUDE", 0) == 0) {
        std::string name = trim(trim(l).substr(7));
        if (name.size() >= 2 && name.front() == '\'' && name.back() == '\'') name = name.substr(1, name.size() - 2);
        if (name.empty()) failAt(path, ln, "INCLUDE", "expected a file name, INCLUDE 'file.bdf'");
        read(resolveRelativeTo(path, name), path, ln, depth + 1);
        continue;
      }
      if (l.find(',') != std::string::npos) {
        // Free field: field 1, eight data fields (four for large-field "NAME*"), field 10.
        std::vector<std::string> tok;
        std::stringstream ss(l);
        for (std::string t; std::getline(ss, t, ',');) tok.push_back(t);
        if (l.back() == ',') tok.push_back("");
        const std::string f1 = upper(trim(tok[0]));
        const bool cont = f1.empty() || f1[0] == '+' || f1[0] == '*';
        const bool large = (!cont && !f1.empty() && f1.back() == '*') || (cont && !f1.empty() && f1[0] == '*');
        const std::size_t per = large ? 4 : 8;
        if (tok.size() > per + 2)
          failAt(path, ln, cont ? "continuation" : f1,
                 "a free-field line has " + std::to_string(tok.size()) + " fields; expected at most " +
                     std::to_string(per + 2) + " (field 1, " + std::to_string(per) +
                     " data fields and the continuation field), the rest on a continuation line");
        data.assign(per, std::string());
        for (std::size_t k = 1; k < tok.size() && k <= per; ++k) data[k - 1] = tok[k];
        if (!cont) {
          cards.push_back({large ? f1.substr(0, f1.size() - 1) : f1, path, ln, {}, {}});
          pending_large = 0;
        } else if (cards.empty()) {
          failAt(path, ln, "continuation", "a continuation line with no card before it");
        }
        addRow(path, ln, data, large);
        continue;
      }
      if (l.find('\t') != std::string::npos) l = expandTabs(l);
      const std::string f1 = upper(trim(l.substr(0, std::min<std::size_t>(8, l.size()))));
      const bool cont = f1.empty() || f1[0] == '+' || f1[0] == '*';
      const bool large = cont ? (!f1.empty() && f1[0] == '*') : (!f1.empty() && f1.back() == '*');
      if (!cont) {
        cards.push_back({large ? f1.substr(0, f1.size() - 1) : f1, path, ln, {}, {}});
        pending_large = 0;
      } else if (cards.empty()) {
        failAt(path, ln, "continuation", "a continuation line with no card before it");
      }
      const std::size_t width = large ? 16 : 8, per = large ? 4 : 8;
      data.assign(per, std::string());
      for (std::size_t k = 0; k < per; ++k) {
        const std::size_t b = 8 + k * width;
        if (b < l.size()) data[k] = l.substr(b, std::min(width, l.size() - b));
      }
      addRow(path, ln, data, large);
    }
  }
};

// ---------------------------------------------------------------- fields

// "field 4" on the card's first line, "field 3 of continuation 2" after it
// (the numbers of the Quick Reference's format tables).
std::string fieldLabel(std::size_t i) {
  const std::size_t row = i / 8, col = i % 8 + 2;
  return row == 0 ? "field " + std::to_string(col)
                  : "field " + std::to_string(col) + " of continuation " + std::to_string(row);
}

struct Card {
  const NastranCard& c;
  std::string id;  // "GRID 12" for messages

  const std::string& text(std::size_t i) const {
    static const std::string empty;
    return i < c.fields.size() ? c.fields[i].text : empty;
  }
  bool blank(std::size_t i) const { return text(i).empty(); }
  int lineOf(std::size_t i) const { return i < c.fields.size() ? c.fields[i].line : c.line; }
  const std::string& fileOf(std::size_t i) const { return c.fileOf(i); }

  [[noreturn]] void fail(std::size_t i, const std::string& name, const std::string& message) const {
    failAt(fileOf(i), lineOf(i), c.name + (id.empty() ? "" : " " + id) + ", " + fieldLabel(i) + " (" + name + ")",
           message);
  }
  [[noreturn]] void failCard(const std::string& message) const {
    failAt(c.file, c.line, c.name + (id.empty() ? "" : " " + id), message);
  }

  static bool parseInt(const std::string& t, long& v) {
    if (t.empty()) return false;
    std::size_t k = (t[0] == '+' || t[0] == '-') ? 1 : 0;
    if (k == t.size()) return false;
    for (std::size_t j = k; j < t.size(); ++j)
      if (!std::isdigit(static_cast<unsigned char>(t[j]))) return false;
    v = std::strtol(t.c_str(), nullptr, 10);
    return true;
  }
  // Nastran reals: 1.5, 1.5E+3, 1.5D3 and the implicit exponent 1.5+3 / 1.5-3.
  static bool parseReal(const std::string& t, double& v) {
    if (t.empty()) return false;
    std::string s = t;
    for (auto& ch : s)
      if (ch == 'D') ch = 'E';
    for (std::size_t j = 1; j < s.size(); ++j)
      if ((s[j] == '+' || s[j] == '-') && s[j - 1] != 'E') {
        s.insert(j, "E");
        break;
      }
    char* end = nullptr;
    v = std::strtod(s.c_str(), &end);
    return end && *end == '\0' && std::isfinite(v) && s.find_first_of("0123456789") != std::string::npos &&
           s.find_first_not_of("0123456789+-.E") == std::string::npos;
  }

  long integer(std::size_t i, const std::string& name) const {
    long v = 0;
    if (blank(i)) fail(i, name, "missing; expected an integer");
    if (!parseInt(text(i), v)) fail(i, name, "expected an integer, got '" + text(i) + "'");
    return v;
  }
  long integerOr(std::size_t i, const std::string& name, long dflt) const { return blank(i) ? dflt : integer(i, name); }
  long positive(std::size_t i, const std::string& name) const {
    const long v = integer(i, name);
    if (v <= 0) fail(i, name, "expected an identification number > 0, got " + std::to_string(v));
    return v;
  }
  double real(std::size_t i, const std::string& name) const {
    double v = 0;
    if (blank(i)) fail(i, name, "missing; expected a real number");
    if (!parseReal(text(i), v)) fail(i, name, "expected a real number, got '" + text(i) + "'");
    return v;
  }
  double realOr(std::size_t i, const std::string& name, double dflt) const { return blank(i) ? dflt : real(i, name); }
  bool isInteger(std::size_t i) const {
    long v;
    return parseInt(text(i), v);
  }
  void mustBeBlank(std::size_t i, const std::string& name, const std::string& why) const {
    if (blank(i)) return;
    double v;
    if (parseReal(text(i), v) && v == 0.0) return;  // an explicit zero is Nastran's default
    fail(i, name, why);
  }
};

// The card's id (its first field) for messages: "GRID 12".
std::string firstField(const NastranCard& c) { return c.fields.empty() ? std::string() : c.fields[0].text; }

// ---------------------------------------------------------------- coordinate systems

struct Cord {
  long cid = 0, rid = 0;
  bool cylindrical = false;
  Eigen::Vector3d a, b, c;  // as given, in RID
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // columns: local axes in basic
  bool resolved = false;
  const NastranCard* card = nullptr;
};

// ---------------------------------------------------------------- the model

struct Mat {
  long id = 0;
  bool orthotropic = false;  // MAT8
  Material m;
  double G = 0;  // MAT1 shear modulus
  const NastranCard* card = nullptr;
};

struct ShellProp {
  long pid = 0;
  const NastranCard* card = nullptr;
  ShellProperty p;
};

struct BeamProp {
  long pid = 0;
  const NastranCard* card = nullptr;
  bool rod = false;  // PROD
  BeamProperty p;
};

Eigen::Vector3d perpendicular(const Eigen::Vector3d& a) {
  const Eigen::Vector3d t = std::abs(a.x()) < 0.9 * a.norm() ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return a.cross(t).normalized();
}

class Builder {
 public:
  Builder(const std::vector<NastranCard>& cards, const UnitSystem& u, const std::vector<std::string>& ignore)
      : cards_(cards), u_(u), ignore_(ignore.begin(), ignore.end()) {}

  NastranModel build();

 private:
  const std::vector<NastranCard>& cards_;
  const UnitSystem& u_;
  std::set<std::string> ignore_;
  std::map<long, Cord> cords_;
  struct Grid {
    long id = 0, cp = 0, cd = 0;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();  // as given, in CP, file units
    Eigen::Vector3d basic = Eigen::Vector3d::Zero();  // SI
    const NastranCard* card = nullptr;
  };
  std::map<long, Grid> grids_;
  std::map<long, Mat> mats_;
  MaterialLibrary library_;
  std::map<long, ShellProp> shells_;
  std::map<long, BeamProp> beams_;
  std::map<long, const NastranCard*> pid_card_;  // every property id, for duplicates

  const Cord& cord(long cid, const Card& at, std::size_t field, const std::string& name, int depth = 0);
  Eigen::Vector3d toBasic(long cid, const Eigen::Vector3d& x, const Card& at, std::size_t field, const std::string& name);
  const Grid& grid(long id, const Card& at, std::size_t field, const std::string& name) {
    auto it = grids_.find(id);
    if (it == grids_.end()) at.fail(field, name, "no GRID " + std::to_string(id) + " in the deck");
    return it->second;
  }
  const Mat& mat(long id, const Card& at, std::size_t field, const std::string& name) {
    auto it = mats_.find(id);
    if (it == mats_.end()) at.fail(field, name, "no MAT1 or MAT8 " + std::to_string(id) + " in the deck");
    return it->second;
  }
  void readMat1(const Card& k);
  void readMat8(const Card& k);
  void readPshell(const Card& k);
  void readPcomp(const Card& k);
  void readBeamProperty(const Card& k);

  // The passes of build(), in order.
  using CardPasses = std::array<std::vector<const NastranCard*>, 4>;
  CardPasses sortCards() const;
  void readSystemsGridsMaterials(const std::vector<const NastranCard*>& cards, NastranModel& out);
  void readProperties(const std::vector<const NastranCard*>& cards);
  void readElements(const std::vector<const NastranCard*>& cards, NastranModel& out);
  void numberNodesAndElements(NastranModel& out);
  void readRigidElementsAndSets(const std::vector<const NastranCard*>& cards, NastranModel& out);
  void readMasses(const std::vector<const NastranCard*>& cards, NastranModel& out);

  // What readElements leaves for the passes after it.
  struct Shell {
    std::vector<long> g;
    long pid;
    Eigen::Vector3d axis;
    const NastranCard* card;
  };
  struct Line {
    long ga, gb, pid;
    Eigen::Vector3d v;
  };
  std::vector<Shell> shell_elements_;
  std::vector<Line> line_elements_;
  std::set<long> used_grids_;                    // grids on an element: the mesh's nodes
  std::map<long, const NastranCard*> eids_;      // every element id, for duplicates
};

const Cord& Builder::cord(long cid, const Card& at, std::size_t field, const std::string& name, int depth) {
  auto it = cords_.find(cid);
  if (it == cords_.end())
    at.fail(field, name, "no coordinate system " + std::to_string(cid) + " (CORD2R or CORD2C) in the deck");
  Cord& c = it->second;
  if (c.resolved) return c;
  if (depth > 50) at.fail(field, name, "coordinate systems reference each other in a loop");
  Card ck{*c.card, std::to_string(c.cid)};
  auto basic = [&](const Eigen::Vector3d& p) {
    if (c.rid == 0) return Eigen::Vector3d(p * u_.length);
    const Cord& r = cord(c.rid, ck, 1, "RID", depth + 1);
    Eigen::Vector3d q = p;
    if (r.cylindrical) q = Eigen::Vector3d(p.x() * std::cos(p.y() * kPi / 180), p.x() * std::sin(p.y() * kPi / 180), p.z());
    return Eigen::Vector3d(r.origin + r.R * (q * u_.length));
  };
  const Eigen::Vector3d A = basic(c.a), B = basic(c.b), C = basic(c.c);
  const Eigen::Vector3d z = B - A;
  const Eigen::Vector3d y = z.cross(C - A);
  if (z.norm() == 0 || y.norm() <= 1e-12 * z.norm() * (C - A).norm())
    ck.failCard("the points A, B, C are collinear or coincide; expected A the origin, B on the z axis, C in the x-z plane");
  c.origin = A;
  c.R.col(2) = z.normalized();
  c.R.col(1) = y.normalized();
  c.R.col(0) = c.R.col(1).cross(c.R.col(2));
  c.resolved = true;
  return c;
}

Eigen::Vector3d Builder::toBasic(long cid, const Eigen::Vector3d& x, const Card& at, std::size_t field,
                                 const std::string& name) {
  if (cid == 0) return x * u_.length;
  const Cord& c = cord(cid, at, field, name);
  Eigen::Vector3d q = x;
  if (c.cylindrical) q = Eigen::Vector3d(x.x() * std::cos(x.y() * kPi / 180), x.x() * std::sin(x.y() * kPi / 180), x.z());
  return c.origin + c.R * (q * u_.length);
}

void Builder::readMat1(const Card& k) {
  const long id = k.positive(0, "MID");
  double E = k.realOr(1, "E", 0.0) * u_.stress(), G = k.realOr(2, "G", 0.0) * u_.stress(), nu = k.realOr(3, "NU", 0.0);
  const bool hasE = !k.blank(1), hasG = !k.blank(2), hasNu = !k.blank(3);
  if (!hasE && !hasG) k.fail(1, "E", "E and G are both blank; expected E and NU (or two of E, G, NU)");
  if (hasE && !hasG && !hasNu)
    k.fail(3, "NU", "G and NU are both blank (Nastran then takes G = 0: no shear stiffness); expected NU or G");
  if (!hasE) E = 2 * (1 + nu) * G;
  if (!hasNu) nu = E / (2 * G) - 1;
  if (!hasG) G = E / (2 * (1 + nu));
  if (hasE && hasG && hasNu && std::abs(E / (2 * (1 + nu)) - G) > 1e-4 * G)
    k.fail(2, "G", "E, G and NU are all given and G differs from E / (2 (1 + NU)) = " + std::to_string(E / (2 * (1 + nu)) / u_.stress()) +
                       "; an isotropic material here needs them consistent: leave one blank");
  const double rho = k.realOr(4, "RHO", 0.0) * u_.density();
  if (!(rho > 0)) k.fail(4, "RHO", "expected a density > 0 (the body's modes need its mass)");
  Mat m;
  m.id = id;
  m.card = &k.c;
  m.G = G;
  try {
    m.m = makeIsotropic("MAT1 " + std::to_string(id), E, nu, rho);
  } catch (const std::invalid_argument& e) {
    k.failCard(std::string("not an admissible material: ") + e.what());
  }
  if (!mats_.emplace(id, m).second) k.fail(0, "MID", "a second material with id " + std::to_string(id));
  library_[m.m.name] = m.m;
}

void Builder::readMat8(const Card& k) {
  const long id = k.positive(0, "MID");
  const double s = u_.stress();
  const double E1 = k.real(1, "E1") * s, E2 = k.real(2, "E2") * s, nu12 = k.real(3, "NU12");
  const double G12 = k.real(4, "G12") * s;
  if (k.blank(5) || k.blank(6))
    k.fail(k.blank(5) ? 5 : 6, k.blank(5) ? "G1Z" : "G2Z",
           "blank (Nastran then neglects transverse shear flexibility); the shell elements here need G1Z and G2Z");
  const double G1Z = k.real(5, "G1Z") * s, G2Z = k.real(6, "G2Z") * s;
  const double rho = k.realOr(7, "RHO", 0.0) * u_.density();
  if (!(rho > 0)) k.fail(7, "RHO", "expected a density > 0 (the body's modes need its mass)");
  // Plane stress: E3, nu13 and nu23 do not enter the shell (common/laminate.cpp condenses
  // sigma_33 out); taken transversely isotropic (E3 = E2, nu13 = nu12, G23 = E2 / (2 (1 + nu23))).
  double nu23 = std::clamp(E2 / (2 * G2Z) - 1, 0.0, 0.95);
  Mat m;
  m.id = id;
  m.card = &k.c;
  m.orthotropic = true;
  const std::string name = "MAT8 " + std::to_string(id);
  try {
    m.m = makeOrthotropic(name, E1, E2, E2, G12, G1Z, G2Z, nu12, nu12, nu23, rho);
  } catch (const std::invalid_argument&) {
    try {
      m.m = makeOrthotropic(name, E1, E2, E2, G12, G1Z, G2Z, nu12, nu12, 0.0, rho);
    } catch (const std::invalid_argument& e) {
      k.failCard(std::string("not an admissible material: ") + e.what());
    }
  }
  // Strengths (Xt, Xc, Yt, Yc, S) for the failure index, when all are given (Xc, Yc default Xt, Yt).
  if (!k.blank(11) && !k.blank(13) && !k.blank(15)) {
    PlyStrength st;
    st.Xt = k.real(11, "Xt") * s;
    st.Xc = std::abs(k.realOr(12, "Xc", st.Xt / s)) * s;
    st.Yt = k.real(13, "Yt") * s;
    st.Yc = std::abs(k.realOr(14, "Yc", st.Yt / s)) * s;
    st.S12 = k.real(15, "S") * s;
    if (st.Xt > 0 && st.Xc > 0 && st.Yt > 0 && st.Yc > 0 && st.S12 > 0) m.m.strength = st;
  }
  if (!mats_.emplace(id, m).second) k.fail(0, "MID", "a second material with id " + std::to_string(id));
  library_[m.m.name] = m.m;
}

void Builder::readPshell(const Card& k) {
  const long pid = k.positive(0, "PID");
  const long mid1 = k.integerOr(1, "MID1", 0);
  if (mid1 <= 0) k.fail(1, "MID1", "expected the membrane material (a shell without membrane stiffness is not supported)");
  const Mat& m = mat(mid1, k, 1, "MID1");
  const double t = k.real(2, "T") * u_.length;
  if (!(t > 0)) k.fail(2, "T", "expected a thickness > 0");
  const long mid2 = k.integerOr(3, "MID2", 0);
  if (mid2 != mid1)
    k.fail(3, "MID2", mid2 == 0 ? "blank (a membrane without bending) is not supported; expected MID2 = MID1"
                                : "a bending material different from MID1 is not supported; expected MID2 = MID1");
  if (std::abs(k.realOr(4, "12I/T**3", 1.0) - 1.0) > 1e-12) k.fail(4, "12I/T**3", "expected 1.0 (blank): a homogeneous plate");
  const long mid3 = k.integerOr(5, "MID3", 0);
  if (mid3 != 0 && mid3 != mid1) k.fail(5, "MID3", "a transverse shear material different from MID1 is not supported; expected MID1 or blank");
  // TS/T blank: Nastran's 0.833333, taken as 5/6 exactly.
  const double ts = k.realOr(6, "TS/T", 5.0 / 6.0);
  if (!(ts > 0)) k.fail(6, "TS/T", "expected a shear correction > 0");
  const double nsm = k.realOr(7, "NSM", 0.0) * u_.mass / u_.area();
  if (nsm < 0) k.fail(7, "NSM", "expected a non-structural mass per area >= 0");
  k.mustBeBlank(10, "MID4", "membrane-bending coupling (MID4) is not supported; expected blank");
  ShellProp sp;
  sp.pid = pid;
  sp.card = &k.c;
  const Laminate lam = homogeneousLaminate(m.m.name, t);
  sp.p.laminate = laminateStiffness(lam, library_, ts);
  sp.p.plies = plyTable(lam, library_);
  sp.p.laminate_name = "PSHELL " + std::to_string(pid) + " (" + m.m.name + ", t = " + std::to_string(t) + " m)";
  // MID3 blank: no transverse shear flexibility (Kirchhoff), fe-prep's DKT.
  sp.p.kind = mid3 == 0 ? fe::ShellKind::DKT : fe::ShellKind::DST;
  sp.p.non_structural_mass = nsm;
  sp.p.laminate.mass_per_area += nsm;
  shells_[pid] = sp;
}

void Builder::readPcomp(const Card& k) {
  const long pid = k.positive(0, "PID");
  const std::string lam = k.text(7);
  if (!lam.empty() && lam != "SYM")
    k.fail(7, "LAM", "LAM = " + lam + " is not supported (MEM, BEND, SMEAR, SMCORE change which plies carry what); "
                     "expected blank (every ply listed) or SYM");
  const double nsm = k.realOr(2, "NSM", 0.0) * u_.mass / u_.area();
  if (nsm < 0) k.fail(2, "NSM", "expected a non-structural mass per area >= 0");
  Laminate L;
  L.name = "PCOMP " + std::to_string(pid);
  long mid = 0;
  double t = 0;
  for (std::size_t i = 8; i < k.c.fields.size(); i += 4) {
    if (k.blank(i) && k.blank(i + 1) && k.blank(i + 2) && k.blank(i + 3)) continue;
    // A blank MIDi or Ti repeats the ply before (Nastran's rule); the first ply needs both.
    if (!k.blank(i)) mid = k.positive(i, "MID");
    if (!k.blank(i + 1)) t = k.real(i + 1, "T") * u_.length;
    if (mid == 0) k.fail(i, "MID1", "missing; expected the first ply's material");
    if (!(t > 0)) k.fail(i + 1, "T", "expected a ply thickness > 0");
    const Mat& m = mat(mid, k, i, "MID");
    L.plies.push_back({m.m.name, t, k.realOr(i + 2, "THETA", 0.0)});
  }
  if (L.plies.empty()) k.failCard("no plies; expected MID1 T1 THETA1 SOUT1 ... on the continuation lines");
  if (lam == "SYM")
    for (std::size_t j = L.plies.size(); j-- > 0;) L.plies.push_back(L.plies[j]);
  const double h = L.thickness();
  if (!k.blank(1) && std::abs(k.real(1, "Z0") * u_.length + h / 2) > 1e-9 * h)
    k.fail(1, "Z0", "an offset laminate (Z0 other than -T/2, the plies not centred on the grid surface) is not supported; "
                    "expected blank");
  ShellProp sp;
  sp.pid = pid;
  sp.card = &k.c;
  sp.p.laminate = laminateStiffness(L, library_);  // As from the stacking, as Nastran for PCOMP
  sp.p.plies = plyTable(L, library_);
  sp.p.laminate_name = L.name;
  sp.p.kind = fe::ShellKind::DST;
  sp.p.non_structural_mass = nsm;
  sp.p.laminate.mass_per_area += nsm;
  shells_[pid] = sp;
}

// A, I2 = int z^2 (Nastran's I2), I3 = int y^2 (Nastran's I1), J; shear factors
// k2 (plane 1, shear along y), k3 (plane 2, along z); nsm per length.
SectionMatrices sectionFrom(double A, double I2, double I3, double J, double k2, double k3, double E, double G,
                            double rho, double nsm) {
  SectionMatrices s;
  s.K.setZero();
  s.K.diagonal() << E * A, k2 * G * A, k3 * G * A, G * J, E * I2, E * I3;
  s.M.setZero();
  s.M.diagonal() << rho * A + nsm, rho * A + nsm, rho * A + nsm, rho * (I2 + I3), rho * I2, rho * I3;
  return s;
}

// Blank PBAR K1/K2: Nastran's infinite shear stiffness; 1e8 G A leaves a shear
// flexibility 1e-8 of the area's, far below any bending flexibility of a beam
// (the flexibility-based element takes it exactly, no locking).
constexpr double kRigidShear = 1e8;

void Builder::readBeamProperty(const Card& k) {
  const std::string& n = k.c.name;
  const long pid = k.positive(0, "PID");
  const long mid = k.positive(1, "MID");
  const Mat& m = mat(mid, k, 1, "MID");
  if (m.orthotropic) k.fail(1, "MID", "a beam property needs a MAT1 material (Nastran's rule), got MAT8 " + std::to_string(mid));
  const double E = m.m.E1, G = m.G, rho = m.m.rho, L = u_.length, L4 = L * L * L * L;
  BeamProp bp;
  bp.pid = pid;
  bp.card = &k.c;
  SectionMatrices s;
  const double nsm_unit = u_.mass / u_.length;
  if (n == "PROD") {
    const double A = k.real(2, "A") * L * L, J = k.realOr(3, "J", 0.0) * L4;
    if (!(A > 0)) k.fail(2, "A", "expected an area > 0");
    const double nsm = k.realOr(5, "NSM", 0.0) * nsm_unit;
    s.K.setZero();
    s.K(0, 0) = E * A;
    s.K(3, 3) = G * J;
    s.M.setZero();
    s.M(0, 0) = s.M(1, 1) = s.M(2, 2) = rho * A + nsm;
    s.M(3, 3) = rho * J;
    bp.rod = true;
    bp.p.source = "PROD " + std::to_string(pid);
  } else if (n == "PBAR") {
    const double A = k.real(2, "A") * L * L, I1 = k.realOr(3, "I1", 0.0) * L4, I2 = k.realOr(4, "I2", 0.0) * L4;
    const double J = k.realOr(5, "J", 0.0) * L4, nsm = k.realOr(6, "NSM", 0.0) * nsm_unit;
    if (!(A > 0)) k.fail(2, "A", "expected an area > 0");
    if (!(I1 > 0)) k.fail(3, "I1", "expected a second moment of area > 0 (a bar without bending stiffness: use CROD)");
    if (!(I2 > 0)) k.fail(4, "I2", "expected a second moment of area > 0");
    if (!(J > 0)) k.fail(5, "J", "expected a torsion constant > 0 (blank is 0: the bar would not resist torsion)");
    const double k1 = k.realOr(16, "K1", kRigidShear), k2 = k.realOr(17, "K2", kRigidShear);
    k.mustBeBlank(18, "I12", "a product of inertia I12 (principal axes not along v) is not supported; expected blank or 0");
    s = sectionFrom(A, I2, I1, J, k1, k2, E, G, rho, nsm);
    bp.p.source = "PBAR " + std::to_string(pid);
  } else if (n == "PBEAM") {
    const double A = k.real(2, "A") * L * L, I1 = k.realOr(3, "I1", 0.0) * L4, I2 = k.realOr(4, "I2", 0.0) * L4;
    k.mustBeBlank(5, "I12", "a product of inertia I12 is not supported; expected blank or 0");
    const double J = k.realOr(6, "J", 0.0) * L4, nsm = k.realOr(7, "NSM", 0.0) * nsm_unit;
    if (!(A > 0)) k.fail(2, "A", "expected an area > 0");
    if (!(I1 > 0)) k.fail(3, "I1(A)", "expected a second moment of area > 0");
    if (!(I2 > 0)) k.fail(4, "I2(A)", "expected a second moment of area > 0");
    if (!(J > 0)) k.fail(6, "J(A)", "expected a torsion constant > 0");
    // Rows after the first two (end A and its stress points): stations SO X/XB A I1 I2 I12 J NSM
    // must repeat end A (a constant section), then K1 K2 S1 S2 NSI CW, then offsets.
    double k1 = 1.0, k2 = 1.0;
    const std::size_t rows = (k.c.fields.size() + 7) / 8;
    bool kseen = false;
    for (std::size_t r = 1; r < rows; ++r) {
      const std::size_t b = 8 * r;
      const std::string so = k.text(b);
      const bool station = so == "YES" || so == "YESA" || so == "NO";
      if (r == 1 && !station) continue;  // end A's stress recovery points
      if (!kseen && station) {
        const double vals[4] = {A / (L * L), I1 / L4, I2 / L4, J / L4};
        const std::size_t at[4] = {b + 2, b + 3, b + 4, b + 6};
        const char* names[4] = {"A", "I1", "I2", "J"};
        for (int q = 0; q < 4; ++q)
          if (!k.blank(at[q]) && std::abs(k.real(at[q], names[q]) - vals[q]) > 1e-9 * std::abs(vals[q]))
            k.fail(at[q], names[q], "a tapered beam (a station's section differs from end A's) is not supported; expected " +
                                        std::to_string(vals[q]) + " or blank");
        if (so == "YES") ++r;  // its stress recovery points
        continue;
      }
      if (!kseen) {
        kseen = true;
        k1 = k.realOr(b, "K1", 1.0);
        k2 = k.realOr(b + 1, "K2", 1.0);
        const char* names[6] = {"S1", "S2", "NSI(A)", "NSI(B)", "CW(A)", "CW(B)"};
        for (int q = 0; q < 6; ++q)
          k.mustBeBlank(b + 2 + static_cast<std::size_t>(q), names[q],
                        "shear relief, non-structural inertia and warping are not supported; expected blank");
        continue;
      }
      for (std::size_t q = 0; q < 8; ++q)
        k.mustBeBlank(b + q, "M/N offsets", "offsets of the centre of mass or the neutral axis are not supported; expected blank");
    }
    if (k1 == 0) k1 = kRigidShear;  // Nastran: 0.0 neglects shear flexibility
    if (k2 == 0) k2 = kRigidShear;
    s = sectionFrom(A, I2, I1, J, k1, k2, E, G, rho, nsm);
    bp.p.source = "PBEAM " + std::to_string(pid);
  } else {  // PBARL
    const std::string group = k.text(2);
    if (!group.empty() && group != "MSCBML0")
      k.fail(2, "GROUP", "user cross-section libraries are not supported; expected blank or MSCBML0");
    const std::string type = k.text(3);
    std::vector<double> dim;
    std::size_t i = 8;
    const std::size_t need = type == "ROD" ? 1 : type == "TUBE" || type == "BAR" ? 2 : type == "BOX" ? 4 : 0;
    if (need == 0) k.fail(3, "TYPE", "cross-section '" + type + "' is not supported; expected ROD, TUBE, BAR or BOX");
    for (; dim.size() < need; ++i) {
      const double d = k.real(i, "DIM" + std::to_string(dim.size() + 1)) * L;
      if (!(d > 0)) k.fail(i, "DIM" + std::to_string(dim.size() + 1), "expected a dimension > 0");
      dim.push_back(d);
    }
    const double nsm = k.realOr(i, "NSM", 0.0) * nsm_unit;
    const double nu = m.m.nu12;
    if (type == "ROD") {
      s = solidCircleSection(2 * dim[0], E, nu, rho);  // DIM1 is the radius
    } else if (type == "TUBE") {
      if (dim[1] >= dim[0]) k.fail(9, "DIM2", "expected the inner radius below the outer radius DIM1");
      s = tubeSection(2 * dim[0], dim[0] - dim[1], E, nu, rho);
    } else if (type == "BAR") {
      s = rectangleSection(dim[0], dim[1], E, nu, rho);  // DIM1 along y (v), DIM2 along z
    } else {
      const double W = dim[0], H = dim[1], t1 = dim[2], t2 = dim[3];
      if (2 * t1 >= H) k.fail(10, "DIM3", "expected the flange thickness below half the height DIM2");
      if (2 * t2 >= W) k.fail(11, "DIM4", "expected the web thickness below half the width DIM1");
      s = boxSection(W, H, t1, t2, E, nu, rho);
    }
    s.M(0, 0) += nsm;
    s.M(1, 1) += nsm;
    s.M(2, 2) += nsm;
    bp.p.source = "PBARL " + std::to_string(pid) + " " + type;
  }
  bp.p.Ks = s.K;
  bp.p.Ms = s.M;
  beams_[pid] = bp;
}

NastranModel Builder::build() {
  // A list of passes, each needing what the ones before it read.
  NastranModel out;
  const CardPasses by_pass = sortCards();
  readSystemsGridsMaterials(by_pass[0], out);
  readProperties(by_pass[1]);
  readElements(by_pass[2], out);
  numberNodesAndElements(out);
  readRigidElementsAndSets(by_pass[3], out);
  readMasses(by_pass[3], out);
  return out;
}

// Supported cards sorted into the passes that read them; every unsupported
// card not under ignore: is named, with its count and first place.
Builder::CardPasses Builder::sortCards() const {
  // Unsupported cards: name -> count and first place.
  struct Tally {
    int count = 0;
    std::string where;
  };
  std::map<std::string, Tally> unsupported;
  static const std::set<std::string> kSupported = {"GRID",  "CORD2R", "CORD2C", "CTRIA3", "CQUAD4", "CBAR",
                                                   "CBEAM", "CROD",   "PSHELL", "PCOMP",  "MAT1",   "MAT8",
                                                   "PBAR",  "PBARL",  "PBEAM",  "PROD",   "CONM2",  "RBE2",
                                                   "RBE3",  "SPC1"};
  CardPasses by_pass;  // 0: CORD, GRID, MAT; 1: properties; 2: elements; 3: rigid, masses, sets
  for (const auto& c : cards_) {
    if (ignore_.count(c.name)) continue;
    if (!kSupported.count(c.name)) {
      auto& t = unsupported[c.name];
      if (t.count++ == 0) t.where = c.file + ":" + std::to_string(c.line);
      continue;
    }
    const std::string& n = c.name;
    int pass = 3;
    if (n == "GRID" || n == "CORD2R" || n == "CORD2C" || n == "MAT1" || n == "MAT8") pass = 0;
    else if (n[0] == 'P') pass = 1;
    else if (n == "CTRIA3" || n == "CQUAD4" || n == "CBAR" || n == "CBEAM" || n == "CROD") pass = 2;
    by_pass[pass].push_back(&c);
  }
  if (!unsupported.empty()) {
    std::string list;
    for (const auto& [name, t] : unsupported)
      list += (list.empty() ? "" : "; ") + name + " (" + std::to_string(t.count) + ", first at " + t.where + ")";
    throw InputError(cards_.empty() ? "" : cards_.front().file, 0, 0, "",
                     "the deck has cards fe-prep does not support: " + list +
                         "; list them under ignore: [CARD, ...] in the body to leave them out (docs/nastran.md lists the supported cards)");
  }

  return by_pass;
}

void Builder::readSystemsGridsMaterials(const std::vector<const NastranCard*>& cards, NastranModel& out) {
  // Pass 0: coordinate systems, grids, materials.
  for (const NastranCard* c : cards) {
    const Card k{*c, firstField(*c)};
    if (c->name == "CORD2R" || c->name == "CORD2C") {
      Cord cs;
      cs.cid = k.positive(0, "CID");
      cs.rid = k.integerOr(1, "RID", 0);
      cs.cylindrical = c->name == "CORD2C";
      for (int q = 0; q < 3; ++q) {
        const std::size_t b = 2 + 3 * static_cast<std::size_t>(q);
        const char* an[3] = {"A", "B", "C"};
        Eigen::Vector3d p;
        for (int j = 0; j < 3; ++j)
          p(j) = k.real(b + static_cast<std::size_t>(j), std::string(an[q]) + std::to_string(j + 1));
        (q == 0 ? cs.a : q == 1 ? cs.b : cs.c) = p;
      }
      cs.card = c;
      if (!cords_.emplace(cs.cid, cs).second) k.fail(0, "CID", "a second coordinate system with id " + std::to_string(cs.cid));
    } else if (c->name == "GRID") {
      Grid g;
      g.id = k.positive(0, "ID");
      g.cp = k.integerOr(1, "CP", 0);
      for (int j = 0; j < 3; ++j) g.x(j) = k.realOr(2 + static_cast<std::size_t>(j), "X" + std::to_string(j + 1), 0.0);
      g.cd = k.integerOr(5, "CD", 0);
      if (!k.blank(6)) k.fail(6, "PS", "permanent single-point constraints are not supported; expected blank (hold the grid with SPC1 and reference:)");
      if (k.integerOr(7, "SEID", 0) != 0) k.fail(7, "SEID", "superelements are not supported; expected blank or 0");
      g.card = c;
      if (!grids_.emplace(g.id, g).second) k.fail(0, "ID", "a second GRID with id " + std::to_string(g.id));
    } else if (c->name == "MAT1") {
      readMat1(k);
    } else {
      readMat8(k);
    }
  }
  for (auto& [id, g] : grids_) {
    const Card k{*g.card, std::to_string(id)};
    g.basic = toBasic(g.cp, g.x, k, 1, "CP");
    if (g.cd != 0) cord(g.cd, k, 5, "CD");
    out.grid_point[id] = g.basic;
  }
}

void Builder::readProperties(const std::vector<const NastranCard*>& cards) {
  // Pass 1: properties.
  for (const NastranCard* c : cards) {
    const Card k{*c, firstField(*c)};
    const long pid = k.positive(0, "PID");
    if (!pid_card_.emplace(pid, c).second)
      k.fail(0, "PID", "a second property with id " + std::to_string(pid) + " (the first at " + pid_card_[pid]->file + ":" +
                           std::to_string(pid_card_[pid]->line) + ")");
    if (ignore_.count("PID" + std::to_string(pid))) continue;
    const Card kk{*c, std::to_string(pid)};
    if (c->name == "PSHELL") readPshell(kk);
    else if (c->name == "PCOMP") readPcomp(kk);
    else readBeamProperty(kk);
  }
}

void Builder::readElements(const std::vector<const NastranCard*>& cards, NastranModel& out) {
  // Pass 2: elements, nodes numbered by ascending GRID id.
  std::set<long> rod_grids, bending_grids;
  for (const NastranCard* c : cards) {
    const Card k0{*c, firstField(*c)};
    const long eid = k0.positive(0, "EID");
    const Card k{*c, std::to_string(eid)};
    if (!eids_.emplace(eid, c).second) k.fail(0, "EID", "a second element with id " + std::to_string(eid));
    const long pid = k.integerOr(1, "PID", eid);
    if (ignore_.count("PID" + std::to_string(pid))) continue;
    ++out.element_counts[c->name];
    const std::string& n = c->name;
    if (n == "CTRIA3" || n == "CQUAD4") {
      const std::size_t nn = n == "CTRIA3" ? 3 : 4;
      if (!shells_.count(pid))
        k.fail(1, "PID", pid_card_.count(pid) ? "property " + std::to_string(pid) + " is a " + pid_card_[pid]->name +
                                                    "; expected a PSHELL or PCOMP for a shell element"
                                              : "no PSHELL or PCOMP " + std::to_string(pid) + " in the deck");
      Shell s;
      s.pid = pid;
      s.card = c;
      std::vector<Eigen::Vector3d> x;
      for (std::size_t j = 0; j < nn; ++j) {
        const long gid = k.positive(2 + j, "G" + std::to_string(j + 1));
        x.push_back(grid(gid, k, 2 + j, "G" + std::to_string(j + 1)).basic);
        s.g.push_back(gid);
        if (std::count(s.g.begin(), s.g.end(), gid) > 1) k.fail(2 + j, "G" + std::to_string(j + 1), "a grid repeated in the element");
      }
      const std::size_t th = 2 + nn, zo = 3 + nn;
      k.mustBeBlank(zo, "ZOFFS", "offset shells (ZOFFS) are not supported; expected blank or 0");
      for (std::size_t j = 10; j < 11 + nn; ++j)
        if (!k.blank(j)) k.fail(j, j == 10 ? "TFLAG" : "T" + std::to_string(j - 10), "element grid thicknesses are not supported; expected blank (the property's thickness)");
      const Eigen::Vector3d normal = nn == 3 ? Eigen::Vector3d((x[1] - x[0]).cross(x[2] - x[0]))
                                             : Eigen::Vector3d((x[2] - x[0]).cross(x[3] - x[1]));
      if (!(normal.norm() > 0)) k.failCard("a degenerate element (its grids are collinear)");
      const Eigen::Vector3d nrm = normal.normalized();
      if (!k.blank(th) && k.isInteger(th)) {
        // MCID: the x axis of the system, projected on the element.
        const long mcid = k.integer(th, "MCID");
        if (mcid == 0) {
          s.axis = Eigen::Vector3d::UnitX();
        } else {
          const Cord& cs = cord(mcid, k, th, "MCID");
          if (cs.cylindrical) k.fail(th, "MCID", "a cylindrical material system is not supported; expected a CORD2R (or a THETA)");
          s.axis = cs.R.col(0);
        }
        if ((s.axis - s.axis.dot(nrm) * nrm).norm() < 1e-6)
          k.fail(th, "MCID", "the system's x axis is normal to the element; expected an axis with a component in its plane");
      } else {
        // THETA from the G1-G2 edge, about the element normal.
        const double theta = k.realOr(th, "THETA", 0.0) * kPi / 180;
        Eigen::Vector3d e1 = x[1] - x[0];
        e1 = (e1 - e1.dot(nrm) * nrm).normalized();
        s.axis = std::cos(theta) * e1 + std::sin(theta) * nrm.cross(e1);
      }
      for (long gid : s.g) used_grids_.insert(gid), bending_grids.insert(gid);
      shell_elements_.push_back(s);
    } else {
      const bool rod = n == "CROD";
      if (!beams_.count(pid) || beams_[pid].rod != rod)
        k.fail(1, "PID", !pid_card_.count(pid) ? "no property " + std::to_string(pid) + " in the deck"
                                               : "property " + std::to_string(pid) + " is a " + pid_card_[pid]->name +
                                                     "; expected " + (rod ? "a PROD" : n == "CBAR" ? "a PBAR or PBARL" : "a PBEAM, PBAR or PBARL"));
      Line l;
      l.pid = pid;
      l.ga = k.positive(2, "GA");
      l.gb = k.positive(3, "GB");
      if (l.ga == l.gb) k.fail(3, "GB", "expected a grid other than GA");
      const Grid& a = grid(l.ga, k, 2, "GA");
      const Eigen::Vector3d axis = grid(l.gb, k, 3, "GB").basic - a.basic;
      if (rod) {
        l.v = perpendicular(axis);
        used_grids_.insert(l.ga), used_grids_.insert(l.gb), rod_grids.insert(l.ga), rod_grids.insert(l.gb);
        line_elements_.push_back(l);
        continue;
      }
      if (k.isInteger(4)) {
        const long g0 = k.positive(4, "G0");
        l.v = grid(g0, k, 4, "G0").basic - a.basic;
      } else {
        if (k.blank(4) && k.blank(5) && k.blank(6))
          k.fail(4, "X1", "no orientation vector; expected X1 X2 X3 or G0 (BAROR/BEAMOR defaults are not supported)");
        Eigen::Vector3d v(k.realOr(4, "X1", 0.0), k.realOr(5, "X2", 0.0), k.realOr(6, "X3", 0.0));
        // X1-X3 are in GA's displacement system (CD).
        if (a.cd != 0) {
          const Cord& cs = cord(a.cd, k, 2, "GA's CD");
          if (cs.cylindrical) {
            const Eigen::Vector3d loc = cs.R.transpose() * (a.basic - cs.origin);
            const double phi = std::atan2(loc.y(), loc.x());
            v = Eigen::Vector3d(v.x() * std::cos(phi) - v.y() * std::sin(phi), v.x() * std::sin(phi) + v.y() * std::cos(phi), v.z());
          }
          v = cs.R * v;
        }
        l.v = v;
      }
      if (l.v.cross(axis).norm() <= 1e-6 * l.v.norm() * axis.norm())
        k.fail(4, "X1/G0", "the orientation vector is parallel to the element (or zero); expected a direction across it");
      const std::string off = k.text(7);
      if (!off.empty() && !(n == "CBEAM" && k.isInteger(7)) && off.size() != 3)
        k.fail(7, n == "CBAR" ? "OFFT" : "OFFT/BIT", "expected an offset type such as GGG");
      if (n == "CBEAM" && k.isInteger(7)) k.fail(7, "BIT", "a built-in twist (BIT) is not supported; expected blank");
      k.mustBeBlank(8, "PA", "pin flags (released end DOF) are not supported; expected blank");
      k.mustBeBlank(9, "PB", "pin flags (released end DOF) are not supported; expected blank");
      const char* wn[6] = {"W1A", "W2A", "W3A", "W1B", "W2B", "W3B"};
      for (std::size_t j = 0; j < 6; ++j) k.mustBeBlank(10 + j, wn[j], "offsets of the element ends are not supported; expected blank or 0");
      if (n == "CBEAM") {
        k.mustBeBlank(16, "SA", "warping grids are not supported; expected blank");
        k.mustBeBlank(17, "SB", "warping grids are not supported; expected blank");
      }
      used_grids_.insert(l.ga), used_grids_.insert(l.gb), bending_grids.insert(l.ga), bending_grids.insert(l.gb);
      line_elements_.push_back(l);
    }
  }
  for (long g : rod_grids)
    if (!bending_grids.count(g)) {
      const Grid& gr = grids_.at(g);
      failAt(gr.card->file, gr.card->line, "GRID " + std::to_string(g),
             "the grid joins only CROD elements: its rotations would have no stiffness; model the truss with CBAR/PBAR "
             "or give the grid a shell or beam");
    }
  if (shell_elements_.empty() && line_elements_.empty())
    throw InputError(cards_.empty() ? "" : cards_.front().file, 0, 0, "", "the deck has no CTRIA3, CQUAD4, CBAR, CBEAM or CROD elements");

}

void Builder::numberNodesAndElements(NastranModel& out) {
  Mesh& mesh = out.mesh;
  mesh.nodes.resize(static_cast<long>(used_grids_.size()), 3);
  for (long g : used_grids_) {
    const long k = static_cast<long>(out.node_of_grid.size());
    out.node_of_grid[g] = k;
    mesh.nodes.row(k) = grids_.at(g).basic.transpose();
  }
  // Properties: one shell or beam property per PID, in PID order; groups PID<n>.
  std::map<long, int> shell_index, beam_index, group_index;
  auto group = [&](long pid) {
    auto [it, fresh] = group_index.emplace(pid, static_cast<int>(mesh.groups.size()));
    if (fresh) mesh.groups.push_back("PID" + std::to_string(pid));
    return it->second;
  };
  for (auto& [pid, sp] : shells_) {
    sp.p.name = "PID" + std::to_string(pid);
    shell_index[pid] = static_cast<int>(mesh.shell_properties.size());
    mesh.shell_properties.push_back(sp.p);
  }
  for (auto& [pid, bp] : beams_) {
    bp.p.name = "PID" + std::to_string(pid);
    beam_index[pid] = static_cast<int>(mesh.beam_properties.size());
    mesh.beam_properties.push_back(bp.p);
  }
  auto node = [&](long g) { return out.node_of_grid.at(g); };
  for (const auto& s : shell_elements_) {
    const int grp = group(s.pid);
    auto add = [&](long a, long b, long c) {
      mesh.triangles.push_back({node(a), node(b), node(c)});
      mesh.triangle_group.push_back(grp);
      mesh.triangle_property.push_back(shell_index.at(s.pid));
      mesh.triangle_axis.push_back(s.axis);
    };
    add(s.g[0], s.g[1], s.g[2]);
    if (s.g.size() == 4) add(s.g[0], s.g[2], s.g[3]);  // the 1-3 diagonal, as the .msh reader
    // Each triangle must have a frame (not degenerate, the axis not along its normal).
    for (std::size_t t = mesh.triangles.size() - (s.g.size() - 2); t < mesh.triangles.size(); ++t) {
      try {
        fe::shellFrame(triangleXyz(mesh, static_cast<long>(t)), s.axis);
      } catch (const std::invalid_argument& e) {
        failAt(s.card->file, s.card->line, s.card->name + " " + firstField(*s.card),
               std::string(e.what()) + (s.g.size() == 4 ? " (in one of the two triangles on the G1-G3 diagonal)" : "") +
                   "; expected distinct grids spanning a plane, and a THETA/MCID axis not normal to it");
      }
    }
  }
  for (const auto& l : line_elements_) {
    mesh.beams.push_back({node(l.ga), node(l.gb)});
    mesh.beam_group.push_back(group(l.pid));
    mesh.beam_property.push_back(beam_index.at(l.pid));
    mesh.beam_x2.push_back(l.v.normalized());
  }

}

void Builder::readRigidElementsAndSets(const std::vector<const NastranCard*>& cards, NastranModel& out) {
  Mesh& mesh = out.mesh;
  // Pass 3: rigid elements, masses, SPC sets.
  auto meshNode = [&](long gid, const Card& k, std::size_t i, const std::string& name) {
    grid(gid, k, i, name);
    auto it = out.node_of_grid.find(gid);
    if (it == out.node_of_grid.end())
      k.fail(i, name, "GRID " + std::to_string(gid) + " is on no element of the body; expected a grid of a shell or beam element");
    return it->second;
  };
  // "G1 THRU G2" lists and plain lists of grids from field i on.
  auto gridList = [&](const Card& k, std::size_t i, const std::string& name, bool stop_at_real) {
    std::vector<std::pair<long, std::size_t>> g;
    for (; i < k.c.fields.size(); ++i) {
      if (k.blank(i)) continue;
      if (k.text(i) == "THRU") {
        if (g.empty() || i + 1 >= k.c.fields.size()) k.fail(i, name, "THRU needs a grid before and after it");
        const long hi = k.positive(i + 1, name);
        const long lo = g.back().first;
        if (hi < lo) k.fail(i + 1, name, "expected a grid id above " + std::to_string(lo) + " after THRU");
        for (long q = lo + 1; q <= hi; ++q)
          if (grids_.count(q)) g.push_back({q, i + 1});
        ++i;
        continue;
      }
      if (stop_at_real && !k.isInteger(i)) break;
      g.push_back({k.positive(i, name), i});
    }
    return g;
  };
  for (const NastranCard* c : cards) {
    const Card k0{*c, firstField(*c)};
    const std::string& n = c->name;
    if (n == "SPC1") {
      const long sid = k0.positive(0, "SID");
      const Card k{*c, std::to_string(sid)};
      std::string comp = k.text(1);
      std::sort(comp.begin(), comp.end());
      if (comp != "123456" && comp != "123")
        k.fail(1, "C", "components '" + k.text(1) + "' are not supported; expected 123456 (clamp) or 123 (pin)");
      auto [it, fresh] = out.spc_components.emplace(sid, comp);
      if (!fresh && it->second != comp)
        k.fail(1, "C", "set " + std::to_string(sid) + " already holds components " + it->second + "; one set holds the same components at every grid");
      auto& set = mesh.sets["SPC" + std::to_string(sid)];
      for (const auto& [g, i] : gridList(k, 2, "G", false)) set.push_back(meshNode(g, k, i, "G"));
      std::sort(set.begin(), set.end());
      set.erase(std::unique(set.begin(), set.end()), set.end());
    } else if (n == "RBE2" || n == "RBE3") {
      const long eid = k0.positive(0, "EID");
      const Card k{*c, std::to_string(eid)};
      if (!eids_.emplace(eid, c).second) k.fail(0, "EID", "a second element with id " + std::to_string(eid));
      NastranRbe r;
      r.eid = eid;
      r.rigid = n == "RBE2";
      r.where = c->file + ":" + std::to_string(c->line);
      std::map<long, double> w;  // node -> weight
      if (r.rigid) {
        r.grid = k.positive(1, "GN");
        std::string cm = k.text(2);
        std::sort(cm.begin(), cm.end());
        if (cm != "123456") k.fail(2, "CM", "components '" + k.text(2) + "' are not supported; expected 123456 (a rigid patch)");
        for (const auto& [g, i] : gridList(k, 3, "GM", true)) w[meshNode(g, k, i, "GM")] = 1.0;
        if (out.node_of_grid.count(r.grid)) w[out.node_of_grid[r.grid]] = 1.0;
      } else {
        r.grid = k.positive(2, "REFGRID");
        std::string refc = k.text(3);
        std::sort(refc.begin(), refc.end());
        if (refc != "123456") k.fail(3, "REFC", "components '" + k.text(3) + "' are not supported; expected 123456");
        std::size_t i = 4;
        while (i < k.c.fields.size()) {
          if (k.blank(i)) {
            ++i;
            continue;
          }
          const std::string t = k.text(i);
          if (t == "UM") k.fail(i, "UM", "user-chosen dependent DOF (UM) are not supported; expected none");
          if (t == "ALPHA" || t == "TREF") break;  // thermal expansion: no effect on the modes
          const double wt = k.real(i, "WT");
          if (!(wt > 0)) k.fail(i, "WT", "expected a weight > 0");
          std::string ci = k.text(i + 1);
          std::sort(ci.begin(), ci.end());
          if (ci != "123") k.fail(i + 1, "C", "components '" + k.text(i + 1) + "' are not supported; expected 123 (the grids' translations)");
          i += 2;
          std::size_t j = i;
          while (j < k.c.fields.size() && (k.blank(j) || k.isInteger(j) || k.text(j) == "THRU")) ++j;
          // Grids up to the next weight (a real) or keyword.
          std::vector<std::pair<long, std::size_t>> gs;
          for (std::size_t q = i; q < j; ++q) {
            if (k.blank(q)) continue;
            if (k.text(q) == "THRU") {
              const long lo = gs.empty() ? 0 : gs.back().first, hi = k.positive(q + 1, "G");
              for (long p = lo + 1; p <= hi; ++p)
                if (grids_.count(p)) gs.push_back({p, q + 1});
              ++q;
              continue;
            }
            gs.push_back({k.positive(q, "G"), q});
          }
          if (gs.empty()) k.fail(i, "G", "a weight with no grids; expected WT C G1 G2 ...");
          for (const auto& [g, q] : gs) w[meshNode(g, k, q, "G")] += wt;
          i = j;
        }
        if (w.empty()) k.failCard("no dependent grids; expected WT1 C1 G1,1 ...");
      }
      if (!grids_.count(r.grid)) k.fail(r.rigid ? 1 : 2, r.rigid ? "GN" : "REFGRID", "no GRID " + std::to_string(r.grid) + " in the deck");
      r.point = grids_.at(r.grid).basic;
      for (const auto& [nd, wt] : w) r.nodes.push_back(nd);
      r.weights.resize(static_cast<long>(w.size()));
      long q = 0;
      for (const auto& kv : w) r.weights(q++) = kv.second;
      mesh.sets["RBE" + std::to_string(eid)] = r.nodes;
      out.rbes[eid] = r;
    }
  }
}

void Builder::readMasses(const std::vector<const NastranCard*>& cards, NastranModel& out) {
  Mesh& mesh = out.mesh;
  for (const NastranCard* c : cards) {
    if (c->name != "CONM2") continue;
    const Card k0{*c, firstField(*c)};
    const long eid = k0.positive(0, "EID");
    const Card k{*c, std::to_string(eid)};
    if (!eids_.emplace(eid, c).second) k.fail(0, "EID", "a second element with id " + std::to_string(eid));
    const long gid = k.positive(1, "G");
    const Grid& g = grid(gid, k, 1, "G");
    const long cid = k.integerOr(2, "CID", 0);
    PointMass pm;
    pm.mass = k.real(3, "M") * u_.mass;
    if (!(pm.mass >= 0)) k.fail(3, "M", "expected a mass >= 0");
    const Eigen::Vector3d X(k.realOr(4, "X1", 0.0), k.realOr(5, "X2", 0.0), k.realOr(6, "X3", 0.0));
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (cid > 0) {
      const Cord& cs = cord(cid, k, 2, "CID");
      if (cs.cylindrical) k.fail(2, "CID", "a cylindrical system for the offset and inertia is not supported; expected a CORD2R or 0");
      R = cs.R;
    } else if (cid < -1) {
      k.fail(2, "CID", "expected -1, 0 or a coordinate system id");
    }
    pm.point = cid == -1 ? Eigen::Vector3d(X * u_.length) : Eigen::Vector3d(g.basic + R * (X * u_.length));
    // Nastran's inertia: [I11 -I21 -I31; -I21 I22 -I32; -I31 -I32 I33] about the centre of mass, in CID.
    const double i11 = k.realOr(8, "I11", 0.0), i21 = k.realOr(9, "I21", 0.0), i22 = k.realOr(10, "I22", 0.0);
    const double i31 = k.realOr(11, "I31", 0.0), i32 = k.realOr(12, "I32", 0.0), i33 = k.realOr(13, "I33", 0.0);
    Eigen::Matrix3d I;
    I << i11, -i21, -i31, -i21, i22, -i32, -i31, -i32, i33;
    I *= u_.inertiaMoment();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(I);
    if (es.eigenvalues().minCoeff() < -1e-12 * std::max(1e-300, es.eigenvalues().cwiseAbs().maxCoeff()))
      k.fail(8, "I11", "the inertia matrix is not positive semi-definite");
    pm.inertia = R * I * R.transpose();
    // On a grid of the body, or on an RBE2's independent grid (then on its patch's node nearest the mass).
    auto it = out.node_of_grid.find(gid);
    if (it != out.node_of_grid.end()) {
      pm.node = it->second;
    } else {
      const NastranRbe* rb = nullptr;
      for (const auto& [e, r] : out.rbes)
        if (r.rigid && r.grid == gid) rb = &r;
      if (!rb)
        k.fail(1, "G", "GRID " + std::to_string(gid) + " is on no element nor the independent grid of an RBE2; expected a grid of the body");
      double best = 1e300;
      for (long nd : rb->nodes) {
        const double d = (mesh.nodes.row(nd).transpose() - g.basic).norm();
        if (d < best) best = d, pm.node = nd;
      }
    }
    mesh.point_masses.push_back(pm);
  }
}

}  // namespace

SectionMatrices boxSection(double W, double H, double t1, double t2, double E, double nu, double rho) {
  // DIM1 = W along y, DIM2 = H along z, DIM3 = t1 the horizontal walls' (top, bottom) thickness,
  // DIM4 = t2 the vertical walls'. Torsion: Bredt's thin-walled closed section on the
  // walls' mid-lines (Roark, table 10.7, hollow rectangle):
  //   J = 2 t1 t2 (W - t2)^2 (H - t1)^2 / (W t2 + H t1 - t2^2 - t1^2).
  // Shear: the walls parallel to each shear force carry it (areas 2 W t1 along y, 2 H t2 along z).
  const double wi = W - 2 * t2, hi = H - 2 * t1;
  const double A = W * H - wi * hi;
  const double Iy = (W * H * H * H - wi * hi * hi * hi) / 12;  // int z^2
  const double Iz = (H * W * W * W - hi * wi * wi * wi) / 12;  // int y^2
  const double J = 2 * t1 * t2 * (W - t2) * (W - t2) * (H - t1) * (H - t1) / (W * t2 + H * t1 - t2 * t2 - t1 * t1);
  const double G = E / (2 * (1 + nu));
  SectionMatrices s;
  s.K.setZero();
  s.K.diagonal() << E * A, G * 2 * W * t1, G * 2 * H * t2, G * J, E * Iy, E * Iz;
  s.M.setZero();
  s.M.diagonal() << rho * A, rho * A, rho * A, rho * (Iy + Iz), rho * Iy, rho * Iz;
  return s;
}

const std::string& NastranCard::fileOf(std::size_t field) const {
  const std::string* f = &file;
  for (const auto& [first, other] : other_files)
    if (first <= field) f = &other;
  return *f;
}

std::vector<NastranCard> readNastranCards(const std::string& path) {
  Reader r;
  r.read(path, "", 0, 0);
  return r.cards;
}

bool isNastranFile(const std::string& path) {
  const std::string p = upper(path);
  for (const char* e : {".BDF", ".DAT", ".NAS", ".BULK"}) {
    const std::string s(e);
    if (p.size() >= s.size() && p.compare(p.size() - s.size(), s.size(), s) == 0) return true;
  }
  return false;
}

NastranModel nastranModel(const std::vector<NastranCard>& cards, const UnitSystem& units,
                          const std::vector<std::string>& ignore) {
  return Builder(cards, units, ignore).build();
}

void applyNastranDeck(BodySpec& spec) {
  GeneralMeshSpec& g = *spec.general;
  const UnitSystem* u = findUnitSystem(g.units);
  std::vector<NastranCard> cards;
  NastranModel model;
  try {
    cards = readNastranCards(g.file);
    if (cards.empty()) g.file_node.fail("the deck '" + g.file + "' has no bulk data cards");
    model = nastranModel(cards, *u, g.ignore);
  } catch (const InputError& e) {
    // Errors of the whole deck (no line to name: unsupported cards, no elements) at the YAML's key.
    if (e.line() == 0 && e.file() != g.file_node.file()) g.file_node.fail("the deck '" + g.file + "': " + e.message());
    throw;
  } catch (const std::exception& e) {
    g.file_node.fail(std::string("cannot read the Nastran deck: ") + e.what());
  }
  Mesh& mesh = model.mesh;
  // regions: PID<n> entries replace the deck's property of those elements.
  for (const auto& r : g.regions) {
    std::set<int> replaced;  // property indices already given the region's property
    auto it = std::find(mesh.groups.begin(), mesh.groups.end(), r.name);
    if (it == mesh.groups.end())
      r.node.fail("the deck has no elements with property '" + r.name + "'" + didYouMean(r.name, mesh.groups) +
                  "; expected PID<n> of a PSHELL, PCOMP, PBAR, PBARL, PBEAM or PROD its elements use");
    const int grp = static_cast<int>(it - mesh.groups.begin());
    for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
      if (mesh.triangle_group[e] != grp) continue;
      if (!r.shell) r.node.fail("region '" + r.name + "' has shell elements; expected shell: {...}");
      if (replaced.insert(mesh.triangle_property[e]).second) {
        ShellProperty& p = mesh.shell_properties[static_cast<std::size_t>(mesh.triangle_property[e])];
        p = r.shell_property;
        p.name = r.name;
      }
      mesh.triangle_axis[e] = regionAxisOnTriangle(r, mesh, static_cast<long>(e));
    }
    for (std::size_t e = 0; e < mesh.beams.size(); ++e) {
      if (mesh.beam_group[e] != grp) continue;
      if (r.shell) r.node.fail("region '" + r.name + "' has beam elements; expected beam: {...}");
      if (replaced.insert(mesh.beam_property[e]).second) {
        BeamProperty& p = mesh.beam_properties[static_cast<std::size_t>(mesh.beam_property[e])];
        p = r.beam_property;
        p.name = r.name;
      }
      mesh.beam_x2[e] = r.orientation.normalized();
    }
  }
  // Interfaces named by the deck's GRID and RBE ids.
  for (auto& i : spec.interfaces) {
    if (i.grid > 0) {
      auto n = model.node_of_grid.find(i.grid);
      if (n == model.node_of_grid.end())
        i.node.fail(model.grid_point.count(i.grid) ? "GRID " + std::to_string(i.grid) + " is on no element of the body; expected a grid of a shell or beam (or {rbe: EID})"
                                                   : "the deck has no GRID " + std::to_string(i.grid));
      i.position = mesh.nodes.row(n->second).transpose();
      i.coupling = Coupling::Node;
    } else if (i.rbe > 0) {
      auto r = model.rbes.find(i.rbe);
      if (r == model.rbes.end()) {
        std::string known;
        for (const auto& kv : model.rbes) known += (known.empty() ? "" : ", ") + std::to_string(kv.first);
        i.node.fail("the deck has no RBE2 or RBE3 with element id " + std::to_string(i.rbe) +
                    (known.empty() ? std::string("; it has none") : "; expected one of " + known));
      }
      i.position = r->second.point;
      i.coupling = r->second.rigid ? Coupling::Rigid : Coupling::Distributing;
      i.select = PatchSelect::Set;
      i.edge = "RBE" + std::to_string(i.rbe);
      i.nodes_node = i.node;
      if (!r->second.rigid) i.given_weights = r->second.weights;
    }
  }
  // masses: at points or interfaces (now that {grid:}/{rbe:} interfaces have points).
  for (auto& m : g.masses) {
    if (!m.interface.empty())
      for (const auto& i : spec.interfaces)
        if (i.name == m.interface) m.at = i.position;
    PointMass pm;
    pm.node = mesh.nearestNode(m.at);
    pm.point = mesh.nodes.row(pm.node).transpose();
    pm.mass = m.mass;
    pm.inertia = m.inertia;
    mesh.point_masses.push_back(pm);
  }
  // SPC1 sets are held as the deck says.
  for (const auto& r : spec.reference) {
    if (r.set.rfind("SPC", 0) != 0) continue;
    long sid = 0;
    try {
      sid = std::stol(r.set.substr(3));
    } catch (const std::exception&) {
      continue;
    }
    auto c = model.spc_components.find(sid);
    if (c == model.spc_components.end()) continue;
    if (r.clamp != (c->second == "123456"))
      r.node.fail("the deck's SPC1 set " + std::to_string(sid) + " holds components " + c->second + "; expected " +
                  (c->second == "123456" ? "clamp:" : "pin:") + " for it");
  }
  g.deck_mesh = std::make_shared<const Mesh>(std::move(mesh));
  g.deck_element_counts = model.element_counts;
}

}  // namespace fc::feprep
