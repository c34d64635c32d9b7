#include "section-prep/section_mesher.h"

#include <gmsh.h>

#include "common/geo_script.h"
#include "common/termination.h"

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

namespace fc::section {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Holds gmsh open for one meshing and closes it on every path out.
struct GmshSession {
  GmshSession() {
    // No configuration files (~/.gmshrc may hold commands): geometry only.
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("section");
  }
  ~GmshSession() { gmsh::finalize(); }
};

// How the elements of one gmsh surface are oriented.
struct Region {
  int material = 0;
  double theta3 = 0;
  enum class Theta1 { Fixed, Radial, BoxWall } rule = Theta1::Fixed;
  double theta1 = 0;
};

using DimTags = std::vector<std::pair<int, int>>;

// Conforming surfaces from a list of (possibly touching) surfaces: region k
// ends up as the surfaces gmsh's fragment derived from input k.
std::vector<std::vector<int>> fragmentAll(const std::vector<int>& tags) {
  DimTags in, out;
  for (int t : tags) in.push_back({2, t});
  std::vector<DimTags> map;
  if (in.size() > 1) {
    gmsh::model::occ::fragment(DimTags(in.begin(), in.begin() + 1),
                               DimTags(in.begin() + 1, in.end()), out, map);
  } else {
    map.push_back(in);
  }
  gmsh::model::occ::synchronize();
  std::vector<std::vector<int>> result;
  for (const auto& m : map) {
    std::vector<int> s;
    for (const auto& dt : m) s.push_back(dt.second);
    result.push_back(s);
  }
  return result;
}

int ring(int outer, int inner) {
  DimTags out;
  std::vector<DimTags> map;
  gmsh::model::occ::cut({{2, outer}}, {{2, inner}}, out, map);
  return out.at(0).second;
}

// Builds the geometry; returns (surface tags, region) pairs.
std::vector<std::pair<std::vector<int>, Region>> buildGeometry(const SectionSpec& spec) {
  namespace occ = gmsh::model::occ;
  std::vector<int> tags;
  std::vector<Region> regions;
  const auto& plies = spec.plies;
  switch (spec.shape) {
    case SectionSpec::Shape::SolidCircle: {
      const double R = 0.5 * spec.diameter;
      tags.push_back(occ::addDisk(0, 0, 0, R, R));
      regions.push_back({spec.material});
      break;
    }
    case SectionSpec::Shape::Tube: {
      double r = 0.5 * spec.outer_diameter;
      for (const auto& p : plies) {
        const int o = occ::addDisk(0, 0, 0, r, r);
        const int i = occ::addDisk(0, 0, 0, r - p.thickness, r - p.thickness);
        tags.push_back(ring(o, i));
        Region reg{p.material, p.angle_deg, Region::Theta1::Radial};
        regions.push_back(reg);
        r -= p.thickness;
      }
      break;
    }
    case SectionSpec::Shape::Rectangle: {
      const double w = spec.width, h = spec.height;
      if (plies.empty()) {
        tags.push_back(occ::addRectangle(-w / 2, -h / 2, 0, w, h));
        regions.push_back({spec.material});
      } else {
        double total = 0;
        for (const auto& p : plies) total += p.thickness;
        if (std::abs(total - h) > 1e-9 * h) {
          std::ostringstream m;
          m << "the plies add up to " << total << " m but the rectangle's height is " << h << " m";
          throw std::runtime_error(m.str());
        }
        double z = -h / 2;
        for (const auto& p : plies) {
          tags.push_back(occ::addRectangle(-w / 2, z, 0, w, p.thickness));
          regions.push_back({p.material, p.angle_deg, Region::Theta1::Fixed, 0.0});
          z += p.thickness;
        }
      }
      break;
    }
    case SectionSpec::Shape::Box: {
      double d = 0;
      const double w = spec.width, h = spec.height;
      for (const auto& p : plies) {
        const int o = occ::addRectangle(-w / 2 + d, -h / 2 + d, 0, w - 2 * d, h - 2 * d);
        const double e = d + p.thickness;
        const int i = occ::addRectangle(-w / 2 + e, -h / 2 + e, 0, w - 2 * e, h - 2 * e);
        tags.push_back(ring(o, i));
        regions.push_back({p.material, p.angle_deg, Region::Theta1::BoxWall});
        d = e;
      }
      break;
    }
    case SectionSpec::Shape::Mesh:
      break;
  }
  occ::synchronize();
  const auto frag = fragmentAll(tags);
  std::vector<std::pair<std::vector<int>, Region>> out;
  for (std::size_t k = 0; k < frag.size(); ++k) out.push_back({frag[k], regions[k]});
  return out;
}

// Physical surfaces named MATERIAL or MATERIAL/PLY_ANGLE_DEG/WALL_ANGLE_DEG.
std::vector<std::pair<std::vector<int>, Region>> regionsFromPhysicalNames(const SectionSpec& spec) {
  std::map<std::string, int> mat;
  for (std::size_t i = 0; i < spec.materials.size(); ++i) mat[spec.materials[i].name] = static_cast<int>(i);
  DimTags groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  if (groups.empty())
    throw std::runtime_error(spec.mesh_file + ": no physical surfaces; name each surface "
                             "MATERIAL or MATERIAL/PLY_ANGLE_DEG/WALL_ANGLE_DEG");
  std::vector<std::pair<std::vector<int>, Region>> out;
  for (const auto& g : groups) {
    std::string name;
    gmsh::model::getPhysicalName(2, g.second, name);
    std::vector<std::string> parts;
    std::stringstream ss(name);
    for (std::string p; std::getline(ss, p, '/');) parts.push_back(p);
    auto it = parts.empty() ? mat.end() : mat.find(parts[0]);
    if (it == mat.end() || (parts.size() != 1 && parts.size() != 3))
      throw std::runtime_error(spec.mesh_file + ": physical surface '" + name +
                               "': expected MATERIAL or MATERIAL/PLY_ANGLE_DEG/WALL_ANGLE_DEG "
                               "with MATERIAL one of the materials: block");
    Region r{it->second};
    if (parts.size() == 3) {
      try {
        r.theta3 = std::stod(parts[1]);
        r.theta1 = std::stod(parts[2]);
      } catch (...) {
        throw std::runtime_error(spec.mesh_file + ": physical surface '" + name +
                                 "': the angles must be numbers in degrees");
      }
    }
    std::vector<int> ents;
    gmsh::model::getEntitiesForPhysicalGroup(2, g.second, ents);
    out.push_back({ents, r});
  }
  return out;
}

double elementTheta1(const Region& r, const Eigen::Vector2d& c, const SectionSpec& spec) {
  switch (r.rule) {
    case Region::Theta1::Fixed: return r.theta1;
    case Region::Theta1::Radial: return theta1FromNormal(c.x(), c.y());
    case Region::Theta1::BoxWall: {
      // The nearest outer side decides the wall (corners split along the diagonals).
      const double right = spec.width / 2 - c.x(), left = spec.width / 2 + c.x();
      const double top = spec.height / 2 - c.y(), bottom = spec.height / 2 + c.y();
      const double m = std::min({right, left, top, bottom});
      if (m == top) return theta1FromNormal(0, 1);
      if (m == bottom) return theta1FromNormal(0, -1);
      if (m == right) return theta1FromNormal(1, 0);
      return theta1FromNormal(-1, 0);
    }
  }
  return 0;
}

// gmsh node order to VABS slots (same corner order; mid-sides 0-1, 1-2, ...).
bool vabsSlots(int type, ElementShape& shape, std::vector<int>& slots) {
  switch (type) {
    case 2: shape = ElementShape::Triangle; slots = {0, 1, 2}; return true;
    case 9: shape = ElementShape::Triangle; slots = {0, 1, 2, 4, 5, 6}; return true;
    case 3: shape = ElementShape::Quadrilateral; slots = {0, 1, 2, 3}; return true;
    case 16: shape = ElementShape::Quadrilateral; slots = {0, 1, 2, 3, 4, 5, 6, 7}; return true;
    case 10: shape = ElementShape::Quadrilateral; slots = {0, 1, 2, 3, 4, 5, 6, 7, 8}; return true;
    default: return false;
  }
}

SectionMesh meshSectionWithGmsh(const SectionSpec& spec);

}  // namespace

double theta1FromNormal(double n2, double n3) { return std::atan2(-n2, n3) * 180.0 / kPi; }

SectionMesh meshSection(const SectionSpec& spec) {
  // A .geo file is a program: refuse shell, file and exit commands before gmsh runs it.
  if (spec.shape == SectionSpec::Shape::Mesh) checkGmshInput(spec.mesh_file);
  try {
    return meshSectionWithGmsh(spec);
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // out of memory is no input error (common/memory.h)
  } catch (...) {
    // gmsh reports geometry and syntax errors by throwing std::string: one error,
    // never an abort.
    throw std::runtime_error("gmsh: " + currentExceptionMessage());
  }
}

namespace {

SectionMesh meshSectionWithGmsh(const SectionSpec& spec) {
  GmshSession session;
  std::vector<std::pair<std::vector<int>, Region>> regions;
  bool needs_meshing = true;
  if (spec.shape == SectionSpec::Shape::Mesh) {
    try {
      gmsh::open(spec.mesh_file);
    } catch (const std::exception& e) {
      throw std::runtime_error(spec.mesh_file + ": gmsh cannot read it: " + e.what());
    }
    std::vector<std::size_t> tags;
    std::vector<double> coords, params;
    gmsh::model::mesh::getNodes(tags, coords, params);
    needs_meshing = tags.empty();  // a .geo, or a .msh without a mesh
    regions = regionsFromPhysicalNames(spec);
  } else {
    regions = buildGeometry(spec);
  }
  if (needs_meshing) {
    const double h = spec.mesh_size > 0 ? spec.mesh_size : automaticMeshSize(spec);
    if (spec.shape != SectionSpec::Shape::Mesh || spec.mesh_size > 0) {
      // Sizes at the geometry's points drive gmsh's 1-D meshing; set them all.
      gmsh::vectorpair points;
      gmsh::model::getEntities(points, 0);
      gmsh::model::mesh::setSize(points, h);
      gmsh::option::setNumber("Mesh.MeshSizeMax", h);
      gmsh::option::setNumber("Mesh.MeshSizeMin", 0);
      gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 24);
    }
    if (spec.shape == SectionSpec::Shape::Mesh) {
      // The file's own sizes are unknown before meshing: a floor on the element
      // size keeps the count near max_elements over the model's bounding box.
      double x0, y0, z0, x1, y1, z1;
      gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
      const double area = std::max((x1 - x0) * (y1 - y0), 0.0);
      const double floor = std::sqrt(4.0 * area / (std::sqrt(3.0) * static_cast<double>(spec.max_elements)));
      if (spec.mesh_size > 0 && spec.mesh_size < floor) {
        std::ostringstream os;
        os << spec.mesh_file << ": mesh_size " << spec.mesh_size << " m over a " << (x1 - x0) << " x "
           << (y1 - y0) << " m section gives more than max_elements: " << spec.max_elements
           << " elements; use a larger mesh_size or raise max_elements in the section block";
        throw std::runtime_error(os.str());
      }
      if (std::isfinite(floor) && floor > 0) gmsh::option::setNumber("Mesh.MeshSizeMin", floor);
    }
    gmsh::option::setNumber("Mesh.ElementOrder", 2);
    gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);
    gmsh::model::mesh::generate(2);
  }

  SectionMesh mesh;
  mesh.materials = spec.materials;
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, params;
  gmsh::model::mesh::getNodes(node_tags, coords, params);
  std::map<std::size_t, int> index;
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    index[node_tags[i]] = static_cast<int>(i);
    mesh.nodes.emplace_back(coords[3 * i], coords[3 * i + 1]);
  }
  for (const auto& [surfaces, region] : regions) {
    for (int s : surfaces) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> etags, enodes;
      gmsh::model::mesh::getElements(types, etags, enodes, 2, s);
      for (std::size_t t = 0; t < types.size(); ++t) {
        ElementShape shape;
        std::vector<int> slots;
        if (!vabsSlots(types[t], shape, slots))
          throw std::runtime_error("gmsh produced element type " + std::to_string(types[t]) +
                                   "; section-prep takes 3- and 6-node triangles and 4-, 8- and "
                                   "9-node quadrilaterals");
        const std::size_t nn = slots.size();
        for (std::size_t e = 0; e < etags[t].size(); ++e) {
          SectionElement el;
          el.shape = shape;
          el.user_id = static_cast<int>(etags[t][e]);
          el.material = region.material;
          el.theta3_deg = region.theta3;
          Eigen::Vector2d c = Eigen::Vector2d::Zero();
          for (std::size_t k = 0; k < nn; ++k) {
            const int n = index.at(enodes[t][e * nn + k]);
            el.nodes[slots[k]] = n;
            c += mesh.nodes[n];
          }
          el.theta1_deg[0] = elementTheta1(region, c / double(nn), spec);
          mesh.elements.push_back(el);
        }
      }
    }
  }
  if (mesh.elements.empty()) throw std::runtime_error("meshing produced no elements");
  if (static_cast<long>(mesh.elements.size()) > 2 * spec.max_elements)
    throw std::runtime_error("meshing produced " + std::to_string(mesh.elements.size()) +
                             " elements, more than twice max_elements: " +
                             std::to_string(spec.max_elements) +
                             "; use a larger mesh_size or raise max_elements");
  return mesh;
}

}  // namespace

}  // namespace fc::section
