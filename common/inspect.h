#pragma once
// A short, human description of any flexcomp HDF5 file: its format, provenance,
// datasets with their shapes, and a summary of what matters for its kind
// (section: EA, GJ, EI; flexbody: mass, modes and frequencies, interfaces;
// results: time span, bodies, status). Behind every tool's `--inspect FILE`.
#include <string>

namespace fc {

// Throws fc::H5Error when the file cannot be opened.
std::string inspectFile(const std::string& path);

}  // namespace fc
