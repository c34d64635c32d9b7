#include "common/termination.h"

#include "common/memory.h"

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <exception>
#include <new>
#include <string>

namespace fc {

namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGALRM, SIGXCPU, SIGPIPE};
constexpr int kSignalCount = sizeof(kSignals) / sizeof(kSignals[0]);

// Everything the handler touches is static storage and lock-free atomics: a
// signal handler may only call async-signal-safe functions (unlink, write, _exit).
std::atomic<int> g_signal{0};
std::atomic<long long> g_signal_ns{0};  // CLOCK_MONOTONIC time of the first signal
std::atomic<int> g_policy{static_cast<int>(TerminationPolicy::ExitNow)};
char g_prefix[128] = "flexcomp";

constexpr int kSlots = 32;
constexpr std::size_t kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 holds a path to remove
  char path[kPathMax];
};
Slot g_slots[kSlots];

const char* nameOf(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGQUIT: return "SIGQUIT";
    case SIGALRM: return "SIGALRM";
    case SIGXCPU: return "SIGXCPU";
    case SIGPIPE: return "SIGPIPE";
    default: return "a signal";
  }
}

void writeAll(const char* s) {
  std::size_t n = std::strlen(s);
  while (n > 0) {
    const ssize_t w = ::write(STDERR_FILENO, s, n);
    if (w <= 0) return;  // stderr gone (e.g. the SIGPIPE case): nothing to tell
    s += w;
    n -= static_cast<std::size_t>(w);
  }
}

[[noreturn]] void removeTemporariesAndExit(int sig, const char* what) {
  for (auto& slot : g_slots)
    if (slot.state.load() == 2) ::unlink(slot.path);
  writeAll(g_prefix);
  writeAll(": interrupted by ");
  writeAll(nameOf(sig));
  writeAll(what);
  ::_exit(terminationExitCode(sig));
}

// clock_gettime is async-signal-safe (POSIX.1-2008).
long long monotonicNs() {
  struct timespec ts {};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<long long>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

// One stop request often arrives twice: timeout(1) sends its SIGTERM to the
// child and then to the whole process group, a batch system may signal both the
// process and its group. The same signal again within this window is that
// duplicate, not a user asking a second time (the fuzzer found mbs-run under
// `timeout` exiting at once without its results file).
constexpr long long kDuplicateWindowNs = 1000000000LL;

extern "C" void onTerminationSignal(int sig) {
  int expected = 0;
  const bool first = g_signal.compare_exchange_strong(expected, sig);
  const bool record = g_policy.load() == static_cast<int>(TerminationPolicy::Record);
  if (first) g_signal_ns.store(monotonicNs());
  if (first && record) return;
  if (!first && record && expected == sig && monotonicNs() - g_signal_ns.load() < kDuplicateWindowNs) return;
  removeTemporariesAndExit(sig, first ? "; no output written\n"
                                      : " (second termination signal); stopped at once\n");
}

std::string g_fatal_context;

// Out of memory where no catch reaches (gmsh's OpenMP meshing loop): said as
// such, with the stage, exit 1; it is no input error, so no input location.
bool outOfMemoryNow() {
  const std::exception_ptr p = std::current_exception();
  if (!p) return false;
  try {
    std::rethrow_exception(p);
  } catch (const std::bad_alloc&) {
    return true;
  } catch (...) {
    return false;
  }
}

[[noreturn]] void onTerminate() {
  const std::string msg = currentExceptionMessage();
  const bool oom = outOfMemoryNow();
  for (auto& slot : g_slots)
    if (slot.state.load() == 2) ::unlink(slot.path);
  writeAll(g_prefix);
  writeAll(": error: ");
  if (!oom) writeAll(g_fatal_context.c_str());
  writeAll(msg.c_str());
  writeAll("\n");
  ::_exit(g_fatal_context.empty() || oom ? 1 : 2);
}

}  // namespace

FatalErrorContext::FatalErrorContext(const std::string& prefix) : previous_(g_fatal_context) {
  g_fatal_context = prefix;
}

FatalErrorContext::~FatalErrorContext() { g_fatal_context = previous_; }

void installTerminationHandlers(const std::string& tool, TerminationPolicy policy) {
  std::set_terminate(onTerminate);
  std::strncpy(g_prefix, tool.c_str(), sizeof g_prefix - 1);
  g_prefix[sizeof g_prefix - 1] = '\0';
  g_policy.store(static_cast<int>(policy));
  struct sigaction sa {};
  sa.sa_handler = onTerminationSignal;
  // Block the other termination signals while one is handled: the handler runs once.
  sigemptyset(&sa.sa_mask);
  for (int s : kSignals) sigaddset(&sa.sa_mask, s);
  sa.sa_flags = SA_RESTART;
  // A file-size limit (ulimit -f, batch systems) must fail the write (EFBIG, then a
  // clean error and the temporary removed), not kill the tool with a core dump.
  ::signal(SIGXFSZ, SIG_IGN);
  for (int s : kSignals) {
    struct sigaction old {};
    sigaction(s, nullptr, &old);
    // `nohup` asks for SIGHUP to be ignored: respect it. (INT and QUIT are not
    // checked: a non-interactive shell ignores them in background jobs, yet a
    // batch system's `kill -INT` must still stop the tool cleanly.)
    if (s == SIGHUP && old.sa_handler == SIG_IGN) continue;
    sigaction(s, &sa, nullptr);
  }
}

int terminationSignal() { return g_signal.load(); }

std::string signalName(int sig) { return nameOf(sig); }

void throwIfTerminated() {
  if (const int s = g_signal.load()) throw Terminated(s);
}

void resetTerminationForTests() {
  g_signal.store(0);
  g_signal_ns.store(0);
}
void raiseTerminationForTests(int sig) { g_signal.store(sig); }

const int* terminationSignals(int* count) {
  if (count) *count = kSignalCount;
  return kSignals;
}

TemporaryRegistration::TemporaryRegistration(const std::string& path) {
  if (path.size() >= kPathMax) throw std::runtime_error("temporary path too long: " + path);
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(2);
      slot_ = i;
      return;
    }
  }
  throw std::runtime_error("too many temporary files open at once (" + std::to_string(kSlots) +
                           ") to register " + path);
}

TemporaryRegistration::~TemporaryRegistration() { release(); }

TemporaryRegistration& TemporaryRegistration::operator=(TemporaryRegistration&& o) noexcept {
  if (this != &o) {
    release();
    slot_ = o.slot_;
    o.slot_ = -1;
  }
  return *this;
}

void TemporaryRegistration::release() {
  if (slot_ >= 0) {
    g_slots[slot_].state.store(0);
    slot_ = -1;
  }
}

std::string currentExceptionMessage() {
  const std::exception_ptr p = std::current_exception();
  if (!p) return "internal error (std::terminate without an exception)";
  try {
    std::rethrow_exception(p);
  } catch (const std::bad_alloc& e) {
    return outOfMemoryMessage(e, g_prefix);
  } catch (const std::exception& e) {
    return e.what();
  } catch (const std::string& s) {
    return s;
  } catch (const char* s) {
    return s ? s : "unknown error";
  } catch (...) {
    return "unknown error";
  }
}

}  // namespace fc
