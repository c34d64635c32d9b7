#pragma once
// Termination signals (INT, TERM, HUP, QUIT, ALRM, XCPU, PIPE): what a batch system
// or a user sends to stop a tool. One module so that the three tools agree on them.
//
// API (all in namespace fc):
//
//   installTerminationHandlers(tool, policy)
//       Installs one handler for the seven signals (call once, early in main),
//       ignores SIGXFSZ (a file-size limit then fails the write with EFBIG, which
//       the atomic writers report) and installs the std::terminate handler below.
//       Policy::ExitNow   (section-prep, fe-prep): the handler removes every
//           registered temporary file, writes "TOOL: interrupted by SIGxxx; no
//           output written" to stderr and _exit(128 + signal). Nothing partial
//           is left, whatever the tool was doing (inside gmsh, a factorisation...).
//       Policy::Record    (mbs-run): the handler only records the signal; the
//           run loop polls terminationSignal() and finishes its results file
//           with a status. A SECOND termination signal while the first is
//           pending acts as ExitNow (removes temporaries, exits), so a loop that
//           fails to poll can still be stopped; the same signal repeated within
//           1 s is taken as one request delivered twice (timeout(1) signals the
//           child and then its process group) and only recorded.
//
//   int  terminationSignal()      0, or the first signal received (async-safe read).
//   void throwIfTerminated()      throws fc::Terminated when a signal is pending:
//                                 call it from long loops when under Policy::Record.
//   std::string signalName(int)   "SIGTERM", ...
//   int  terminationExitCode(int) 128 + signal (the shell convention).
//   void resetTerminationForTests()  clears the recorded signal (tests only).
//   void raiseTerminationForTests(int sig) records sig as if it had been received,
//                                 without the handler's exit (tests only).
//
//   TemporaryRegistration reg(path)
//       RAII: while alive, `path` is unlinked by the handler before it exits.
//       fc::AtomicH5Writer and fc::writeFileAtomic register their temporaries,
//       so tools need not do it themselves. Up to 32 at once (more throws).
#include <stdexcept>
#include <string>

namespace fc {

enum class TerminationPolicy { ExitNow, Record };

void installTerminationHandlers(const std::string& tool, TerminationPolicy policy);

int terminationSignal();
std::string signalName(int sig);

// Message of the exception being handled, whatever its type: gmsh throws
// std::string, some libraries const char*; std::bad_alloc is "out of memory".
// Used in catch blocks and by the std::terminate handler.
std::string currentExceptionMessage();
inline int terminationExitCode(int sig) { return 128 + sig; }

class Terminated : public std::runtime_error {
 public:
  explicit Terminated(int sig)
      : std::runtime_error("interrupted by " + signalName(sig)), sig_(sig) {}
  int signal() const { return sig_; }

 private:
  int sig_;
};

void throwIfTerminated();

void resetTerminationForTests();
void raiseTerminationForTests(int sig);

class TemporaryRegistration {
 public:
  TemporaryRegistration() = default;
  explicit TemporaryRegistration(const std::string& path);
  ~TemporaryRegistration();
  TemporaryRegistration(const TemporaryRegistration&) = delete;
  TemporaryRegistration& operator=(const TemporaryRegistration&) = delete;
  TemporaryRegistration(TemporaryRegistration&& o) noexcept : slot_(o.slot_) { o.slot_ = -1; }
  TemporaryRegistration& operator=(TemporaryRegistration&& o) noexcept;
  // Unregisters (e.g. once the temporary has been renamed onto its final name).
  void release();

 private:
  int slot_ = -1;
};

// Uncaught exceptions: a library that throws inside an OpenMP parallel region
// (gmsh meshing a self-intersecting outline does) cannot be caught by any try
// block, and the C++ runtime aborts. installTerminationHandlers also installs a
// std::terminate handler that prints "TOOL: error: CONTEXT MESSAGE", removes the
// registered temporaries and exits 2 (with a context: an input problem) or 1.
// FatalErrorContext sets CONTEXT (e.g. "sec.yaml:6:9: section.file: cannot mesh
// this section: gmsh: ") for the duration of a call into such a library.
class FatalErrorContext {
 public:
  explicit FatalErrorContext(const std::string& prefix);
  ~FatalErrorContext();
  FatalErrorContext(const FatalErrorContext&) = delete;
  FatalErrorContext& operator=(const FatalErrorContext&) = delete;

 private:
  std::string previous_;
};

// The signals this module handles, for tests and documentation.
const int* terminationSignals(int* count);

}  // namespace fc
