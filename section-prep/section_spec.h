#pragma once
// The `section:` block of a section-prep YAML input (contracts.md), checked and
// resolved against the `materials:` block, before any meshing.
#include <string>
#include <vector>

#include "common/input.h"
#include "common/laminate.h"
#include "common/materials.h"
#include "section-prep/section_mesh.h"

namespace fc::section {

struct PlySpec {
  int material = 0;  // index into SectionSpec::materials
  double thickness = 0.0;
  double angle_deg = 0.0;  // theta3: fibre from x1, about the wall's outward normal
};

// About 1.5 GB and a few minutes of section-prep; `max_elements:` raises it.
constexpr long kDefaultMaxElements = 400000;

struct SectionSpec {
  enum class Shape { SolidCircle, Tube, Rectangle, Box, Mesh };
  Shape shape = Shape::SolidCircle;
  double diameter = 0, outer_diameter = 0, width = 0, height = 0;
  int material = -1;            // homogeneous section or wall
  std::vector<PlySpec> plies;   // tube and box: outer surface inwards; rectangle: bottom up
  double mesh_size = 0;         // element size; 0 = automatic
  long max_elements = kDefaultMaxElements;  // refuse meshes estimated larger (memory, time)
  std::string mesh_file;        // shape mesh: absolute or relative to the YAML file
  std::vector<SectionMaterial> materials;
};

// Reads `materials:` (and `laminates:` if present) and `section:` from the root.
SectionSpec readSectionSpec(const InputNode& root);

// Reads a `section:` block against libraries read elsewhere: for tools that
// embed a section in their own input (fe-prep's `beam: {section: {shape: ...}}`).
SectionSpec readSectionSpec(const InputNode& section, const MaterialLibrary& materials,
                            const LaminateLibrary& laminates = {});

// The automatic element size: a twentieth of the section's smallest outer
// dimension, and no larger than the thinnest ply so each ply gets elements.
double automaticMeshSize(const SectionSpec& spec);

// Area of the section's outer shape (m^2) for the YAML shapes; 0 for mesh files.
double sectionArea(const SectionSpec& spec);
// Triangles gmsh makes for element size h over `area`, with thin plies (thinner
// than h) each getting their own row of elements along the wall.
double estimatedElements(const SectionSpec& spec, double h);

}  // namespace fc::section
