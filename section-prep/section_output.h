#pragma once
// The edges of the tool: the contract's HDF5 layout ("section/1") and the
// readable stdout summary.
#include <ostream>
#include <string>

#include "section-prep/cross_section.h"
#include "section-prep/stress_recovery.h"

namespace fc::section {

// Writes atomically (fc::AtomicH5Writer): the file appears whole or not at all.
void writeSectionFile(const std::string& path, const SectionProperties& p,
                      const std::string& inputs_sha256, const std::string& source);

// Stresses for one set of resultants (section-prep --recover).
struct RecoveryRun {
  Vector6d resultants = Vector6d::Zero();
  std::vector<RecoveredElement> elements;
};

// With the mesh: also the recovery basis (/recovery/, /mesh/, /materials/,
// docs/file-formats.md) when `p` has one, and `run`'s stresses under /recovered/.
void writeSectionFile(const std::string& path, const SectionProperties& p,
                      const std::string& inputs_sha256, const std::string& source,
                      const SectionMesh& mesh, const RecoveryRun* run = nullptr);

// The per-element table of a recovery run, and where the largest index is.
void printRecovery(std::ostream& out, const SectionMesh& mesh, const SectionProperties& p,
                   const RecoveryRun& run);

void printSummary(std::ostream& out, const SectionProperties& p);

}  // namespace fc::section
