// The serial program's file table: loaded from libflexcomp_feprep_h5.so on
// first use (file_io.h says why).
#include <dlfcn.h>
#include <malloc.h>
#include <unistd.h>

#include <mutex>
#include <stdexcept>
#include <string>

#include "common/files.h"
#include "common/memory.h"
#include "fe-prep/io/file_io.h"

namespace fc::feprep {

namespace {

constexpr const char* kModule = "libflexcomp_feprep_h5.so";

// The module's path: beside the program in the build tree (fe-prep/), in
// PREFIX/LIBDIR/flexcomp installed (FLEXCOMP_BIN_TO_MODULE_DIR from
// PREFIX/BINDIR, set by CMake from the install directories).
std::string modulePath() {
  const std::string dir = programDirectory();
  const std::string installed = dir + FLEXCOMP_BIN_TO_MODULE_DIR;
  for (const std::string& path : {dir + kModule, installed + kModule})
    if (access(path.c_str(), R_OK) == 0) return path;
  throw std::runtime_error(std::string("fe-prep's HDF5 module ") + kModule + " is in neither " + dir + " nor " +
                           installed + "; reinstall flexcomp (cmake --install), or run fe-prep-mpi");
}

const FileIO* load() {
  const std::string path = modulePath();
  // RTLD_NOW: a module that does not match this program fails here, whole,
  // not at its first call; RTLD_LOCAL keeps HDF5's symbols out of our scope.
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char* e = dlerror();
    const std::string reason = e ? e : path;
    // Under an address-space limit the loader cannot map the libraries: that
    // is memory, said as such (common/memory.h), not a broken installation.
    if (reason.find("map segment") != std::string::npos || reason.find("allocate memory") != std::string::npos)
      throw OutOfMemory("loading HDF5 (" + reason + ")");
    throw std::runtime_error("cannot load fe-prep's HDF5 module: " + reason + "; reinstall flexcomp, or run fe-prep-mpi");
  }
  using Entry = const FileIO* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(h, "flexcomp_feprep_file_io"));
  if (!entry) throw std::runtime_error(path + " is not fe-prep's HDF5 module (no flexcomp_feprep_file_io)");
  return entry();
}

}  // namespace

const FileIO& fileIO() {
  static std::once_flag once;
  static const FileIO* io = nullptr;
  std::call_once(once, [] { io = load(); });
  return *io;
}

void requireFileIO() { (void)modulePath(); }

void loadFileIOForWrite() {
  // The heap's free pages back to the system first: the module's libraries
  // then take pages the factorisations gave back, not new ones on top.
  malloc_trim(0);
  (void)fileIO();
}

}  // namespace fc::feprep
