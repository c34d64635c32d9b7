#include "common/progress.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace fc {

Progress::Progress(std::string label, double total, bool quiet)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1.0),
      quiet_(quiet || std::getenv("FLEXCOMP_QUIET") != nullptr),
      tty_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_),
      stage_(label_) {}

Progress::~Progress() {
  if (!finished_ && !quiet_ && tty_ && last_decile_ >= 0) std::fputc('\n', stderr);
}

void Progress::update(double done, const std::string& detail) {
  if (quiet_ || finished_) return;
  const double frac = std::min(1.0, std::max(0.0, done / total_));
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (tty_) {
    // Redraw at most 10 times a second: drawing must not cost the work it reports.
    if (std::chrono::duration<double>(now - last_draw_).count() < 0.1 && last_decile_ >= 0) return;
    last_draw_ = now;
    last_decile_ = 0;
    const int width = 30, filled = static_cast<int>(frac * width);
    std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%% %6.1fs %s\033[K", label_.c_str(), filled,
                 "##############################", width - filled, "", 100 * frac, elapsed,
                 detail.c_str());
    std::fflush(stderr);
  } else {
    const int decile = static_cast<int>(frac * 10);
    if (decile <= last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stderr, "%s: %3d%% (%.1f s) %s\n", label_.c_str(), decile * 10, elapsed,
                 detail.c_str());
  }
}

void Progress::finish(const std::string& detail) {
  stage_.end();
  if (quiet_ || finished_) return;
  finished_ = true;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (tty_) std::fputc('\r', stderr);
  std::fprintf(stderr, "%s: done in %.2f s %s%s\n", label_.c_str(), elapsed, detail.c_str(),
               tty_ ? "\033[K" : "");
}

}  // namespace fc
