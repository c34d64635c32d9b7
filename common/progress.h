#pragma once
// One-line progress on stderr for long work (meshing, eigen-solves, integration).
// On a terminal it redraws in place; otherwise (logs, CI) it prints a line every
// 10 %. Silent when FLEXCOMP_QUIET is set or quiet=true. Its label names the
// stage being run for an out-of-memory message (common/memory.h).
#include <chrono>
#include <string>

#include "common/memory.h"

namespace fc {

class Progress {
 public:
  Progress(std::string label, double total, bool quiet = false);
  ~Progress();
  void update(double done, const std::string& detail = "");
  void finish(const std::string& detail = "");

 private:
  std::string label_;
  double total_;
  bool quiet_, tty_, finished_ = false;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
  StageScope stage_;
};

}  // namespace fc
