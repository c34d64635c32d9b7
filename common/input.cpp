#include "common/input.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/files.h"

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

InputNode InputNode::loadString(const std::string& text, const std::string& name) {
  auto file = std::make_shared<const std::string>(name);
  try {
    YAML::Node root = YAML::Load(text);
    return InputNode(root, file, "");
  } catch (const YAML::Exception& e) {
    throw InputError(name, e.mark.line + 1, e.mark.column + 1, "",
                     "invalid YAML: " + e.msg);
  }
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

bool InputNode::has(const std::string& key) const {
  return node_.IsMap() && node_[key] && !node_[key].IsNull();
}

InputNode InputNode::operator[](const std::string& key) const {
  const std::string child_path = path_.empty() ? key : path_ + "." + key;
  if (!node_.IsMap()) fail("expected a map with key '" + key + "', got " + describe(node_));
  YAML::Node child = node_[key];
  if (!child || child.IsNull())
    throw InputError(file(), line(), column(), child_path, "missing required key '" + key + "'");
  return InputNode(child, file_, child_path);
}

std::optional<InputNode> InputNode::get(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return (*this)[key];
}

std::vector<std::string> InputNode::keys() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (const auto& kv : node_) out.push_back(kv.first.as<std::string>());
  return out;
}

std::size_t InputNode::size() const {
  if (!node_.IsSequence()) fail("expected a list, got " + describe(node_));
  return node_.size();
}

InputNode InputNode::at(std::size_t i) const {
  if (!node_.IsSequence()) fail("expected a list, got " + describe(node_));
  if (i >= node_.size()) fail("list has only " + std::to_string(node_.size()) + " entries");
  return InputNode(node_[i], file_, path_ + "[" + std::to_string(i) + "]");
}

double InputNode::asDouble() const {
  if (!node_.IsScalar()) fail("expected a number, got " + describe(node_));
  const std::string& s = node_.Scalar();
  try {
    std::size_t used = 0;
    double v = std::stod(s, &used);
    if (used != s.size()) throw std::invalid_argument(s);
    if (!std::isfinite(v)) fail("expected a finite number, got '" + s + "'");
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
    std::string msg = "unknown key '" + key + "'";
    const std::string guess = closestMatch(key, allowed);
    if (!guess.empty()) msg += " (did you mean '" + guess + "'?)";
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
      InputNode root;
      try {
        root = InputNode::loadFile(path);
      } catch (const InputError& e) {
        if (e.line() == 0) inc.fail("cannot read included file '" + path + "'");
        throw;
      }
      // An included file holds the entries directly, or under the same block name.
      const std::string block_name =
          block.path().substr(block.path().find_last_of('.') == std::string::npos
                                  ? 0
                                  : block.path().find_last_of('.') + 1);
      InputNode entries = (root.isMap() && root.has(block_name)) ? root[block_name] : root;
      for (auto& e : namedEntries(entries)) out.push_back(std::move(e));
    }
  }
  for (const auto& key : block.keys()) {
    if (key == "include") continue;
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
