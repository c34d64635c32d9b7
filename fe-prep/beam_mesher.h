#pragma once
// Straight beams along the body x axis, centred on the origin.
#include <vector>

#include "fe-prep/mesh.h"

namespace fc::feprep {

// `elements` equal two-node elements on [-L/2, L/2]; every forced abscissa that
// does not coincide with a node splits the element containing it, so that each
// interface has a node at its projection on the axis. Node sets end_min, end_max.
// Forced abscissae outside the beam raise std::invalid_argument.
Mesh meshBeam(double length, long elements, const std::vector<double>& forced_x);

}  // namespace fc::feprep
