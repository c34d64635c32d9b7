// The regions of a general body as the body file records them (/regions/NAME,
// docs/body-file.md "Regions"): what `--inspect` lists.
#pragma once

#include <string>
#include <vector>

#include "common/flexbody.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

// One record per shell property, beam property, node set that is no region,
// and one for the concentrated masses; `summary` holds fe-prep's printed
// region lines (regionSummary), each matched to its record by name.
std::vector<FlexRegion> regionRecords(const Mesh& mesh, const std::vector<std::string>& summary);

}  // namespace fc::feprep
