#include "common/memory.h"

#include <sys/mman.h>

#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <vector>

namespace fc {

namespace {

std::vector<const StageScope*> g_active;   // running stages, outermost first
std::vector<std::string> g_failed_stages;  // the stages an exception left
bool g_failed = false;

std::vector<std::string> activeNames() {
  std::vector<std::string> out;
  for (const StageScope* s : g_active) out.push_back(s->name());
  return out;
}
std::size_t g_failed_allocation = 0;

// "VmPeak:   123456 kB" -> MB.
double procField(const char* file, const char* key) {
  std::ifstream in(file);
  std::string line;
  const std::size_t n = std::strlen(key);
  while (std::getline(in, line))
    if (line.compare(0, n, key) == 0 && line.size() > n && line[n] == ':') return std::atof(line.c_str() + n + 1) / 1024.0;
  return -1;
}

}  // namespace

double MemoryState::headroom_mb() const {
  double h = available_mb;
  if (limit_mb >= 0 && size_mb >= 0) {
    const double left = limit_mb - size_mb;
    h = h < 0 ? left : std::min(h, left);
  }
  return h;
}

MemoryState memoryState() {
  MemoryState s;
  s.available_mb = procField("/proc/meminfo", "MemAvailable");
  rlimit r{};
  if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY) s.limit_mb = static_cast<double>(r.rlim_cur) / (1024.0 * 1024.0);
  s.size_mb = procField("/proc/self/status", "VmSize");
  s.peak_mb = procField("/proc/self/status", "VmPeak");
  s.peak_rss_mb = procField("/proc/self/status", "VmHWM");
  return s;
}

std::string formatMegabytes(double mb) {
  char buf[64];
  if (mb >= 1024.0) std::snprintf(buf, sizeof buf, "%.1f GB", mb / 1024.0);
  else if (mb * 1024.0 < 1.0) std::snprintf(buf, sizeof buf, "%.0f bytes", mb * 1048576.0);
  else if (mb < 1.0) std::snprintf(buf, sizeof buf, "%.0f kB", mb * 1024.0);
  else std::snprintf(buf, sizeof buf, "%.0f MB", mb);
  return buf;
}

std::string describeMemory(const MemoryState& s) {
  std::ostringstream os;
  if (s.available_mb >= 0) os << formatMegabytes(s.available_mb) << " of RAM available (MemAvailable)";
  if (s.limit_mb >= 0) {
    os << (s.available_mb >= 0 ? "; " : "") << "address-space limit " << formatMegabytes(s.limit_mb) << " (ulimit -v)";
    if (s.size_mb >= 0) os << ", " << formatMegabytes(s.size_mb) << " in use";
  }
  if (s.peak_rss_mb >= 0) os << "; peak resident " << formatMegabytes(s.peak_rss_mb);
  return os.str();
}

StageScope::StageScope(std::string name)
    : name_(std::move(name)), uncaught_(std::uncaught_exceptions()) {
  // A stage begun in normal flow: an earlier failure was handled.
  if (uncaught_ == 0) g_failed = false;
  g_active.push_back(this);
}

void StageScope::end() {
  for (auto it = g_active.begin(); it != g_active.end(); ++it)
    if (*it == this) {
      g_active.erase(it);
      return;
    }
}

StageScope::~StageScope() {
  // Left by an exception: the first stage unwound is the innermost one, the
  // stage the error came from.
  if (std::uncaught_exceptions() > uncaught_ && !g_failed) {
    g_failed = true;
    g_failed_stages = activeNames();
  }
  end();
}

std::string failedStage(const std::string& skip) {
  const std::vector<std::string> stages = g_failed ? g_failed_stages : activeNames();
  std::string out;
  for (const std::string& s : stages)
    if (s != skip && s != out) out += (out.empty() ? "" : " / ") + s;
  return out;
}

std::size_t lastFailedAllocation() { return g_failed_allocation; }

void requireHeadroom(std::size_t bytes, const std::string& what) {
  // An address-space reservation, not malloc: a freed malloc block this large
  // raises glibc's dynamic mmap threshold, after which large buffers come from
  // the heap and stay resident once freed (a run's peak memory grew by it).
  void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (p == MAP_FAILED)
    throw OutOfMemory(what + " needs about " + formatMegabytes(static_cast<double>(bytes) / 1048576.0) + " more");
  ::munmap(p, bytes);
}

std::string outOfMemoryMessage(const std::bad_alloc& e, const std::string& tool) {
  std::ostringstream os;
  os << "out of memory";
  const std::string stage = failedStage(tool);
  if (!stage.empty()) os << " in stage '" << stage << "'";
  const bool specific = dynamic_cast<const OutOfMemory*>(&e) != nullptr;
  if (specific) os << ": " << e.what();
  else if (g_failed_allocation > 0)
    os << ": an allocation of " << formatMegabytes(static_cast<double>(g_failed_allocation) / (1024.0 * 1024.0))
       << " failed";
  const std::string mem = describeMemory(memoryState());
  if (!mem.empty()) os << " (" << mem << ")";
  os << "; no output was written. A coarser mesh, fewer modes or a shorter output history needs less; "
        "a larger memory limit or machine runs it as it is";
  return os.str();
}

}  // namespace fc

// The replaceable operator new, as the standard's default but remembering the
// size that failed, for the message above. Array, nothrow and sized forms of
// the library call this one; the aligned forms and Eigen's allocator do not
// (their failures are reported without a size).
void* operator new(std::size_t n) {
  if (n == 0) n = 1;
  for (;;) {
    if (void* p = std::malloc(n)) return p;
    std::new_handler h = std::get_new_handler();
    if (!h) {
      fc::g_failed_allocation = n;
      throw std::bad_alloc();
    }
    h();
  }
}
