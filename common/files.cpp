#include "common/files.h"

#include <fcntl.h>
#include <openssl/evp.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/input.h"
#include "common/termination.h"

namespace fc {

std::string sha256Hex(const std::string& data) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (EVP_Digest(data.data(), data.size(), digest, &len, EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256 failed");
  std::ostringstream os;
  for (unsigned int i = 0; i < len; ++i)
    os << std::hex << std::setw(2) << std::setfill('0') << static_cast<int>(digest[i]);
  return os.str();
}

namespace {
std::mutex g_inputs_mutex;
std::vector<std::string> g_inputs;
}  // namespace

void recordInputFile(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_inputs_mutex);
  if (std::find(g_inputs.begin(), g_inputs.end(), path) == g_inputs.end()) g_inputs.push_back(path);
}

std::vector<std::string> inputFilesRead() {
  std::lock_guard<std::mutex> lock(g_inputs_mutex);
  return g_inputs;
}

std::string readTextFile(const std::string& path) {
  recordInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path + ": " + osReason(errno));
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

std::string sha256File(const std::string& path) { return sha256Hex(readTextFile(path)); }

std::string sha256Files(const std::vector<std::string>& paths) {
  if (paths.size() == 1) return sha256File(paths[0]);
  std::string all;
  for (const auto& p : paths) all += sha256File(p);
  return sha256Hex(all);
}

std::string osReason(int err) { return std::strerror(err); }

std::string temporaryNameFor(const std::string& final_path) {
  static const char alphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  unsigned char bytes[12];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error("cannot draw a random temporary name: " + osReason(errno));
    }
    got += static_cast<std::size_t>(n);
  }
  std::string name = final_path + ".tmp-";
  for (unsigned char b : bytes) name += alphabet[b % (sizeof alphabet - 1)];
  return name;
}

namespace {

// Opens `path` for fsync without following a link; O_RDONLY suffices on Linux.
void fsyncOpen(const std::string& path, int flags, const char* what) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error(std::string("cannot open ") + what + " " + path + " to sync it: " +
                             osReason(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // EINVAL: the file system does not support syncing (e.g. some pseudo-fs); not an error.
  if (rc != 0 && err != EINVAL)
    throw std::runtime_error(std::string("cannot sync ") + what + " " + path + ": " + osReason(err));
}

}  // namespace

void fsyncFile(const std::string& path) { fsyncOpen(path, O_RDONLY | O_NOFOLLOW, "file"); }

void fsyncDirectoryOf(const std::string& path) {
  fsyncOpen(directoryOf(path), O_RDONLY | O_DIRECTORY, "directory");
}

StagedFile::StagedFile(const std::string& path, const std::string& content) : path_(path) {
  int fd = -1;
  for (int attempt = 0; attempt < 8 && fd < 0; ++attempt) {
    tmp_ = temporaryNameFor(path);
    fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) throw std::runtime_error("cannot create " + tmp_ + ": " + osReason(errno));
  registration_ = TemporaryRegistration(tmp_);
  auto fail = [&](const std::string& what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp_.c_str());
    tmp_.clear();
    throw std::runtime_error(what + ": " + osReason(err) + " (" + path + " left unchanged)");
  };
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write " + tmp_, errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 && errno != EINVAL) fail("cannot sync " + tmp_, errno);
  if (::close(fd) != 0) {
    fd = -1;
    fail("cannot close " + tmp_, errno);
  }
}

StagedFile::~StagedFile() {
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
}

void StagedFile::commit() {
  if (tmp_.empty()) throw std::logic_error("StagedFile::commit: nothing staged for " + path_);
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    const std::string tmp = tmp_;
    ::unlink(tmp.c_str());
    tmp_.clear();
    throw std::runtime_error("cannot rename " + tmp + " to " + path_ + ": " + osReason(err) + " (" + path_ +
                             " left unchanged)");
  }
  tmp_.clear();
  registration_.release();
  fsyncDirectoryOf(path_);
}

void writeFileAtomic(const std::string& path, const std::string& content) { StagedFile(path, content).commit(); }

void checkOutputWritable(const std::string& output) {
  if (output.empty()) throw std::runtime_error("the output path is empty");
  struct stat st {};
  if (::stat(output.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw std::runtime_error("cannot write " + output + ": it is a directory");
  const std::string dir = directoryOf(output);
  if (::stat(dir.c_str(), &st) != 0)
    throw std::runtime_error("cannot write " + output + ": directory " + dir + ": " +
                             osReason(errno));
  if (!S_ISDIR(st.st_mode))
    throw std::runtime_error("cannot write " + output + ": " + dir + " is not a directory");
  // A probe file tells the truth where access(2) does not (root, read-only mounts, ACLs).
  const std::string probe = temporaryNameFor(output);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0)
    throw std::runtime_error("cannot write " + output + ": cannot create a file in " + dir + ": " +
                             osReason(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

void checkOutputIsNotAnInput(const std::string& output, const std::vector<std::string>& inputs) {
  struct stat out {};
  if (::stat(output.c_str(), &out) != 0) return;  // no such file yet: cannot be an input
  for (const auto& in : inputs) {
    struct stat st {};
    if (::stat(in.c_str(), &st) != 0) continue;
    if (st.st_dev == out.st_dev && st.st_ino == out.st_ino)
      throw InputError(output, 0, 0, "",
                       "the output file is the input file " + in +
                           "; writing it would destroy that input: choose another output path");
  }
}

std::string directoryOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  if (pos == std::string::npos) return ".";
  if (pos == 0) return "/";
  return path.substr(0, pos);
}

std::string programDirectory() {
  char self[4096];
  const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
  if (len <= 0) return "";
  std::string dir(self, static_cast<std::size_t>(len));
  dir.resize(dir.rfind('/') + 1);
  return dir;
}

std::string resolveRelativeTo(const std::string& including_file, const std::string& path) {
  if (!path.empty() && path[0] == '/') return path;
  const std::string dir = directoryOf(including_file);
  return dir == "." ? path : dir + "/" + path;
}

}  // namespace fc
