#pragma once
// Writing a run's results: the HDF5 layout of contracts.md ("results/1"),
// written atomically, and CSV extracts of chosen channels.
#include <string>
#include <vector>

#include "mbs-run/model.h"
#include "mbs-run/simulation.h"

namespace fc::mbs {

void writeResults(const std::string& path, const Model& model, const Results& results,
                  const std::string& inputs_sha256);

// Channels are results paths without the leading slash, e.g. "joints/R3/angle",
// "bodies/B3/angular_velocity", "energy/kinetic"; vectors give one column per
// component. Unknown names throw std::invalid_argument listing the valid ones.
void writeCsv(const std::string& path, const Model& model, const Results& results,
              const std::vector<std::string>& channels);

}  // namespace fc::mbs
