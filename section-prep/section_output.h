#pragma once
// The edges of the tool: the contract's HDF5 layout ("section/1") and the
// readable stdout summary.
#include <ostream>
#include <string>

#include "section-prep/cross_section.h"

namespace fc::section {

// Writes atomically (fc::AtomicH5Writer): the file appears whole or not at all.
void writeSectionFile(const std::string& path, const SectionProperties& p,
                      const std::string& inputs_sha256, const std::string& source);

void printSummary(std::ostream& out, const SectionProperties& p);

}  // namespace fc::section
