#pragma once
// Gives every element of a meshed body its property and material frame
// (fe-prep/mesh.h): the one shell or beam of `shell:`/`beam:` bodies, or the
// regions of a body from a mesh file (contracts.md, "General bodies").
#include <Eigen/Dense>

#include "fe-prep/body_spec.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

// The fibre reference direction of a shell region at a point (the triangle's
// centroid), before its projection on the element: the vector itself, or the
// axial or hoop direction of the cylindrical system there (hoop = axis x radial,
// radial the point's offset from the axis).
Eigen::Vector3d referenceAxisAt(const MaterialAxis& axis, const Eigen::Vector3d& point);

// The three nodes' coordinates of triangle e, one row each.
Eigen::Matrix3d triangleXyz(const Mesh& mesh, long e);

// Shell region r's fibre reference axis on triangle e: referenceAxisAt the
// triangle's centroid, checked to give the element a frame (fe::shellFrame:
// defined there and not normal to the element); an InputError at the region
// otherwise. The one projection of a region's axis, for mesh files and for the
// regions that replace a Nastran deck's properties.
Eigen::Vector3d regionAxisOnTriangle(const RegionSpec& r, const Mesh& mesh, long e);

// Fills mesh.shell_properties, beam_properties, triangle_property,
// triangle_axis, beam_property, beam_x2 and point_masses. `shell:` bodies: one
// property, axis body x; `beam:` bodies: one section, x2 body y (the previous
// fixed choices). Mesh-file bodies: each element by its group's region; an
// element of a group that is no region (nor ignored, nor only a node set)
// is an InputError naming the group and its element count, at the mesh file.
void assignElementProperties(const BodySpec& spec, Mesh& mesh);

// The in-plane fibre direction of every triangle (the reference axis projected
// on the element; its first row of fe::shellFrame), (n_triangles, 3).
Eigen::MatrixXd triangleMaterialAxes(const Mesh& mesh);

}  // namespace fc::feprep
