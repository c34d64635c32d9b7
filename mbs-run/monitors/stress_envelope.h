#pragma once
// The envelope of a body's recovered stresses over a whole run (docs/stresses.md,
// "Envelope and decimation"): what an engineer signing off a design reads
// first, taken from EVERY output row whether or not the row's full field is
// written (outputs.stress_every decimates only the full fields).
//   shells with strengths: per element and ply the largest failure index, the
//     time of the first row that reaches it, and the ply stresses in that row;
//     and each Hashin mode's largest index;
//   shells without strengths: per element, ply and component the largest and
//     smallest ply stress;
//   beams: per element and component the largest and smallest section force
//     (beams with a section basis: their plies' failure envelope as shells');
//   bodies mixing shells and beams: the shells' envelope, then the beams' as a
//     beam body's (BodyStressRecovery::beam_part), its ply datasets prefixed
//     beam_ as the mixed body's outputs are.
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "mbs-run/monitors/stress_recovery.h"

namespace fc::mbs {

// One envelope dataset under /bodies/NAME/: name, trailing dims (no time), C-order values.
struct EnvelopeDataset {
  std::string name;
  std::vector<long> dims;
  Eigen::VectorXd values;
};

class StressEnvelope {
 public:
  // Folds one output row's recovered fields (BodyStressRecovery::recover) at time t.
  void observe(const BodyStressRecovery& r, const std::vector<Eigen::VectorXd>& fields, double t);
  bool empty() const { return rows_ == 0; }
  long rows() const { return rows_; }
  // The datasets to write, in file order: failure_index_peak,
  // failure_index_peak_time, ply_stress_at_peak, hashin_peak (shells with strengths);
  // ply_stress_max, ply_stress_min (shells without); section_forces_max,
  // section_forces_min (beams); a mixed body's shells' then its beams'.
  // Empty before the first row.
  std::vector<EnvelopeDataset> datasets(const BodyStressRecovery& r) const;

 private:
  long rows_ = 0;
  // Shells with strengths: peak_ (n_el n_plies), peak_time_, at_peak_ (n_el n_plies 3).
  Eigen::VectorXd peak_, peak_time_, at_peak_;
  // With Hashin indices: each mode's largest value (same layout as `hashin`).
  Eigen::VectorXd hashin_peak_;
  // The others: componentwise max_ and min_ of the one field.
  Eigen::VectorXd max_, min_;
  // A mixed body's beams, folded as a beam body's from their outputs (one
  // element or none; a vector keeps the envelope a value that copies whole).
  std::vector<StressEnvelope> beams_;
};

}  // namespace fc::mbs
