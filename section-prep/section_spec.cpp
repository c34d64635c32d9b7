#include "section-prep/section_spec.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "common/files.h"
#include "common/laminate.h"
#include "common/materials.h"

namespace fc::section {

namespace {

int materialIndex(SectionSpec& spec, std::map<std::string, int>& index, const Material& m) {
  auto it = index.find(m.name);
  if (it != index.end()) return it->second;
  SectionMaterial sm;
  sm.name = m.name;
  sm.C = m.C;
  sm.rho = m.rho;
  sm.strength = m.strength;
  spec.materials.push_back(sm);
  return index[m.name] = static_cast<int>(spec.materials.size()) - 1;
}

std::vector<PlySpec> toPlies(SectionSpec& spec, std::map<std::string, int>& index,
                             const Laminate& lam, const MaterialLibrary& lib) {
  std::vector<PlySpec> out;
  for (const auto& p : lam.plies)
    out.push_back({materialIndex(spec, index, lib.at(p.material)), p.thickness, p.angle_deg});
  return out;
}

// plies: [...] or laminate: NAME on `node`.
void readLayup(SectionSpec& spec, std::map<std::string, int>& index, const InputNode& node,
               const MaterialLibrary& lib, const LaminateLibrary& lams) {
  if (node.has("plies")) {
    spec.plies = toPlies(spec, index, readPlies(node["plies"], lib), lib);
    return;
  }
  const InputNode n = node["laminate"];
  auto it = lams.find(n.asString());
  if (it == lams.end()) n.fail("unknown laminate '" + n.asString() + "'; define it under laminates:");
  spec.plies = toPlies(spec, index, it->second, lib);
}

// wall: {material, thickness} | {plies: [...]} | {laminate: NAME}
void readWall(SectionSpec& spec, std::map<std::string, int>& index, const InputNode& wall,
              const MaterialLibrary& lib, const LaminateLibrary& lams) {
  wall.allowKeys({"material", "thickness", "plies", "laminate"});
  const int given = wall.has("material") + wall.has("plies") + wall.has("laminate");
  if (given != 1)
    wall.fail("expected exactly one of {material, thickness}, {plies: [...]} or {laminate: NAME}");
  if (wall.has("material")) {
    const Material& m = lookupMaterial(lib, wall["material"]);
    spec.plies.push_back({materialIndex(spec, index, m), wall["thickness"].asLength(1e-7, 1.0), 0.0});
  } else {
    readLayup(spec, index, wall, lib, lams);
  }
}

double totalThickness(const std::vector<PlySpec>& plies) {
  double t = 0;
  for (const auto& p : plies) t += p.thickness;
  return t;
}

}  // namespace

SectionSpec readSectionSpec(const InputNode& root) {
  root.allowKeys({"units", "materials", "laminates", "section"});
  const MaterialLibrary lib = readMaterials(root["materials"]);
  LaminateLibrary lams;
  if (root.has("laminates")) lams = readLaminates(root["laminates"], lib);
  return readSectionSpec(root["section"], lib, lams);
}

SectionSpec readSectionSpec(const InputNode& s, const MaterialLibrary& lib,
                            const LaminateLibrary& lams) {
  SectionSpec spec;
  std::map<std::string, int> index;
  const std::string shape = s["shape"].asString();
  // Cross-section dimensions from 1 um to 100 m: outside, a unit mistake (1e-150,
  // a width of 1e6 m) that would make gmsh fail or exhaust memory.
  constexpr double kMinLength = 1e-6, kMaxLength = 100.0;
  if (s.has("mesh_size")) spec.mesh_size = s["mesh_size"].asLength(1e-9, kMaxLength);
  if (s.has("max_elements")) {
    spec.max_elements = s["max_elements"].asInt();
    if (spec.max_elements < 1) s["max_elements"].fail("expected a positive element count");
  }
  if (shape == "solid_circle") {
    s.allowKeys({"shape", "diameter", "material", "mesh_size", "max_elements"});
    spec.shape = SectionSpec::Shape::SolidCircle;
    spec.diameter = s["diameter"].asLength(kMinLength, kMaxLength);
    spec.material = materialIndex(spec, index, lookupMaterial(lib, s["material"]));
  } else if (shape == "tube") {
    s.allowKeys({"shape", "outer_diameter", "wall", "mesh_size", "max_elements"});
    spec.shape = SectionSpec::Shape::Tube;
    spec.outer_diameter = s["outer_diameter"].asLength(kMinLength, kMaxLength);
    readWall(spec, index, s["wall"], lib, lams);
    if (totalThickness(spec.plies) >= 0.5 * spec.outer_diameter)
      s["wall"].fail("the wall is as thick as the tube's radius or thicker; use shape: solid_circle");
  } else if (shape == "rectangle") {
    s.allowKeys({"shape", "width", "height", "material", "plies", "laminate", "mesh_size", "max_elements"});
    spec.shape = SectionSpec::Shape::Rectangle;
    spec.width = s["width"].asLength(kMinLength, kMaxLength);
    spec.height = s["height"].asLength(kMinLength, kMaxLength);
    if (s.has("material") == (s.has("plies") || s.has("laminate")))
      s.fail("a rectangle takes either material: or plies: (stacked along x3)");
    if (s.has("material")) {
      spec.material = materialIndex(spec, index, lookupMaterial(lib, s["material"]));
    } else {
      readLayup(spec, index, s, lib, lams);
      const double total = totalThickness(spec.plies);
      if (std::abs(total - spec.height) > 1e-9 * spec.height)
        s[s.has("plies") ? "plies" : "laminate"].fail(
            "the plies add up to " + std::to_string(total) + " m but height is " +
            std::to_string(spec.height) + " m; expected them to fill the height");
    }
  } else if (shape == "box") {
    s.allowKeys({"shape", "width", "height", "wall", "mesh_size", "max_elements"});
    spec.shape = SectionSpec::Shape::Box;
    spec.width = s["width"].asLength(kMinLength, kMaxLength);
    spec.height = s["height"].asLength(kMinLength, kMaxLength);
    readWall(spec, index, s["wall"], lib, lams);
    if (2 * totalThickness(spec.plies) >= std::min(spec.width, spec.height))
      s["wall"].fail("the wall fills the box; expected a total thickness below half the smaller side");
  } else if (shape == "mesh") {
    s.allowKeys({"shape", "file", "mesh_size", "max_elements"});
    spec.shape = SectionSpec::Shape::Mesh;
    // The mesh file's coordinates are metres: `units:` converts this file's numbers only.
    if (s.units())
      s["file"].fail("a section mesh file is read in metres; with units: " + s.units()->name +
                     " its coordinates would be taken as metres (write the mesh in metres, or this file in m-kg-s)");
    spec.mesh_file = resolveRelativeTo(s.file(), s["file"].asString());
    for (const auto& [name, m] : lib) materialIndex(spec, index, m);
  } else {
    s["shape"].fail("unknown shape '" + shape +
                    "'; expected solid_circle, tube, rectangle, box or mesh");
  }
  for (const auto& m : spec.materials)
    if (const std::string why = materialProblem(m); !why.empty())
      s.fail("material '" + m.name + "' cannot be used in a section: " + why);
  // Refuse, before meshing, a mesh that would exhaust memory or run for hours.
  if (spec.shape != SectionSpec::Shape::Mesh) {
    const double h = spec.mesh_size > 0 ? spec.mesh_size : automaticMeshSize(spec);
    const double n = estimatedElements(spec, h);
    if (n > static_cast<double>(spec.max_elements)) {
      std::ostringstream os;
      os << "element size " << h << " m gives about " << std::setprecision(2) << n
         << " elements, more than the limit max_elements: " << spec.max_elements
         << " (about 1.5 GB and minutes per 400000); use a larger mesh_size, or raise "
            "max_elements in the section block if the machine can take it";
      (s.has("mesh_size") ? s["mesh_size"] : s).fail(os.str());
    }
  }
  return spec;
}

double sectionArea(const SectionSpec& spec) {
  constexpr double kPi = 3.14159265358979323846;
  double d = 0;
  for (const auto& p : spec.plies) d += p.thickness;
  switch (spec.shape) {
    case SectionSpec::Shape::SolidCircle: return kPi * spec.diameter * spec.diameter / 4;
    case SectionSpec::Shape::Tube: {
      const double R = spec.outer_diameter / 2, r = R - d;
      return kPi * (R * R - r * r);
    }
    case SectionSpec::Shape::Rectangle: return spec.width * spec.height;
    case SectionSpec::Shape::Box:
      return spec.width * spec.height - (spec.width - 2 * d) * (spec.height - 2 * d);
    case SectionSpec::Shape::Mesh: return 0;
  }
  return 0;
}

double estimatedElements(const SectionSpec& spec, double h) {
  // Equilateral triangles of side h have area sqrt(3)/4 h^2; a ply thinner than h
  // still gets a row of about 2 L / t triangles of side ~t along its length L.
  constexpr double kPi = 3.14159265358979323846;
  double n = sectionArea(spec) * 4.0 / (std::sqrt(3.0) * h * h);
  double L = 0;
  if (spec.shape == SectionSpec::Shape::Tube) L = kPi * spec.outer_diameter;
  if (spec.shape == SectionSpec::Shape::Box) L = 2 * (spec.width + spec.height);
  if (spec.shape == SectionSpec::Shape::Rectangle) L = spec.width;
  for (const auto& p : spec.plies)
    if (p.thickness < h) n += 2 * L / p.thickness;
  return n;
}

double automaticMeshSize(const SectionSpec& spec) {
  double L = 0;
  switch (spec.shape) {
    case SectionSpec::Shape::SolidCircle: L = spec.diameter; break;
    case SectionSpec::Shape::Tube: L = spec.outer_diameter; break;
    default: L = std::min(spec.width, spec.height); break;
  }
  double h = L / 20;
  for (const auto& p : spec.plies) h = std::min(h, p.thickness);
  return h;
}

}  // namespace fc::section
