#include "common/input.h"

#include <climits>
#include <cstdlib>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/files.h"
#include "common/memory.h"

namespace fc {

namespace {

std::string formatLocation(const std::string& file, int line, int column,
                           const std::string& key_path, const std::string& message) {
  std::ostringstream os;
  os << file;
  if (line > 0) {
    os << ":" << line;
    if (column > 0) os << ":" << column;
  }
  os << ": ";
  if (!key_path.empty()) os << key_path << ": ";
  os << message;
  return os.str();
}

std::string describe(const YAML::Node& n) {
  if (!n || n.IsNull()) return "nothing";
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  return "an undefined value";
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

InputError::InputError(const std::string& file, int line, int column, const std::string& key_path,
                       const std::string& message)
    : std::runtime_error(formatLocation(file, line, column, key_path, message)),
      file_(file),
      key_path_(key_path),
      message_(message),
      line_(line),
      column_(column) {}

InputNode::InputNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

InputNode InputNode::loadFile(const std::string& path) {
  std::string text;
  try {
    text = readTextFile(path);
  } catch (const std::exception& e) {
    throw InputError(path, 0, 0, "", "cannot read the file (" + std::string(e.what()) + ")");
  }
  return loadString(text, path);
}

namespace {

std::string describeKeyPath(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

// Checks what yaml-cpp accepts but flexcomp must not: duplicate keys (yaml-cpp
// keeps the first silently), non-scalar ("complex") keys, and nesting so deep
// that recursive code would exhaust the stack. Iterative, so it cannot overflow.
void validateTree(const YAML::Node& root, const std::string& file) {
  constexpr std::size_t kMaxDepth = 64;
  struct Item {
    YAML::Node node;
    std::string path;
    std::size_t depth;
  };
  std::vector<Item> stack{{root, "", 0}};
  // Aliases share nodes: "billion laughs" (&a [*b, *b, ...] nested) expands to an
  // exponential tree. No flexcomp input comes near this many nodes.
  constexpr std::size_t kMaxNodes = 200000;
  std::size_t visited = 0;
  while (!stack.empty()) {
    Item it = std::move(stack.back());
    stack.pop_back();
    if (++visited > kMaxNodes) {
      const YAML::Mark m = it.node.Mark();
      throw InputError(file, m.line + 1, m.column + 1, it.path,
                       "the document expands to more than " + std::to_string(kMaxNodes) +
                           " values (nested aliases?); flexcomp inputs are far smaller");
    }
    const YAML::Mark m = it.node.Mark();
    if (it.depth > kMaxDepth)
      throw InputError(file, m.line + 1, m.column + 1, it.path,
                       "nesting deeper than " + std::to_string(kMaxDepth) + " levels");
    if (it.node.IsMap()) {
      std::vector<std::pair<std::string, YAML::Mark>> seen;
      for (const auto& kv : it.node) {
        const YAML::Mark km = kv.first.Mark();
        if (!kv.first.IsScalar())
          throw InputError(file, km.line + 1, km.column + 1, it.path,
                           "a key must be a plain name, got a " +
                               std::string(kv.first.IsMap() ? "map" : kv.first.IsSequence() ? "list" : "null") +
                               " as key (a stray '?' or '[' before a key?)");
        const std::string key = kv.first.Scalar();
        for (const auto& [k, where] : seen)
          if (k == key)
            throw InputError(file, km.line + 1, km.column + 1, describeKeyPath(it.path, key),
                             "duplicate key '" + key + "' (first given at line " +
                                 std::to_string(where.line + 1) + ", column " +
                                 std::to_string(where.column + 1) + "); give each key once");
        seen.emplace_back(key, km);
        stack.push_back({kv.second, describeKeyPath(it.path, key), it.depth + 1});
      }
    } else if (it.node.IsSequence()) {
      for (std::size_t i = 0; i < it.node.size(); ++i)
        stack.push_back({it.node[i], it.path + "[" + std::to_string(i) + "]", it.depth + 1});
    }
  }
}

}  // namespace

InputNode InputNode::loadString(const std::string& text, const std::string& name) {
  auto file = std::make_shared<const std::string>(name);
  // yaml-cpp's parser recurses once per nesting level: a few thousand '[' would
  // overflow the stack before any check of ours runs. Count the flow nesting first.
  {
    int depth = 0, line = 1, worst_line = 0;
    for (char c : text) {
      if (c == '\n') ++line;
      if (c == '[' || c == '{') {
        if (++depth > 64 && worst_line == 0) worst_line = line;
      } else if ((c == ']' || c == '}') && depth > 0) {
        --depth;
      }
    }
    if (worst_line > 0)
      throw InputError(name, worst_line, 0, "", "brackets nested deeper than 64 levels");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(name, e.mark.line + 1, e.mark.column + 1, "",
                     "invalid YAML: " + e.msg);
  } catch (const std::bad_alloc&) {
    // Out of memory is no input error: exit 1 with the stage (common/memory.h).
    throw OutOfMemory("parsing " + name + " (" + std::to_string(text.size()) + " bytes of YAML)");
  }
  validateTree(root, name);
  InputNode top(root, file, "");
  // `units:` (default SI): every number of this file is converted when it is read.
  if (top.isMap() && top.has("units")) {
    const InputNode u = top["units"];
    UnitSystem system;
    if (u.isMap()) {
      u.allowKeys({"length", "mass", "time"});
      system.name = "custom";
      system.length = u["length"].asPositive();
      system.mass = u["mass"].asPositive();
      system.time = u["time"].asPositive();
    } else {
      const std::string n = u.asString();
      const UnitSystem* found = findUnitSystem(n);
      if (!found) {
        std::vector<std::string> names;
        std::string list;
        for (const UnitSystem& k : unitSystems()) {
          names.push_back(k.name);
          list += (list.empty() ? "" : ", ") + k.name;
        }
        u.fail("unknown unit system '" + n + "'" + didYouMean(n, names) +
               "; expected one of " + list + ", or {length: m, mass: kg, time: s}");
      }
      system = *found;
    }
    if (!system.isSI()) top.units_ = std::make_shared<const UnitSystem>(system);
  }
  return top;
}

// A child node: it keeps the file's units, and its numbers take the dimension of
// its key (common/units.h), or of the enclosing key when the table has none for it.
InputNode InputNode::child(YAML::Node node, std::string path, const std::string& key) const {
  InputNode c(std::move(node), file_, std::move(path));
  c.units_ = units_;
  c.scale_ = scale_;
  if (units_ && !key.empty()) {
    std::string type;
    if (node_.IsMap() && node_["type"] && node_["type"].IsScalar()) type = node_["type"].Scalar();
    Dimension d;
    if (keyDimension(key, type, d)) c.scale_ = toSI(*units_, d);
  }
  return c;
}

const std::string& InputNode::file() const {
  static const std::string unknown = "<input>";
  return file_ ? *file_ : unknown;
}

int InputNode::line() const {
  if (!node_) return 0;
  const YAML::Mark m = node_.Mark();
  return m.line >= 0 ? m.line + 1 : 0;
}

int InputNode::column() const {
  if (!node_) return 0;
  const YAML::Mark m = node_.Mark();
  return m.column >= 0 ? m.column + 1 : 0;
}

void InputNode::fail(const std::string& message) const {
  throw InputError(file(), line(), column(), path_, message);
}

// A key written without a value (`static_correction:` or `key: ~`) is an error at
// that key, not an absent key: read as absent, an optional key silently took its
// default (the fuzzer's `static_correction: null` built a body without the
// correction, exit 0). Every optional key is read through has() or get().
void InputNode::failIfValueless(const std::string& key) const {
  if (!node_.IsMap()) return;
  const YAML::Node child = node_[key];
  if (!child || !child.IsNull()) return;
  const YAML::Mark m = child.Mark();
  const bool located = m.line >= 0;
  throw InputError(file(), located ? m.line + 1 : line(), located ? m.column + 1 : column(),
                   path_.empty() ? key : path_ + "." + key,
                   "the key is given without a value; expected a value (remove the key to use its default)");
}

bool InputNode::has(const std::string& key) const {
  failIfValueless(key);
  return node_.IsMap() && node_[key];
}

InputNode InputNode::operator[](const std::string& key) const {
  const std::string child_path = path_.empty() ? key : path_ + "." + key;
  if (!node_.IsMap()) fail("expected a map with key '" + key + "', got " + describe(node_));
  failIfValueless(key);
  YAML::Node child = node_[key];
  if (!child) throw InputError(file(), line(), column(), child_path, "missing required key '" + key + "'");
  return this->child(child, child_path, key);
}

std::optional<InputNode> InputNode::get(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return (*this)[key];
}

std::vector<std::string> InputNode::keys() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) {
      const YAML::Mark m = kv.first.Mark();
      throw InputError(file(), m.line + 1, m.column + 1, path_, "a key must be a plain name");
    }
    out.push_back(kv.first.Scalar());
  }
  return out;
}

std::size_t InputNode::size() const {
  if (!node_.IsSequence()) fail("expected a list, got " + describe(node_));
  return node_.size();
}

InputNode InputNode::at(std::size_t i) const {
  if (!node_.IsSequence()) fail("expected a list, got " + describe(node_));
  if (i >= node_.size()) fail("list has only " + std::to_string(node_.size()) + " entries");
  return child(node_[i], path_ + "[" + std::to_string(i) + "]", "");
}

double InputNode::asDouble() const {
  if (!node_.IsScalar()) fail("expected a number, got " + describe(node_));
  const std::string& s = node_.Scalar();
  try {
    std::size_t used = 0;
    double v = std::stod(s, &used);
    if (used != s.size()) throw std::invalid_argument(s);
    if (!std::isfinite(v)) fail("expected a finite number, got '" + s + "'");
    v *= scale_;  // to SI (1 unless the file gives units:)
    if (!std::isfinite(v)) fail("expected a finite number, got '" + s + "' (infinite in SI units)");
    return v;
  } catch (const std::logic_error&) {
    fail("expected a number, got '" + s + "'");
  }
}

double InputNode::asPositive() const {
  double v = asDouble();
  if (!(v > 0)) fail("expected a positive number, got '" + node_.Scalar() + "'");
  return v;
}

double InputNode::asInRange(double lo, double hi, const std::string& unit,
                            const std::string& why) const {
  const double v = asDouble();
  if (!(v >= lo && v <= hi)) {
    std::ostringstream os;
    os << "expected a value in [" << lo << ", " << hi << "] " << unit << ", got '" << node_.Scalar()
       << "'";
    if (scale_ != 1.0) os << " = " << v << " " << unit << " in SI (the file's units: " << units_->name << ")";
    if (!why.empty()) os << " (" << why << ")";
    fail(os.str());
  }
  return v;
}

double InputNode::asLength(double lo, double hi) const {
  if (!(asDouble() > 0)) fail("expected a positive length, got '" + node_.Scalar() + "'");
  return asInRange(lo, hi, "m", "SI units; outside this range the value is a unit mistake or typo");
}

double InputNode::asNonNegative() const {
  double v = asDouble();
  if (v < 0) fail("expected a number >= 0, got '" + node_.Scalar() + "'");
  return v;
}

long InputNode::asInt() const {
  if (!node_.IsScalar()) fail("expected an integer, got " + describe(node_));
  const std::string& s = node_.Scalar();
  try {
    std::size_t used = 0;
    long v = std::stol(s, &used);
    if (used != s.size()) throw std::invalid_argument(s);
    return v;
  } catch (const std::logic_error&) {
    fail("expected an integer, got '" + s + "'");
  }
}

bool InputNode::asBool() const {
  if (!node_.IsScalar()) fail("expected true or false, got " + describe(node_));
  const std::string& s = node_.Scalar();
  if (s == "true" || s == "True" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "False" || s == "no" || s == "off") return false;
  fail("expected true or false, got '" + s + "'");
}

std::string InputNode::asString() const {
  if (!node_.IsScalar()) fail("expected a string, got " + describe(node_));
  return node_.Scalar();
}

std::string InputNode::asName() const {
  const std::string name = asString();
  const bool blank = name.find_first_not_of(" \t") == std::string::npos;
  const bool control = std::any_of(name.begin(), name.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  });
  // At most 1024 characters: names are also written as attribute values (the summary's
  // peaks), and HDF5 keeps a root's attributes within 64 kB.
  if (blank || name == "." || name == ".." || name.find('/') != std::string::npos || control ||
      name.size() > 1024)
    fail("expected a name usable as a results group (not empty or blank, '.', '..', without '/' "
         "or control characters, at most 1024 characters), got '" +
         (control ? std::string("(control characters)")
                  : name.size() > 1024 ? name.substr(0, 40) + "...' (" + std::to_string(name.size()) + " characters)" : name + "'"));
  return name;
}

Eigen::VectorXd InputNode::asVector(int expected_size) const {
  if (!node_.IsSequence())
    fail(expected_size > 0 ? "expected a list of " + std::to_string(expected_size) + " numbers, got " +
                                 describe(node_)
                           : "expected a list of numbers, got " + describe(node_));
  const int n = static_cast<int>(node_.size());
  if (expected_size >= 0 && n != expected_size)
    fail("expected a list of " + std::to_string(expected_size) + " numbers, got " +
         std::to_string(n));
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = at(i).asDouble();
  return v;
}

Eigen::MatrixXd InputNode::asMatrix(int rows, int cols) const {
  const std::string what = "expected a " + std::to_string(rows) + "x" + std::to_string(cols) +
                           " matrix as a list of rows [[..], ..]";
  if (!node_.IsSequence() || static_cast<int>(node_.size()) != rows) fail(what);
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i) m.row(i) = at(i).asVector(cols).transpose();
  return m;
}

double InputNode::number(const std::string& key, double fallback) const {
  auto c = get(key);
  return c ? c->asDouble() : fallback;
}

std::string InputNode::string(const std::string& key, const std::string& fallback) const {
  auto c = get(key);
  return c ? c->asString() : fallback;
}

bool InputNode::flag(const std::string& key, bool fallback) const {
  auto c = get(key);
  return c ? c->asBool() : fallback;
}

void InputNode::allowKeys(std::initializer_list<const char*> allowed) const {
  allowKeys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void InputNode::allowKeys(const std::vector<std::string>& allowed) const {
  if (!node_.IsMap()) fail("expected a map, got " + describe(node_));
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string msg = "unknown key '" + key + "'" + didYouMean(key, allowed);
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    msg += "; expected one of: " + list;
    const YAML::Mark m = kv.first.Mark();
    throw InputError(file(), m.line + 1, m.column + 1, path_.empty() ? key : path_ + "." + key,
                     msg);
  }
}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    std::size_t d = editDistance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string guess = closestMatch(word, candidates);
  return guess.empty() ? "" : " (did you mean '" + guess + "'?)";
}

namespace {

// Entry names from an included file: plain names only. Anything else means the
// file is not a flexcomp materials/laminates file, and quoting its keys in an
// error would echo the content of whatever file was named (/etc/shadow...).
bool isPlainName(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == '+'))
      return false;
  return true;
}

// Files being included, outermost first: a file met again is a cycle.
thread_local std::vector<std::string> t_include_chain;

std::string canonicalOrSame(const std::string& path) {
  char buf[PATH_MAX];
  return ::realpath(path.c_str(), buf) ? std::string(buf) : path;
}

}  // namespace

std::vector<std::pair<std::string, InputNode>> namedEntries(const InputNode& block) {
  std::vector<std::pair<std::string, InputNode>> out;
  if (!block.isMap()) block.fail("expected a map of named entries (or include: FILE)");
  if (block.has("include")) {
    InputNode inc = block["include"];
    std::vector<std::string> files;
    if (inc.isSequence()) {
      for (std::size_t i = 0; i < inc.size(); ++i) files.push_back(inc.at(i).asString());
    } else {
      files.push_back(inc.asString());
    }
    for (const auto& f : files) {
      const std::string path = resolveRelativeTo(block.file(), f);
      const std::string canon = canonicalOrSame(path);
      const std::string here = canonicalOrSame(block.file());
      std::vector<std::string> chain = t_include_chain;
      if (chain.empty()) chain.push_back(here);
      if (std::find(chain.begin(), chain.end(), canon) != chain.end()) {
        std::string cycle;
        for (const auto& c : chain) cycle += c + " -> ";
        inc.fail("include cycle: " + cycle + canon + "; a file cannot include itself");
      }
      if (chain.size() > 16) inc.fail("includes nested deeper than 16 files");
      InputNode root;
      try {
        root = InputNode::loadFile(path);
      } catch (const InputError& e) {
        // Only the reason, never the included file's text: it may be any file.
        if (e.line() == 0) inc.fail("cannot read included file '" + path + "'");
        // A .yaml file was meant to be read: give yaml-cpp's reason. Any other file
        // (a typo naming /etc/shadow...) gets the line only.
        const bool yaml = path.size() > 5 && (path.rfind(".yaml") == path.size() - 5 ||
                                              path.rfind(".yml") == path.size() - 4);
        inc.fail("included file '" + path + "' line " + std::to_string(e.line()) + ": " +
                 (yaml ? e.message() : std::string("not valid YAML")));
      }
      // An included file holds the entries directly, or under the same block name.
      const std::string block_name =
          block.path().substr(block.path().find_last_of('.') == std::string::npos
                                  ? 0
                                  : block.path().find_last_of('.') + 1);
      InputNode entries = (root.isMap() && root.has(block_name)) ? root[block_name] : root;
      if (!entries.isMap())
        inc.fail("included file '" + path + "' does not hold a map of named " + block_name +
                 " entries");
      for (const auto& key : entries.keys())
        if (!isPlainName(key))
          inc.fail("included file '" + path + "' is not a flexcomp " + block_name +
                   " file: its entries must be plain names (letters, digits, _ - . +)");
      chain.push_back(canon);
      std::swap(chain, t_include_chain);
      try {
        for (auto& e : namedEntries(entries)) out.push_back(std::move(e));
      } catch (...) {
        std::swap(chain, t_include_chain);
        throw;
      }
      std::swap(chain, t_include_chain);
    }
  }
  for (const auto& key : block.keys()) {
    if (key == "include") continue;
    if (key == "units" && block.path().empty()) continue;  // an included file's own units
    InputNode child = block[key];
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == key; });
    if (it != out.end())
      it->second = child;  // inline entries override included ones
    else
      out.emplace_back(key, child);
  }
  return out;
}

}  // namespace fc
