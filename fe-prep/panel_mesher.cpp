#include "fe-prep/panel_mesher.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

namespace fc::feprep {
namespace {

// gmsh keeps global state: one session per meshing call, always finalized,
// so that a failure in one run never leaks a model into the next.
class GmshSession {
 public:
  explicit GmshSession(bool quiet) {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", quiet ? 0 : 1);
    gmsh::option::setNumber("General.Verbosity", quiet ? 0 : 2);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

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

Mesh meshRectangleOnce(const PanelMeshRequest& r, const std::vector<Eigen::Vector2d>& edge_pts,
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

  for (long i = 0; i < mesh.nodeCount(); ++i) {
    const double x = mesh.nodes(i, 0), y = mesh.nodes(i, 1);
    if (std::abs(x + a) < tol * 10) mesh.sets["edge_xmin"].push_back(i);
    if (std::abs(x - a) < tol * 10) mesh.sets["edge_xmax"].push_back(i);
    if (std::abs(y + b) < tol * 10) mesh.sets["edge_ymin"].push_back(i);
    if (std::abs(y - b) < tol * 10) mesh.sets["edge_ymax"].push_back(i);
  }
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

  Mesh best;
  if (r.size > 0) {
    best = meshRectangleOnce(r, edge_pts, interior, r.size);
  } else {
    if (r.triangles <= 0) throw std::invalid_argument("mesh needs a positive triangle count or size");
    double h = sizeForTriangleCount(r.length * r.width, r.triangles);
    long best_err = -1;
    // The count responds to h roughly as 1/h^2; a few secant-like steps land close.
    for (int it = 0; it < 8; ++it) {
      Mesh m = meshRectangleOnce(r, edge_pts, interior, h);
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

Mesh meshGeoFile(const std::string& path, double size, const std::vector<Eigen::Vector3d>& forced_points,
                 bool quiet) {
  GmshSession session(quiet);
  try {
    gmsh::open(path);
  } catch (const std::exception& e) {
    throw std::runtime_error("gmsh cannot read '" + path + "': " + e.what());
  }
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
  gmsh::model::mesh::generate(2);
  Mesh mesh = extractTriangles();
  return mesh;
}

}  // namespace fc::feprep
