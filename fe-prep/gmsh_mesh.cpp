#include "fe-prep/gmsh_mesh.h"

#include <cmath>
#include <stdexcept>

#include "fe-prep/mesh_files/gmsh_regions.h"
#include "fe-prep/panel_mesher.h"

namespace fc::feprep {

Mesh meshWithGmsh(const BodySpec& spec, const std::vector<std::string>& sets, bool quiet) {
  if (spec.general) {
    RegionMeshRequest r;
    r.path = spec.general->file;
    r.size = spec.general->size;
    r.length_scale = spec.general->length_scale;
    r.max_triangles = spec.general->max_triangles;
    for (const auto& reg : spec.general->regions) r.regions.push_back(reg.name);
    r.ignore = spec.general->ignore;
    // Interface and reference names that are no group are checked later, against the mesh's sets.
    r.sets = sets;
    r.quiet = quiet;
    return readRegionMesh(r);
  } else if (spec.shell && spec.shell->rectangle) {
    PanelMeshRequest r;
    r.length = spec.shell->length;
    r.width = spec.shell->width;
    r.triangles = spec.shell->triangles;
    r.size = spec.shell->size;
    r.max_triangles = spec.shell->max_triangles;
    r.box_graded_from = spec.shell->graded_from;
    const double a = spec.shell->length / 2, b = spec.shell->width / 2;
    for (const auto& i : spec.interfaces) {
      // The node of a single-node interface (at its bracket's panel point, else at its projection); a
      // patch's point needs a node only where it lies over the panel (off it, its bracket's pin).
      if (i.bracket) r.forced_points.push_back(*i.bracket);
      else if (i.coupling == Coupling::Node || (std::abs(i.position.x()) <= a && std::abs(i.position.y()) <= b))
        r.forced_points.emplace_back(i.position.x(), i.position.y());
      // Box patches on the mid-surface (z = 0) are meshed conforming: the same region at every size.
      if (i.coupling != Coupling::Node && i.select == PatchSelect::Box && i.box_lo.z() <= 0.0 && i.box_hi.z() >= 0.0)
        r.conforming_boxes.emplace_back(i.box_lo.x(), i.box_lo.y(), i.box_hi.x(), i.box_hi.y());
    }
    return meshRectangle(r);
  } else if (spec.shell) {
    std::vector<Eigen::Vector3d> pts;
    for (const auto& i : spec.interfaces) pts.push_back(i.position);
    return meshGeoFile(spec.shell->geo_file, spec.shell->size, pts, true, spec.shell->max_triangles);
  }
  throw std::logic_error("meshWithGmsh: the body has no shell or mesh file to mesh");
}

}  // namespace fc::feprep
