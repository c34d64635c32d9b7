#include "fe-prep/panel_mesher.h"

#include <gmsh.h>

#include "common/geo_script.h"
#include "common/input.h"
#include "common/termination.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "fe-prep/gmsh_session.h"

namespace fc::feprep {
namespace {

// Reads the current gmsh model's triangles (linear, type 2) and their nodes.
Mesh extractTriangles() {
  std::vector<std::size_t> tags;
  std::vector<double> coords, param;
  gmsh::model::mesh::getNodes(tags, coords, param, -1, -1, true, false);
  std::vector<std::size_t> elem_tags, elem_nodes;
  gmsh::model::mesh::getElementsByType(2, elem_tags, elem_nodes, -1);
  if (elem_tags.empty()) throw std::runtime_error("gmsh produced no triangles");

  // Keep only nodes that triangles use (geometry points off the surface are dropped).
  std::map<std::size_t, std::size_t> position;
  for (std::size_t i = 0; i < tags.size(); ++i) position[tags[i]] = i;
  std::map<std::size_t, long> index;
  Mesh mesh;
  std::vector<Eigen::Vector3d> pts;
  auto idx = [&](std::size_t tag) {
    auto it = index.find(tag);
    if (it != index.end()) return it->second;
    const std::size_t p = position.at(tag);
    pts.emplace_back(coords[3 * p], coords[3 * p + 1], coords[3 * p + 2]);
    const long k = static_cast<long>(pts.size()) - 1;
    index[tag] = k;
    return k;
  };
  for (std::size_t e = 0; e < elem_tags.size(); ++e)
    mesh.triangles.push_back({idx(elem_nodes[3 * e]), idx(elem_nodes[3 * e + 1]), idx(elem_nodes[3 * e + 2])});
  mesh.nodes.resize(static_cast<long>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) mesh.nodes.row(static_cast<long>(i)) = pts[i].transpose();

  // Node sets from physical groups of points and curves (geo files).
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  for (const auto& [dim, tag] : groups) {
    if (dim > 1) continue;
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (name.empty()) name = "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
    std::vector<std::size_t> ntags;
    std::vector<double> ncoords;
    gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, ntags, ncoords);
    auto& set = mesh.sets[name];
    for (std::size_t t : ntags) {
      auto it = index.find(t);
      if (it != index.end()) set.push_back(it->second);
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  return mesh;
}

Mesh meshRectangleGmsh(const PanelMeshRequest& r, const std::vector<Eigen::Vector2d>& edge_pts,
                       const std::vector<Eigen::Vector2d>& interior, double h);

// gmsh reports errors by throwing std::string, and aborts the process when it
// throws inside its OpenMP meshing loop: the first become std::runtime_error, the
// second a one-line error through the terminate handler (common/termination.h).
template <class F>
auto withGmsh(const std::string& what, F f) -> decltype(f()) {
  const FatalErrorContext context(what + ": gmsh: ");
  try {
    return f();
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // out of memory is no input error (common/memory.h)
  } catch (...) {
    throw std::runtime_error(what + ": gmsh: " + currentExceptionMessage());
  }
}

// A mesh this large would exhaust memory in the eigen solve long before it ended.
void checkTriangleCount(double estimate, long limit, const std::string& how) {
  if (estimate > static_cast<double>(limit)) {
    std::ostringstream os;
    os << how << " gives about " << std::setprecision(2) << estimate
       << " triangles, more than the limit of " << limit
       << " (memory and time of the modal solve); use fewer triangles or a larger size, or raise "
          "mesh.max_triangles if the machine can take it";
    throw std::invalid_argument(os.str());
  }
}

// The element size inside box q at mesh size h (box_size_fraction, box_graded_from), or 0 for none:
// boxes thin enough to be a line, and caps at or above h.
double boxCap(const PanelMeshRequest& r, const Eigen::Vector4d& q, double h) {
  const double tol = 1e-9 * std::max(r.length, r.width);
  const double dx = q(2) - q(0), dy = q(3) - q(1);
  if (!(dx > tol && dy > tol)) return 0.0;
  const double graded = r.box_graded_from > 0 ? std::min(1.0, h / r.box_graded_from) : 1.0;
  const double cap = r.box_size_fraction * std::min(dx, dy) * graded;
  return cap > 0 && cap < h ? cap : 0.0;
}

// A thin box's cap can ask for millions of triangles: its area at the cap plus the graded ring
// around it (size growing linearly from cap to h over h: about perimeter / (sqrt(3)/4 cap)),
// checked against the limit before gmsh runs.
void checkBoxCaps(const PanelMeshRequest& r, const std::vector<Eigen::Vector4d>& boxes, double h) {
  double estimate = r.length * r.width / (std::sqrt(3.0) / 4 * h * h), capped = 0;
  for (const auto& q : boxes)
    if (const double cap = boxCap(r, q, h); cap > 0) {
      estimate += ((q(2) - q(0)) * (q(3) - q(1)) / cap + 2 * (q(2) - q(0) + q(3) - q(1))) / (std::sqrt(3.0) / 4 * cap);
      capped = capped == 0 ? cap : std::min(capped, cap);
    }
  if (capped > 0) {
    std::ostringstream how;
    how << "size " << h << " m with elements of " << capped << " m inside the thinnest box patch (half its smaller side)";
    checkTriangleCount(estimate, r.max_triangles, how.str());
  }
}

Mesh meshRectangleConforming(const PanelMeshRequest& r, const std::vector<Eigen::Vector4d>& boxes, double h);

Mesh meshRectangleOnce(const PanelMeshRequest& r, const std::vector<Eigen::Vector2d>& edge_pts,
                       const std::vector<Eigen::Vector2d>& interior, const std::vector<Eigen::Vector4d>& boxes,
                       double h) {
  if (!boxes.empty()) checkBoxCaps(r, boxes, h);
  return withGmsh("rectangular panel", [&] {
    return boxes.empty() ? meshRectangleGmsh(r, edge_pts, interior, h) : meshRectangleConforming(r, boxes, h);
  });
}

// Node sets of the rectangle's edges, by coordinate.
void addEdgeSets(Mesh& mesh, double a, double b, double tol) {
  for (long i = 0; i < mesh.nodeCount(); ++i) {
    const double x = mesh.nodes(i, 0), y = mesh.nodes(i, 1);
    if (std::abs(x + a) < tol) mesh.sets["edge_xmin"].push_back(i);
    if (std::abs(x - a) < tol) mesh.sets["edge_xmax"].push_back(i);
    if (std::abs(y + b) < tol) mesh.sets["edge_ymin"].push_back(i);
    if (std::abs(y - b) < tol) mesh.sets["edge_ymax"].push_back(i);
  }
}

// The rectangle fragmented by the (clipped) boxes and the forced points (OpenCASCADE
// BooleanFragments: intersecting or touching boxes, points on box outlines and on the
// rectangle's edges are all resolved by the kernel), every face meshed with size h.
Mesh meshRectangleConforming(const PanelMeshRequest& r, const std::vector<Eigen::Vector4d>& boxes, double h) {
  const double a = r.length / 2, b = r.width / 2;
  const double tol = 1e-9 * std::max(r.length, r.width);
  GmshSession session(r.quiet);
  gmsh::model::add("panel");
  const int panel = gmsh::model::occ::addRectangle(-a, -b, 0.0, r.length, r.width);
  gmsh::vectorpair tools;
  for (const auto& q : boxes) {
    const double dx = q(2) - q(0), dy = q(3) - q(1);
    if (dx > tol && dy > tol) {
      tools.emplace_back(2, gmsh::model::occ::addRectangle(q(0), q(1), 0.0, dx, dy));
    } else if (dx > tol || dy > tol) {
      const int p0 = gmsh::model::occ::addPoint(q(0), q(1), 0.0), p1 = gmsh::model::occ::addPoint(q(2), q(3), 0.0);
      tools.emplace_back(1, gmsh::model::occ::addLine(p0, p1));
    } else {
      tools.emplace_back(0, gmsh::model::occ::addPoint(q(0), q(1), 0.0));
    }
  }
  for (const auto& p : r.forced_points) tools.emplace_back(0, gmsh::model::occ::addPoint(p.x(), p.y(), 0.0));
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> out_map;
  gmsh::model::occ::fragment({{2, panel}}, tools, out, out_map);
  gmsh::model::occ::synchronize();
  // The size cap inside each box (box_size_fraction): a gmsh Box field per capped box, the size
  // growing linearly back to h over a distance h outside it (well-shaped triangles in the
  // transition), their minimum the background size. The field's box is widened by tol so that
  // the outline's nodes, on it to rounding, count as inside.
  std::vector<double> caps;
  for (const auto& q : boxes) {
    const double cap = boxCap(r, q, h);
    if (cap == 0.0) continue;
    const int f = gmsh::model::mesh::field::add("Box");
    gmsh::model::mesh::field::setNumber(f, "VIn", cap);
    gmsh::model::mesh::field::setNumber(f, "VOut", h);
    gmsh::model::mesh::field::setNumber(f, "XMin", q(0) - tol);
    gmsh::model::mesh::field::setNumber(f, "XMax", q(2) + tol);
    gmsh::model::mesh::field::setNumber(f, "YMin", q(1) - tol);
    gmsh::model::mesh::field::setNumber(f, "YMax", q(3) + tol);
    gmsh::model::mesh::field::setNumber(f, "ZMin", -1.0);
    gmsh::model::mesh::field::setNumber(f, "ZMax", 1.0);
    gmsh::model::mesh::field::setNumber(f, "Thickness", h);
    caps.push_back(f);
  }
  if (!caps.empty()) {
    const int fmin = gmsh::model::mesh::field::add("Min");
    gmsh::model::mesh::field::setNumbers(fmin, "FieldsList", caps);
    gmsh::model::mesh::field::setAsBackgroundMesh(fmin);
  }
  gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay, as the plain rectangle
  gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  gmsh::model::mesh::generate(2);
  Mesh mesh = extractTriangles();
  addEdgeSets(mesh, a, b, tol * 10);
  return mesh;
}

Mesh meshRectangleGmsh(const PanelMeshRequest& r, const std::vector<Eigen::Vector2d>& edge_pts,
                       const std::vector<Eigen::Vector2d>& interior, double h) {
  GmshSession session(r.quiet);
  gmsh::model::add("panel");
  const double a = r.length / 2, b = r.width / 2;
  const double tol = 1e-9 * std::max(r.length, r.width);

  // Boundary walked counter-clockwise, corners plus the forced points on each edge.
  std::vector<Eigen::Vector2d> loop;
  auto edge = [&](Eigen::Vector2d from, Eigen::Vector2d to) {
    loop.push_back(from);
    const Eigen::Vector2d d = (to - from).normalized();
    const double len = (to - from).norm();
    std::vector<std::pair<double, Eigen::Vector2d>> on;
    for (const auto& p : edge_pts) {
      const double s = (p - from).dot(d);
      const double off = std::abs(d.x() * (p - from).y() - d.y() * (p - from).x());
      if (off < tol && s > tol && s < len - tol) on.emplace_back(s, p);
    }
    std::sort(on.begin(), on.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& [s, p] : on) loop.push_back(p);
  };
  edge({-a, -b}, {a, -b});
  edge({a, -b}, {a, b});
  edge({a, b}, {-a, b});
  edge({-a, b}, {-a, -b});

  std::vector<int> pts, lines;
  for (const auto& p : loop) pts.push_back(gmsh::model::geo::addPoint(p.x(), p.y(), 0.0, h));
  for (std::size_t i = 0; i < pts.size(); ++i)
    lines.push_back(gmsh::model::geo::addLine(pts[i], pts[(i + 1) % pts.size()]));
  const int cl = gmsh::model::geo::addCurveLoop(lines);
  const int surf = gmsh::model::geo::addPlaneSurface({cl});
  std::vector<int> inner;
  for (const auto& p : interior) inner.push_back(gmsh::model::geo::addPoint(p.x(), p.y(), 0.0, h));
  gmsh::model::geo::synchronize();
  if (!inner.empty()) gmsh::model::mesh::embed(0, inner, 2, surf);
  gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay: well-shaped triangles
  gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
  gmsh::model::mesh::generate(2);
  Mesh mesh = extractTriangles();
  addEdgeSets(mesh, a, b, tol * 10);
  return mesh;
}

// Counter-clockwise about +z, as the shell element expects for a +z normal.
void orientUp(Mesh& mesh) {
  for (auto& t : mesh.triangles) {
    const Eigen::Vector3d p0 = mesh.nodes.row(t[0]), p1 = mesh.nodes.row(t[1]), p2 = mesh.nodes.row(t[2]);
    if ((p1 - p0).cross(p2 - p0).z() < 0) std::swap(t[1], t[2]);
  }
}

}  // namespace

double sizeForTriangleCount(double area, long n) {
  return std::sqrt(4.0 * area / (std::sqrt(3.0) * static_cast<double>(n)));
}

Mesh meshRectangle(const PanelMeshRequest& r) {
  if (!(r.length > 0) || !(r.width > 0)) throw std::invalid_argument("panel length and width must be positive");
  const double a = r.length / 2, b = r.width / 2;
  const double tol = 1e-9 * std::max(r.length, r.width);
  std::vector<Eigen::Vector2d> edge_pts, interior;
  for (const auto& p : r.forced_points) {
    if (std::abs(p.x()) > a + tol || std::abs(p.y()) > b + tol) {
      std::ostringstream os;
      os << "point (" << p.x() << ", " << p.y() << ") lies outside the panel [" << -a << ", " << a
         << "] x [" << -b << ", " << b << "]";
      throw std::invalid_argument(os.str());
    }
    const bool on_edge = std::abs(std::abs(p.x()) - a) < tol || std::abs(std::abs(p.y()) - b) < tol;
    auto& list = on_edge ? edge_pts : interior;
    bool dup = false;
    for (const auto& q : list) dup = dup || (q - p).norm() < tol;
    if (!dup) list.push_back(p);
  }
  // Boxes clipped to the rectangle; one that misses it selects nothing there (resolveInterface says so).
  std::vector<Eigen::Vector4d> boxes;
  for (const auto& q : r.conforming_boxes) {
    const Eigen::Vector4d c(std::max(q(0), -a), std::max(q(1), -b), std::min(q(2), a), std::min(q(3), b));
    if (c(2) >= c(0) && c(3) >= c(1)) boxes.push_back(c);
  }

  const double area = r.length * r.width;
  if (r.size > 0)
    checkTriangleCount(area / (std::sqrt(3.0) / 4 * r.size * r.size), r.max_triangles,
                       "size " + std::to_string(r.size) + " m");
  else
    checkTriangleCount(static_cast<double>(r.triangles), r.max_triangles, "triangles: " + std::to_string(r.triangles));
  Mesh best;
  if (r.size > 0) {
    best = meshRectangleOnce(r, edge_pts, interior, boxes, r.size);
  } else {
    if (r.triangles <= 0) throw std::invalid_argument("mesh needs a positive triangle count or size");
    double h = sizeForTriangleCount(r.length * r.width, r.triangles);
    long best_err = -1;
    // The count responds to h roughly as 1/h^2; a few secant-like steps land close.
    for (int it = 0; it < 8; ++it) {
      Mesh m = meshRectangleOnce(r, edge_pts, interior, boxes, h);
      const long count = static_cast<long>(m.triangles.size());
      const long err = std::abs(count - r.triangles);
      if (best_err < 0 || err < best_err) {
        best_err = err;
        best = std::move(m);
      }
      if (err <= std::max<long>(1, r.triangles / 50)) break;
      h *= std::pow(static_cast<double>(count) / static_cast<double>(r.triangles), 0.5 * (it < 4 ? 1.0 : 0.5));
    }
  }
  orientUp(best);
  return best;
}

namespace {
Mesh meshGeoFileGmsh(const std::string& path, double size, const std::vector<Eigen::Vector3d>& forced_points,
                     bool quiet, long max_triangles);
}  // namespace

Mesh meshGeoFile(const std::string& path, double size, const std::vector<Eigen::Vector3d>& forced_points,
                 bool quiet, long max_triangles) {
  // A .geo file is a program: refuse shell, file and exit commands before gmsh runs it.
  checkGmshInput(path);
  return withGmsh(path, [&] { return meshGeoFileGmsh(path, size, forced_points, quiet, max_triangles); });
}

namespace {

Mesh meshGeoFileGmsh(const std::string& path, double size, const std::vector<Eigen::Vector3d>& forced_points,
                     bool quiet, long max_triangles) {
  GmshSession session(quiet);
  gmsh::open(path);
  // Embed forced points strictly inside planar surfaces: gmsh only accepts
  // embedded points inside the surface they belong to.
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  for (const auto& p : forced_points) {
    for (const auto& [dim, tag] : surfaces) {
      std::vector<double> coord = {p.x(), p.y(), p.z()}, closest, param;
      try {
        gmsh::model::getClosestPoint(dim, tag, coord, closest, param);
        if (closest.size() == 3 && (Eigen::Vector3d(closest[0], closest[1], closest[2]) - p).norm() < 1e-9 &&
            gmsh::model::isInside(dim, tag, param) > 0) {
          const int pt = gmsh::model::geo::addPoint(p.x(), p.y(), p.z(), size > 0 ? size : 0.0);
          gmsh::model::geo::synchronize();
          gmsh::model::mesh::embed(0, {pt}, dim, tag);
          break;
        }
      } catch (const std::exception&) {
        // Not a geo-kernel plane surface: the nearest node stands in for the point.
      }
    }
  }
  if (size > 0) gmsh::option::setNumber("Mesh.MeshSizeMax", size);
  // The file's own sizes are unknown before meshing: bound them from below so the
  // count stays near max_triangles over the surfaces' total area.
  double area = 0;
  for (const auto& [dim, tag] : surfaces) {
    // The largest face of the bounding box: an upper bound for a plane surface.
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
    const double dx = x1 - x0, dy = y1 - y0, dz = z1 - z0;
    area += std::max({dx * dy, dy * dz, dx * dz});
  }
  if (area > 0 && std::isfinite(area)) {
    if (size > 0)
      checkTriangleCount(area / (std::sqrt(3.0) / 4 * size * size), max_triangles,
                         "size " + std::to_string(size) + " m");
    gmsh::option::setNumber("Mesh.MeshSizeMin", std::sqrt(area / (std::sqrt(3.0) / 4 * static_cast<double>(max_triangles))));
  }
  gmsh::model::mesh::generate(2);
  Mesh mesh = extractTriangles();
  if (static_cast<long>(mesh.triangles.size()) > 2 * max_triangles)
    checkTriangleCount(static_cast<double>(mesh.triangles.size()), max_triangles, path);
  return mesh;
}

}  // namespace

}  // namespace fc::feprep
