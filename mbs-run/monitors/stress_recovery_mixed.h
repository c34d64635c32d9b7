#pragma once
// The recovery a body's stress data calls for (docs/stresses.md): shells,
// beams, or both for a body mixing shell and beam regions ("Mixed bodies").
#include <memory>
#include <string>
#include <vector>

#include "common/stress_data.h"
#include "mbs-run/monitors/stress_recovery.h"

namespace fc::mbs {

// Shells (shellStressRecovery), beams (beamStressRecovery), or a mixed body:
// one recovery of kind Shell holding the beams' data as well, its outputs the
// shells' (over the triangles: ply_stress, failure_index, hashin) followed by
// the beams' (over the beam elements: section_forces and, with a section
// basis, beam_ply_stress, beam_failure_index, beam_hashin at `stations`).
// A mixed body's data has centroids (n_triangles + n_beams, 3): the
// triangles' then the beams' midpoints.
std::shared_ptr<const BodyStressRecovery> stressRecovery(const StressRecoveryData& data, const std::string& file = "");

// The number of outputs of a mixed recovery that are its shells' (the beams'
// follow); 0 when the recovery is not mixed.
std::size_t mixedShellOutputs(const BodyStressRecovery& r);

// The section forces (n_el, 6) among a recovery's fields (recover()): a beam
// body's first output, a mixed body's beams' first; nullptr for a shell body
// or fields that do not match the recovery's outputs.
const Eigen::VectorXd* sectionForcesField(const BodyStressRecovery& r, const std::vector<Eigen::VectorXd>& fields);

}  // namespace fc::mbs
