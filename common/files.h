#pragma once
// Small file utilities shared by the tools: hashing inputs, atomic writes, and the
// checks on an output path every tool makes before it starts computing.
#include <string>
#include <vector>

#include "common/termination.h"

namespace fc {

std::string sha256Hex(const std::string& data);
// SHA-256 of a file's bytes; throws std::runtime_error if unreadable.
std::string sha256File(const std::string& path);
// SHA-256 over several files (their hashes concatenated in order), for provenance.
std::string sha256Files(const std::vector<std::string>& paths);

std::string readTextFile(const std::string& path);

// Atomic text write: the content goes to a temporary created exclusively beside
// `path` (O_CREAT|O_EXCL|O_NOFOLLOW, unpredictable name, registered with the
// termination handler), every write checked, fsync'ed, renamed onto `path`, and
// the directory fsync'ed. On any error the temporary is removed, `path` keeps its
// previous content, and std::runtime_error names the file and the OS reason.
void writeFileAtomic(const std::string& path, const std::string& content);

// writeFileAtomic in two steps, for a file that must change together with
// another one (fe-prep's .xdmf view of its .h5): the constructor writes and
// fsyncs the temporary (throwing as writeFileAtomic, `path` unchanged),
// commit() renames it onto `path`; destroyed without commit() it removes the
// temporary. Writing the small companion first means a full disk stops the
// run before either file changes, and a failed main write leaves both.
class StagedFile {
 public:
  StagedFile(const std::string& path, const std::string& content);
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  void commit();

 private:
  std::string path_, tmp_;
  TemporaryRegistration registration_;
};

// "PATH.tmp-XXXXXXXXXXXX": a temporary name beside `final_path` with 12 random
// characters (from the kernel's random source), so no one can plant a link at it.
std::string temporaryNameFor(const std::string& final_path);
// fsync of a file's content, and of the directory holding `path` (makes a rename
// durable). Throw std::runtime_error with strerror on failure.
void fsyncFile(const std::string& path);
void fsyncDirectoryOf(const std::string& path);
// "strerror(errno)" as a std::string.
std::string osReason(int err);

// Checks, before any computing, that `output` can be written: its directory
// exists and accepts a new file (a probe file is created exclusively and removed),
// and `output` is not a directory. Throws std::runtime_error naming the path and
// the OS reason.
void checkOutputWritable(const std::string& output);
// Throws fc::InputError when `output` is the same file as one of `inputs`
// (same device and inode, so links and ./a vs a are caught): writing it would
// destroy that input. Inputs that do not exist are skipped.
void checkOutputIsNotAnInput(const std::string& output, const std::vector<std::string>& inputs);

// Every file a tool has read so far (YAML through readTextFile, HDF5 through
// H5File in Read mode), deduplicated: the inputs an output must not overwrite.
void recordInputFile(const std::string& path);
std::vector<std::string> inputFilesRead();

// Directory part of a path ("." when none), and path joined relative to a file's dir.
std::string directoryOf(const std::string& path);
// The directory of this program's executable with its trailing '/', by
// /proc/self/exe ("" if unreadable: a name then resolves from the working
// directory): where a tool finds what is installed beside it (fe-prep-mpi,
// fe-prep's HDF5 module, PREFIX/share/doc).
std::string programDirectory();
std::string resolveRelativeTo(const std::string& including_file, const std::string& path);

}  // namespace fc
