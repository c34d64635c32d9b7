#pragma once
// Shell meshes from gmsh (C++ API): rectangular panels centred on the origin
// and arbitrary .geo files, with interface projections forced in as nodes.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "fe-prep/mesh.h"

namespace fc::feprep {

// About 0.5 M triangles: ~1.5 M shell DOF, several GB in the modal solve.
constexpr long kDefaultMaxTriangles = 500000;

struct PanelMeshRequest {
  double length = 0.0;  // along x
  double width = 0.0;   // along y
  // Exactly one of: approximate number of triangles, or target element size.
  long triangles = 0;
  double size = 0.0;
  // Points (x, y) that must be mesh nodes: the interfaces' projections on z = 0.
  std::vector<Eigen::Vector2d> forced_points;
  // Regions [x0, y0, x1, y1] whose outlines must be mesh lines: the box patches of distributed
  // interfaces (clipped to the rectangle). Each becomes a face of its own (gmsh OpenCASCADE
  // fragments), so the triangles with all nodes in a box tile exactly that box at every element
  // size: the patch, its area and its centre do not change with the mesh. A box thin in one
  // direction becomes a line, in both a point.
  std::vector<Eigen::Vector4d> conforming_boxes;
  // Element size inside each conforming box at most this fraction of the box's smaller side
  // (0: no cap; boxes thin in one direction are lines and are not capped). A box patch's weights
  // spread a moment over it by their second moments, which are the box's only once the box is a few
  // elements across: at h = 0.1 a 25 mm bracket footprint is 0.3 elements wide and its patch's second
  // moments are +200 % off (docs/fe-prep.md, "Distributed interfaces").
  double box_size_fraction = 0.5;
  // 0, or a mesh size H (mesh: {graded_from: H}): below H the size inside each box shrinks with h,
  // min(h, box_size_fraction * side * h / H), so that every mesh of a sequence refined from H refines the
  // boxes too; with the plain cap a box keeps its elements while h is above them (docs/fe-prep.md).
  double box_graded_from = 0.0;
  bool quiet = true;
  // Refused above this (std::invalid_argument), before meshing: mesh.max_triangles.
  long max_triangles = kDefaultMaxTriangles;
};

// Unstructured Frontal-Delaunay triangles on [-L/2, L/2] x [-W/2, W/2], z = 0.
// With a triangle target the element size is iterated (a few gmsh runs) until
// the count is within 10 % of the target or stops improving. Node sets
// edge_xmin, edge_xmax, edge_ymin, edge_ymax. Forced points must lie in the
// rectangle (std::invalid_argument otherwise). Without conforming boxes the geo
// kernel meshes the plain rectangle (the meshes of earlier versions, unchanged).
Mesh meshRectangle(const PanelMeshRequest& request);

// The triangles of a .geo (or .msh) file; size > 0 caps the element size.
// Physical groups of dimension 0 and 1 become node sets under their names.
// Forced points are embedded into the surface that contains them when it is a
// plane surface of the geo kernel; otherwise the nearest node is used.
// A .geo is checked first (common/geo_script.h: no shell, file or exit commands).
Mesh meshGeoFile(const std::string& path, double size, const std::vector<Eigen::Vector3d>& forced_points,
                 bool quiet = true, long max_triangles = kDefaultMaxTriangles);

// Size h giving about n triangles on area A (equilateral triangles: A = n sqrt(3)/4 h^2).
double sizeForTriangleCount(double area, long n);

}  // namespace fc::feprep
