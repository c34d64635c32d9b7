#pragma once
// The meshes gmsh makes or reads: a rectangular panel (panel_mesher.h), a .geo
// outline, a .msh or .geo with regions (mesh_files/gmsh_regions.h). Only the
// program fe-prep-mpi links gmsh; fe-prep hands such bodies to it before any
// work (backend_choice.h), so its own definition (fe-prep/la/serial/) refuses.
#include <string>
#include <vector>

#include "fe-prep/body_spec.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

// The mesh of a shell rectangle, a .geo outline or a general mesh file
// (spec.shell or spec.general without a deck); `sets`: the node-set names the
// body's interfaces and reference conditions use (physical groups kept).
Mesh meshWithGmsh(const BodySpec& spec, const std::vector<std::string>& sets, bool quiet);

}  // namespace fc::feprep
