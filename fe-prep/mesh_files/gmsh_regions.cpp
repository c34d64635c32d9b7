#include "fe-prep/mesh_files/gmsh_regions.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "common/geo_script.h"
#include "common/input.h"
#include "common/termination.h"

#include "fe-prep/gmsh_session.h"

namespace fc::feprep {
namespace {

bool endsWith(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

std::string entityText(int dim, int tag) {
  static const char* const kinds[] = {"point", "curve", "surface", "volume"};
  return std::string(kinds[dim]) + " " + std::to_string(tag);
}

std::string elementName(int type) {
  std::string name;
  int dim, order, nn, npv;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, nn, local, npv);
  return name;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

Mesh readGmsh(const RegionMeshRequest& r) {
  GmshSession session(r.quiet);
  gmsh::open(r.path);
  if (endsWith(r.path, ".geo")) {
    if (r.size > 0) gmsh::option::setNumber("Mesh.MeshSizeMax", r.size);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::model::mesh::generate(2);
  }

  // Physical groups by name (unnamed ones as physical_DIM_TAG).
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  std::map<std::pair<int, int>, std::string> group_name;
  std::vector<std::string> all_names;
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (name.empty()) name = "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
    group_name[{dim, tag}] = name;
    all_names.push_back(name);
  }
  auto known = [&](const std::string& what, const std::vector<std::string>& names) {
    for (const auto& n : names)
      if (!contains(all_names, n)) {
        std::string list;
        for (const auto& a : all_names) list += (list.empty() ? "" : ", ") + a;
        throw std::invalid_argument(what + " '" + n + "' is no physical group of " + r.path +
                                    didYouMean(n, all_names) +
                                    "; the file's groups: " + (list.empty() ? "none" : list));
      }
  };
  known("region", r.regions);
  known("ignored group", r.ignore);

  Mesh mesh;
  mesh.groups = r.regions;
  std::map<std::size_t, long> index;  // gmsh node tag -> body node
  std::vector<std::size_t> order;     // body node -> gmsh node tag
  auto node = [&](std::size_t tag) {
    auto [it, fresh] = index.emplace(tag, static_cast<long>(order.size()));
    if (fresh) order.push_back(tag);
    return it->second;
  };
  std::vector<std::size_t> skipped_line_nodes;  // lines of curves in no group: mesh edges, checked below

  for (int dim = 1; dim <= 3; ++dim) {
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities, dim);
    for (const auto& [d, tag] : entities) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> etags, enodes;
      gmsh::model::mesh::getElements(types, etags, enodes, d, tag);
      std::size_t count = 0;
      for (const auto& t : etags) count += t.size();
      if (count == 0) continue;
      std::vector<int> ptags;
      gmsh::model::getPhysicalGroupsForEntity(d, tag, ptags);
      std::vector<std::string> names, region_names;
      for (int p : ptags) {
        names.push_back(group_name[{d, p}]);
        if (contains(r.regions, names.back())) region_names.push_back(names.back());
      }
      std::string where = entityText(d, tag);
      if (!names.empty()) {
        where += " (physical group";
        for (std::size_t k = 0; k < names.size(); ++k) where += (k ? ", '" : " '") + names[k] + "'";
        where += ")";
      }
      if (region_names.size() > 1)
        throw std::invalid_argument(where + " is in two regions, '" + region_names[0] + "' and '" + region_names[1] +
                                    "'; an element takes the properties of one region");
      if (region_names.empty()) {
        if (d == 1 && names.empty()) {
          // The edges gmsh meshes on every curve bounding a surface: not elements of the body.
          for (const auto& en : enodes) skipped_line_nodes.insert(skipped_line_nodes.end(), en.begin(), en.end());
          continue;
        }
        const bool left_out = std::any_of(names.begin(), names.end(), [&](const std::string& n) {
          return contains(r.ignore, n) || contains(r.sets, n);
        });
        if (left_out) continue;
        throw std::invalid_argument(
            where + " has " + std::to_string(count) + " " + elementName(types.front()) +
            " element(s) that belong to no region; give " +
            (names.empty() ? "the entity a physical group named" : "'" + names.front() + "' properties") +
            " under regions:, use it as a node set (interfaces:, reference:) or list it under ignore:");
      }
      if (d == 3)
        throw std::invalid_argument(where + " has " + std::to_string(count) +
                                    " volume elements; a body's regions are shells (surfaces) and beams (curves)");
      const int g = static_cast<int>(std::find(r.regions.begin(), r.regions.end(), region_names[0]) - r.regions.begin());
      for (std::size_t k = 0; k < types.size(); ++k) {
        const int type = types[k];
        const auto& en = enodes[k];
        const std::size_t n = etags[k].size();
        if (type == 2) {  // 3-node triangle
          for (std::size_t e = 0; e < n; ++e) {
            mesh.triangles.push_back({node(en[3 * e]), node(en[3 * e + 1]), node(en[3 * e + 2])});
            mesh.triangle_group.push_back(g);
          }
        } else if (type == 3) {  // 4-node quadrilateral: two triangles on the 1-3 diagonal
          for (std::size_t e = 0; e < n; ++e) {
            const long a = node(en[4 * e]), b = node(en[4 * e + 1]), c = node(en[4 * e + 2]), dd = node(en[4 * e + 3]);
            mesh.triangles.push_back({a, b, c});
            mesh.triangles.push_back({a, c, dd});
            mesh.triangle_group.push_back(g);
            mesh.triangle_group.push_back(g);
          }
        } else if (type == 1) {  // 2-node line
          for (std::size_t e = 0; e < n; ++e) {
            mesh.beams.push_back({node(en[2 * e]), node(en[2 * e + 1])});
            mesh.beam_group.push_back(g);
          }
        } else if (type == 15) {
          continue;  // a point element on a curve: no stiffness
        } else {
          std::string name;
          int edim, eorder, nn, npv;
          std::vector<double> local;
          gmsh::model::mesh::getElementProperties(type, name, edim, eorder, nn, local, npv);
          throw std::invalid_argument(
              where + " has " + std::to_string(n) + " " + name + " elements: " +
              (eorder > 1 ? "second- and higher-order elements are not read; mesh linear ones (gmsh -order 1, "
                            "Mesh.ElementOrder = 1) or convert the file (gmsh FILE -order 1 -save)"
                          : "expected 3-node triangles, 4-node quadrilaterals (surfaces) or 2-node lines (curves)"));
        }
      }
    }
  }
  if (mesh.triangles.empty() && mesh.beams.empty())
    throw std::invalid_argument(r.path + " has no element in the regions given");
  if (static_cast<long>(mesh.triangles.size()) > r.max_triangles)
    throw std::invalid_argument(r.path + " has " + std::to_string(mesh.triangles.size()) +
                                " triangles, more than mesh.max_triangles = " + std::to_string(r.max_triangles));
  for (std::size_t t : skipped_line_nodes)
    if (!index.count(t))
      throw std::invalid_argument(r.path + ": line elements of a curve in no physical group touch node " +
                                  std::to_string(t) + ", which no region's element uses; put the curve in a "
                                  "physical group and name it under regions: (a beam) or ignore:");

  // Coordinates, in metres.
  std::vector<std::size_t> tags;
  std::vector<double> coords, param;
  gmsh::model::mesh::getNodes(tags, coords, param, -1, -1, true, false);
  mesh.nodes.resize(static_cast<long>(order.size()), 3);
  for (std::size_t i = 0; i < tags.size(); ++i) {
    auto it = index.find(tags[i]);
    if (it == index.end()) continue;
    for (int c = 0; c < 3; ++c) mesh.nodes(it->second, c) = r.length_scale * coords[3 * i + static_cast<std::size_t>(c)];
  }

  // Every physical group's nodes as a set under its name.
  for (const auto& [key, name] : group_name) {
    std::vector<std::size_t> ntags;
    std::vector<double> ncoords;
    gmsh::model::mesh::getNodesForPhysicalGroup(key.first, key.second, ntags, ncoords);
    auto& set = mesh.sets[name];
    long missing = 0;
    for (std::size_t t : ntags) {
      auto it = index.find(t);
      if (it != index.end()) set.push_back(it->second);
      else ++missing;
    }
    if (missing > 0 && contains(r.sets, name))
      throw std::invalid_argument("node set '" + name + "' has " + std::to_string(missing) +
                                  " node(s) that no element of the body uses; a set's nodes must be on the body's "
                                  "shells or beams");
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  return mesh;
}

}  // namespace

Mesh readRegionMesh(const RegionMeshRequest& request) {
  // A .geo file is a program: refuse shell, file and exit commands before gmsh runs it.
  // An ASCII .msh is checked line by line first (counts, numbers given twice).
  if (endsWith(request.path, ".geo") || endsWith(request.path, ".msh")) checkGmshInput(request.path);
  const FatalErrorContext context(request.path + ": gmsh: ");
  try {
    return readGmsh(request);
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // out of memory is no input error (common/memory.h)
  } catch (...) {
    throw std::runtime_error(request.path + ": gmsh: " + currentExceptionMessage());
  }
}

}  // namespace fc::feprep
