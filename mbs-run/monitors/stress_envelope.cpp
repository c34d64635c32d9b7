#include "mbs-run/monitors/stress_envelope.h"

#include "mbs-run/monitors/stress_recovery_mixed.h"

namespace fc::mbs {

void StressEnvelope::observe(const BodyStressRecovery& r, const std::vector<Eigen::VectorXd>& fields, double t) {
  if (fields.size() != r.outputs.size() || fields.empty()) return;
  // ply_stress (shells, and beams with a section basis) or section_forces.
  const Eigen::VectorXd& f0 = fields[static_cast<std::size_t>(r.failure_output >= 0 ? r.ply_output : 0)];
  if (r.failure_output >= 0) {
    const Eigen::VectorXd& fi = fields[static_cast<std::size_t>(r.failure_output)];
    if (rows_ == 0) {
      peak_ = fi;
      peak_time_ = Eigen::VectorXd::Constant(fi.size(), t);
      at_peak_ = f0;
    } else {
      // Strictly larger only: the time is the FIRST row that reaches the peak,
      // as for the summary's largest index (RunSummary::observe).
      for (Eigen::Index i = 0; i < fi.size(); ++i)
        if (fi[i] > peak_[i]) {
          peak_[i] = fi[i];
          peak_time_[i] = t;
          at_peak_.segment<3>(3 * i) = f0.segment<3>(3 * i);
        }
    }
    if (r.hashin_output >= 0) {
      const Eigen::VectorXd& h = fields[static_cast<std::size_t>(r.hashin_output)];
      hashin_peak_ = rows_ == 0 ? h : Eigen::VectorXd(hashin_peak_.cwiseMax(h));
    }
  } else if (rows_ == 0) {
    max_ = min_ = f0;
  } else {
    max_ = max_.cwiseMax(f0);
    min_ = min_.cwiseMin(f0);
  }
  if (r.beam_part) {
    const auto first = fields.begin() + static_cast<std::ptrdiff_t>(mixedShellOutputs(r));
    if (beams_.empty()) beams_.resize(1);
    beams_[0].observe(*r.beam_part, std::vector<Eigen::VectorXd>(first, fields.end()), t);
  }
  ++rows_;
}

std::vector<EnvelopeDataset> StressEnvelope::datasets(const BodyStressRecovery& r) const {
  std::vector<EnvelopeDataset> d;
  if (rows_ == 0) return d;
  // (n_el, n_plies, 3), (n_stations, n_section_elements, 3) or (n_el, 6)
  const std::size_t o = static_cast<std::size_t>(r.failure_output >= 0 ? r.ply_output : 0);
  const std::vector<long>& field = r.outputs[o].dims;
  const std::string base = r.outputs[o].name;  // ply_stress or section_forces
  if (r.failure_output >= 0) {
    const std::vector<long>& fi = r.outputs[static_cast<std::size_t>(r.failure_output)].dims;
    d.push_back({"failure_index_peak", fi, peak_});
    d.push_back({"failure_index_peak_time", fi, peak_time_});
    d.push_back({base + "_at_peak", field, at_peak_});
    if (r.hashin_output >= 0)
      d.push_back({"hashin_peak", r.outputs[static_cast<std::size_t>(r.hashin_output)].dims, hashin_peak_});
  } else {
    d.push_back({base + "_max", field, max_});
    d.push_back({base + "_min", field, min_});
  }
  if (r.beam_part && !beams_.empty())
    for (EnvelopeDataset& b : beams_[0].datasets(*r.beam_part)) {
      // section_forces_* are the beams' alone; the rest would clash with the shells'.
      if (b.name.rfind("section_forces", 0) != 0) b.name = "beam_" + b.name;
      d.push_back(std::move(b));
    }
  return d;
}

}  // namespace fc::mbs
