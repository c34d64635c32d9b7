#pragma once
// Small file utilities shared by the tools: hashing inputs and atomic text writes.
#include <string>
#include <vector>

namespace fc {

std::string sha256Hex(const std::string& data);
// SHA-256 of a file's bytes; throws std::runtime_error if unreadable.
std::string sha256File(const std::string& path);
// SHA-256 over several files (their hashes concatenated in order), for provenance.
std::string sha256Files(const std::vector<std::string>& paths);

std::string readTextFile(const std::string& path);
// Writes to PATH.tmp-PID, then renames onto path.
void writeFileAtomic(const std::string& path, const std::string& content);
// Directory part of a path ("." when none), and path joined relative to a file's dir.
std::string directoryOf(const std::string& path);
std::string resolveRelativeTo(const std::string& including_file, const std::string& path);

}  // namespace fc
