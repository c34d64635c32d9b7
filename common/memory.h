#pragma once
// Memory exhaustion that ends cleanly: which stage was running, what it asked
// for, and how much the machine and the process limit allowed, so that an
// out-of-memory end reads as one sentence instead of std::bad_alloc.
//
// - StageScope names the stage being run (Progress opens one per progress bar);
//   when an exception leaves a stage, the innermost such stage is remembered,
//   so the top-level handler (guardedMain) can name it after the unwinding.
// - OutOfMemory is a std::bad_alloc with a message: what a library (PETSc,
//   MUMPS) or an estimate said was needed. Every catch that turns errors into
//   input errors lets std::bad_alloc through.
// - memoryState() reads MemAvailable (/proc/meminfo), the address-space limit
//   (RLIMIT_AS, `ulimit -v`) and the process's current and peak size.
#include <cstddef>
#include <new>
#include <string>

namespace fc {

class OutOfMemory : public std::bad_alloc {
 public:
  explicit OutOfMemory(std::string message) : message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

struct MemoryState {
  double available_mb = -1;   // MemAvailable, -1 if unknown
  double limit_mb = -1;       // RLIMIT_AS, -1 if unlimited
  double size_mb = -1;        // VmSize: the address space this process holds now
  double peak_mb = -1;        // VmPeak
  double peak_rss_mb = -1;    // VmHWM
  // What one more allocation can have: the smaller of MemAvailable and the
  // limit less VmSize (-1 if neither is known).
  double headroom_mb() const;
};
MemoryState memoryState();
// "1.2 GB", "830 MB".
std::string formatMegabytes(double mb);
// "MemAvailable 12.1 GB; address-space limit 900 MB (ulimit -v), 640 MB in use, peak 880 MB".
std::string describeMemory(const MemoryState& s);

// The stage being run, for the out-of-memory message ("eigen-solve", "reading the scene").
class StageScope {
 public:
  explicit StageScope(std::string name);
  ~StageScope();
  StageScope(const StageScope&) = delete;
  StageScope& operator=(const StageScope&) = delete;
  // The stage is over before the scope ends (a finished progress bar).
  void end();
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  int uncaught_;
};
// The stages an exception left (outermost first, "meshing / gmsh"), or the
// ones running now, or ""; a stage named SKIP (the tool's own progress bar) is left out.
std::string failedStage(const std::string& skip = "");
// The size of the last operator new that failed (bytes; 0 if none or unknown:
// Eigen's and C libraries' allocations are not seen).
std::size_t lastFailedAllocation();

// Throws OutOfMemory naming WHAT unless BYTES can be allocated now (allocated and
// freed at once). For libraries that do not check their own allocations: HDF5
// 1.10 dereferences a failed malloc in H5AC_create when a file is opened or
// created with a few MB left under the limit (a segmentation fault, found under
// ulimit -v).
void requireHeadroom(std::size_t bytes, const std::string& what);

// The whole message for a std::bad_alloc caught at the top: stage, what was
// needed, the machine's and the process's memory, and what needs less.
std::string outOfMemoryMessage(const std::bad_alloc& e, const std::string& tool = "");

}  // namespace fc
