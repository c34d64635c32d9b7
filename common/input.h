#pragma once
// YAML input with errors that point at the user's text: every error names the
// file, line, column and key path, says what is wrong and what is expected.
// All three tools read their inputs through InputNode so errors look alike.
#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <initializer_list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/units.h"

namespace fc {

// A bad input. what() is the full one-line message:
//   "scene.yaml:12:5: bodies[1].rigid.mass: expected a positive number, got '-3'"
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, int column, const std::string& key_path,
             const std::string& message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }  // 1-based, 0 when unknown
  int column() const { return column_; }
  const std::string& keyPath() const { return key_path_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_, key_path_, message_;
  int line_, column_;
};

// A YAML node that remembers where it came from (file, key path) so that any
// check made on it can report the exact place.
class InputNode {
 public:
  InputNode() = default;
  InputNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path);

  // Parses a YAML file; syntax errors become InputError with yaml-cpp's line.
  static InputNode loadFile(const std::string& path);
  // Parses YAML text (for tests); `name` stands for the file name in errors.
  static InputNode loadString(const std::string& text, const std::string& name = "<string>");

  bool isMap() const { return node_.IsMap(); }
  bool isSequence() const { return node_.IsSequence(); }
  bool isScalar() const { return node_.IsScalar(); }
  bool isNull() const { return !node_ || node_.IsNull(); }

  // The file's `units:` (nullptr: SI). Numbers read through asDouble and what uses it
  // (asPositive, asInRange, asLength, asVector, asMatrix, number) are converted to SI
  // by the dimension of their key (common/units.h); asInt never is.
  const UnitSystem* units() const { return units_.get(); }

  bool has(const std::string& key) const;  // present; a key without a value is an error at it
  // Required child: an InputError "missing key" if absent.
  InputNode operator[](const std::string& key) const;
  std::optional<InputNode> get(const std::string& key) const;
  std::vector<std::string> keys() const;  // map keys, in file order

  std::size_t size() const;               // sequence length (error if not a sequence)
  InputNode at(std::size_t i) const;      // sequence element

  double asDouble() const;
  double asPositive() const;              // > 0
  double asNonNegative() const;           // >= 0
  // A number in [lo, hi] (a physical range); the error names the range and unit.
  double asInRange(double lo, double hi, const std::string& unit, const std::string& why = "") const;
  // A positive length in [lo, hi] m.
  double asLength(double lo, double hi) const;
  long asInt() const;
  bool asBool() const;
  std::string asString() const;
  // A name the tools use as an HDF5 group or label (/bodies/NAME, /joints/NAME, a
  // body's name): not empty or blank, not '.' or '..', no '/' or control characters.
  std::string asName() const;
  Eigen::VectorXd asVector(int expected_size = -1) const;  // [a, b, c]
  Eigen::MatrixXd asMatrix(int rows, int cols) const;      // [[..],[..]]

  // Convenience: child value or a default.
  double number(const std::string& key, double fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  bool flag(const std::string& key, bool fallback) const;

  // Unknown keys are errors, with a did-you-mean suggestion.
  void allowKeys(std::initializer_list<const char*> allowed) const;
  void allowKeys(const std::vector<std::string>& allowed) const;

  // An error located at this node.
  [[noreturn]] void fail(const std::string& message) const;

  const std::string& file() const;
  int line() const;    // 1-based
  int column() const;  // 1-based
  const std::string& path() const { return path_; }
  const YAML::Node& raw() const { return node_; }
  std::shared_ptr<const std::string> fileHandle() const { return file_; }

 private:
  void failIfValueless(const std::string& key) const;
  InputNode child(YAML::Node node, std::string path, const std::string& key) const;
  YAML::Node node_;
  std::shared_ptr<const UnitSystem> units_;  // the file's units; null: SI
  double scale_ = 1.0;                        // SI value of one unit of this node's numbers
  std::shared_ptr<const std::string> file_;
  std::string path_;
};

// Resolves `include: FILE` (relative to the including file) for blocks such as
// `materials:` and `laminates:`; a block may mix an include with inline entries.
// Returns the merged entries as (name, node) pairs, inline entries last so they win.
std::vector<std::pair<std::string, InputNode>> namedEntries(const InputNode& block);

// Closest candidate by edit distance, or "" when nothing is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);
// The hint every "unknown NAME" message ends with: " (did you mean 'X'?)" for
// the closest candidate X, or "" when nothing is close.
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace fc
