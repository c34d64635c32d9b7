#pragma once
// BODY.xdmf beside BODY.h5: an XDMF description of a flexible body file so
// that ParaView ("XDMF Reader") opens the mesh with every mode shape as vector
// fields on the nodes. The XDMF file holds no numbers: it points into the
// HDF5 datasets (/mesh/nodes, /mesh/triangles, /mesh/beams, /modes/shapes)
// by relative file name, so the two files travel together. Layout and field
// names: docs/file-formats.md, "BODY.xdmf".
#include <string>

#include "common/flexbody.h"

namespace fc::feprep {

// The XDMF path that goes with a body file: the extension replaced by .xdmf
// (BODY.h5 -> BODY.xdmf; no extension: .xdmf appended).
std::string xdmfPathFor(const std::string& h5_path);

// Field names: mode_01_12.35Hz (translations, m per unit modal coordinate)
// and mode_01_12.35Hz_rotation (rad per unit modal coordinate).
std::string modeFieldName(int mode_index, double frequency_hz);

// The XDMF text describing `body` as written to `h5_path` (which it references
// by its file name only, so it must sit in the same directory).
std::string bodyXdmf(const std::string& h5_path, const FlexBody& body);

}  // namespace fc::feprep
