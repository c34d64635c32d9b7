#include "mbs-run/run_summary.h"

#include <cstdio>

namespace fc::mbs {

void RunSummary::observe(const Sample& s) {
  ++samples;
  max_violation = std::max(max_violation, s.violation);
  energy_scale = std::max({energy_scale, std::abs(s.energy.kinetic), std::abs(s.energy.potential), s.energy.dissipated});
}

std::string timeLabel(double t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "t=%.10g:", t);
  return buf;
}

}  // namespace fc::mbs
