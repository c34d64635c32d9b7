#pragma once
// A gmsh mesh (.msh 2.2 or 4.x, or a .geo meshed here) whose physical groups
// are the regions and node sets of a body (contracts.md, "General bodies"),
// read through the gmsh C++ API.
#include <string>
#include <vector>

#include "fe-prep/mesh.h"

namespace fc::feprep {

struct RegionMeshRequest {
  std::string path;
  double size = 0.0;            // .geo: element size cap (0: the file's own)
  double length_scale = 1.0;    // the file's length unit in metres
  long max_triangles = 500000;  // refused above (a .geo's estimate, any file's count)
  std::vector<std::string> regions;  // groups whose elements form the body
  std::vector<std::string> sets;     // groups used as node sets (interfaces:, reference:)
  std::vector<std::string> ignore;   // groups left out
  bool quiet = true;
};

// The body's elements: linear triangles (quadrilaterals split into two along
// their 1-3 diagonal) of surfaces and two-node lines of curves, each in
// exactly one region group (mesh.groups = the region names, triangle_group and
// beam_group index them), nodes in metres; every physical group's nodes as a
// set under its name. Refused (std::invalid_argument naming the group, the
// element type and count): second-order or volume elements, elements of a
// group that is no region, set or ignored, a region name no group has (with a
// did-you-mean), an entity in two regions, set nodes no element uses.
Mesh readRegionMesh(const RegionMeshRequest& request);

}  // namespace fc::feprep
