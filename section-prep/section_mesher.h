#pragma once
// Meshes a SectionSpec with the gmsh C++ API: quadratic triangles, curved
// edges on curved boundaries, every ply a separate surface so that ply
// interfaces are mesh lines. Gives every element its VABS orientation
// (theta1 from the wall's outward normal, theta3 the ply angle).
#include "section-prep/section_mesh.h"
#include "section-prep/section_spec.h"

namespace fc::section {

// Throws fc::InputError-free std::runtime_error on meshing failures; mesh
// files with unknown physical names raise std::runtime_error naming the name.
SectionMesh meshSection(const SectionSpec& spec);

// theta1 (degrees) that makes the ply normal y3 = (-sin theta1, cos theta1)
// point along the outward normal n = (n2, n3).
double theta1FromNormal(double n2, double n3);

}  // namespace fc::section
