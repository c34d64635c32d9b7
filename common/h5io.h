#pragma once
// HDF5 reading and writing of the layouts in contracts.md, through RAII handles.
// Matrices are stored row-major (HDF5's own order), float64. Every file carries a
// `format` attribute ("section/1", "flexbody/1", "results/1") checked on read.
// Files are written atomically: AtomicH5Writer writes an exclusively created
// NAME.tmp-RANDOM, checks it to the close and renames it on commit(), so a crash,
// a signal or a full disk never leaves a half-written NAME behind.
#include <hdf5.h>

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/h5error.h"
#include "common/termination.h"

namespace fc {

class H5File {
 public:
  // Create truncates; CreateExclusive fails if anything (even a link) is at the path.
  enum class Mode { Read, Create, CreateExclusive };
  H5File() = default;
  H5File(const std::string& path, Mode mode);
  ~H5File();
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;
  H5File(H5File&& o) noexcept;
  H5File& operator=(H5File&& o) noexcept;

  // Takes ownership of an open file identifier.
  static H5File adopt(hid_t id, const std::string& path);
  void close();  // errors ignored (for destructors and error paths)
  // Flushes and closes, throwing H5Error with the OS reason on failure.
  void closeChecked();
  bool isOpen() const { return id_ >= 0; }
  hid_t id() const { return id_; }
  const std::string& path() const { return path_; }

  bool exists(const std::string& object_path) const;  // dataset or group
  std::vector<std::string> children(const std::string& group_path) const;

  // Writers create intermediate groups. Matrices: (rows, cols); vectors: (n).
  void writeMatrix(const std::string& path, const Eigen::MatrixXd& m);
  void writeVector(const std::string& path, const Eigen::VectorXd& v);
  void writeScalar(const std::string& path, double value);
  void writeInt(const std::string& path, long value);
  void writeIntVector(const std::string& path, const std::vector<long>& v);
  void writeIntMatrix(const std::string& path, const Eigen::Matrix<long, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& m);
  void writeString(const std::string& path, const std::string& value);
  // (n) fixed-length strings, padded to the longest.
  void writeStrings(const std::string& path, const std::vector<std::string>& values);
  // Rank-3 array (n0, n1, n2), data in C order.
  void writeArray3(const std::string& path, const std::vector<double>& data, std::size_t n0,
                   std::size_t n1, std::size_t n2);
  void createGroup(const std::string& path);

  // Attributes on an object ("/" for the root).
  void setAttribute(const std::string& object_path, const std::string& name, const std::string& value);
  void setAttribute(const std::string& object_path, const std::string& name, double value);
  void setAttribute(const std::string& object_path, const std::string& name, long value);
  bool hasAttribute(const std::string& object_path, const std::string& name) const;
  std::string stringAttribute(const std::string& object_path, const std::string& name) const;
  double doubleAttribute(const std::string& object_path, const std::string& name) const;

  std::vector<hsize_t> shape(const std::string& path) const;
  Eigen::MatrixXd readMatrix(const std::string& path) const;  // rank 1 -> (n, 1)
  // Exactly (rows, cols) and finite, else H5Error naming the file, dataset and shape.
  Eigen::MatrixXd readMatrix(const std::string& path, Eigen::Index rows, Eigen::Index cols) const;
  Eigen::VectorXd readVector(const std::string& path) const;
  double readScalar(const std::string& path) const;
  long readInt(const std::string& path) const;
  std::vector<long> readIntVector(const std::string& path) const;  // any rank, flattened
  std::string readString(const std::string& path) const;
  // (n) fixed- or variable-length strings.
  std::vector<std::string> readStrings(const std::string& path) const;
  std::vector<double> readArray(const std::string& path) const;   // any rank, flattened C order

  // Checks the root `format` attribute: "KIND/VERSION". Throws H5Error naming the
  // file when the kind differs or the version is newer than `max_version`.
  // Returns the version found.
  int checkFormat(const std::string& kind, int max_version) const;

 private:
  hid_t id_ = -1;
  std::string path_;
};

// Writes to a temporary beside `final_path` (created exclusively under a random
// name, registered with the termination handler). commit() annotates, refuses
// non-finite numbers, flushes and closes with every error checked, fsyncs, reads
// the file back, renames it onto final_path and fsyncs the directory. Destroyed
// without a successful commit(), it removes the temporary: final_path keeps its
// previous content.
class AtomicH5Writer {
 public:
  explicit AtomicH5Writer(const std::string& final_path);
  ~AtomicH5Writer();
  AtomicH5Writer(const AtomicH5Writer&) = delete;
  AtomicH5Writer& operator=(const AtomicH5Writer&) = delete;
  H5File& file() { return file_; }
  const std::string& temporaryPath() const { return tmp_path_; }
  void commit();

 private:
  std::string final_path_, tmp_path_;
  H5File file_;
  std::unique_ptr<TemporaryRegistration> registration_;
  bool committed_ = false;
};

// One entry of walkTree: the link at `path` (`name` within its group, `depth` 0 for the
// group walked), what it leads to, and whether that object was already met through
// another link (then a group is not entered again).
struct H5TreeEntry {
  enum class Kind { Group, Dataset, Other, External, Dangling };
  std::string path, name;
  int depth = 0;
  Kind kind = Kind::Other;
  bool seen_before = false;
  std::string target;  // soft and external links: where the link points
};

// Visits every link below `group` once, depth first in name order, without recursion.
// `enter(entry)` is called for each link; for a group not met before, returning true
// walks its contents. Objects are identified by file and address (H5Oget_info), so a
// group linked into itself or an ancestor (a hard or soft link cycle, as a damaged or
// hostile file can hold) is entered once and every walk ends. External links are
// reported, never followed (they would open another file).
void walkTree(const H5File& f, const std::string& group,
              const std::function<bool(const H5TreeEntry&)>& enter);

// Throws H5Error naming the dataset or attribute when a float one holds NaN/inf.
void checkAllFinite(const H5File& f);

// " (OS or HDF5 reason)" from HDF5's current error stack, or "" when none.
std::string hdf5ErrorReason();

// Root attributes every output carries: format, units, tool, version, input hash.
void writeProvenance(H5File& f, const std::string& format, const std::string& tool,
                     const std::string& inputs_sha256);

}  // namespace fc
