#include "common/files.h"

#include <openssl/evp.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

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

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
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

void writeFileAtomic(const std::string& path, const std::string& content) {
  const std::string tmp = path + ".tmp-" + std::to_string(static_cast<long>(getpid()));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << content;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot write " + tmp);
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename " + tmp + " to " + path);
  }
}

std::string directoryOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  if (pos == std::string::npos) return ".";
  if (pos == 0) return "/";
  return path.substr(0, pos);
}

std::string resolveRelativeTo(const std::string& including_file, const std::string& path) {
  if (!path.empty() && path[0] == '/') return path;
  const std::string dir = directoryOf(including_file);
  return dir == "." ? path : dir + "/" + path;
}

}  // namespace fc
