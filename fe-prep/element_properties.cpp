#include "fe-prep/element_properties.h"

#include <stdexcept>

#include "fe-prep/elements/shell_frame.h"

namespace fc::feprep {

Eigen::Vector3d referenceAxisAt(const MaterialAxis& axis, const Eigen::Vector3d& point) {
  if (axis.kind == MaterialAxis::Kind::Vector) return axis.vector;
  if (!axis.hoop) return axis.direction;
  const Eigen::Vector3d d = point - axis.origin;
  const Eigen::Vector3d radial = d - d.dot(axis.direction) * axis.direction;
  if (!(radial.norm() > 1e-12 * std::max(1.0, d.norm())))
    throw std::invalid_argument("a point on the cylinder's axis has no hoop direction");
  return axis.direction.cross(radial).normalized();
}

Eigen::Matrix3d triangleXyz(const Mesh& mesh, long e) {
  Eigen::Matrix3d xyz;
  for (int i = 0; i < 3; ++i) xyz.row(i) = mesh.nodes.row(mesh.triangles[static_cast<std::size_t>(e)][static_cast<std::size_t>(i)]);
  return xyz;
}

Eigen::Vector3d regionAxisOnTriangle(const RegionSpec& r, const Mesh& mesh, long e) {
  const Eigen::Matrix3d xyz = triangleXyz(mesh, e);
  const Eigen::Vector3d c = xyz.colwise().mean();
  Eigen::Vector3d a;
  try {
    a = referenceAxisAt(r.axis, c);
    fe::shellFrame(xyz, a);  // the axis must not be normal to the element
  } catch (const std::invalid_argument& ex) {
    r.node.fail("region '" + r.name + "': the fibre reference axis is undefined on the triangle at (" +
                std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + "): " +
                ex.what() + "; choose an axis: that is not normal to the surface there");
  }
  return a;
}

namespace {

void legacyProperties(const BodySpec& spec, Mesh& mesh) {
  const long nt = static_cast<long>(mesh.triangles.size()), nb = static_cast<long>(mesh.beams.size());
  if (spec.shell) {
    ShellProperty p;
    p.name = "shell";
    p.laminate_name = spec.shell->laminate_name;
    p.laminate = spec.shell->laminate;
    p.plies = spec.shell->plies;
    p.kind = spec.shell->kind;
    mesh.shell_properties = {p};
  }
  if (spec.beam) {
    BeamProperty p;
    p.name = "beam";
    p.source = spec.beam->section_source;
    p.Ks = spec.beam->Ks;
    p.Ms = spec.beam->Ms;
    mesh.beam_properties = {p};
  }
  // shell: body x is every triangle's reference axis; beam: body y its section x2 (contracts.md).
  mesh.triangle_property.assign(static_cast<std::size_t>(nt), 0);
  mesh.triangle_axis.assign(static_cast<std::size_t>(nt), Eigen::Vector3d::UnitX());
  mesh.beam_property.assign(static_cast<std::size_t>(nb), 0);
  mesh.beam_x2.assign(static_cast<std::size_t>(nb), Eigen::Vector3d::UnitY());
}

}  // namespace

void assignElementProperties(const BodySpec& spec, Mesh& mesh) {
  mesh.shell_properties.clear();
  mesh.beam_properties.clear();
  mesh.point_masses.clear();
  if (!spec.general) return legacyProperties(spec, mesh);
  const GeneralMeshSpec& g = *spec.general;
  const long nt = static_cast<long>(mesh.triangles.size()), nb = static_cast<long>(mesh.beams.size());
  // Region r's property index in its table, by the mesh's group names.
  std::vector<int> shell_of(mesh.groups.size(), -1), beam_of(mesh.groups.size(), -1);
  std::vector<const RegionSpec*> region_of(mesh.groups.size(), nullptr);
  for (std::size_t k = 0; k < mesh.groups.size(); ++k) {
    for (const auto& r : g.regions) {
      if (r.name != mesh.groups[k]) continue;
      region_of[k] = &r;
      if (r.shell) {
        shell_of[k] = static_cast<int>(mesh.shell_properties.size());
        mesh.shell_properties.push_back(r.shell_property);
      } else {
        beam_of[k] = static_cast<int>(mesh.beam_properties.size());
        mesh.beam_properties.push_back(r.beam_property);
      }
    }
  }
  mesh.triangle_property.resize(static_cast<std::size_t>(nt));
  mesh.triangle_axis.resize(static_cast<std::size_t>(nt));
  for (long e = 0; e < nt; ++e) {
    const int grp = mesh.triangle_group[static_cast<std::size_t>(e)];
    const RegionSpec* r = grp >= 0 ? region_of[static_cast<std::size_t>(grp)] : nullptr;
    if (!r) g.file_node.fail("triangle " + std::to_string(e + 1) + " belongs to no region");
    if (!r->shell)
      r->node.fail("region '" + r->name + "' is a beam region but its physical group has surface elements; "
                   "expected shell: {...} for a surface group");
    mesh.triangle_property[static_cast<std::size_t>(e)] = shell_of[static_cast<std::size_t>(grp)];
    mesh.triangle_axis[static_cast<std::size_t>(e)] = regionAxisOnTriangle(*r, mesh, e);
  }
  mesh.beam_property.resize(static_cast<std::size_t>(nb));
  mesh.beam_x2.resize(static_cast<std::size_t>(nb));
  for (long e = 0; e < nb; ++e) {
    const int grp = mesh.beam_group[static_cast<std::size_t>(e)];
    const RegionSpec* r = grp >= 0 ? region_of[static_cast<std::size_t>(grp)] : nullptr;
    if (!r) g.file_node.fail("line element " + std::to_string(e + 1) + " belongs to no region");
    if (r->shell)
      r->node.fail("region '" + r->name + "' is a shell region but its physical group has line elements; "
                   "expected beam: {...} for a curve group");
    const auto& b = mesh.beams[static_cast<std::size_t>(e)];
    const Eigen::Vector3d axis = (mesh.nodes.row(b[1]) - mesh.nodes.row(b[0])).transpose();
    if (axis.cross(r->orientation).norm() <= 1e-6 * axis.norm() * r->orientation.norm())
      r->node.fail("region '" + r->name + "': the orientation vector is parallel to the beam element from (" +
                   std::to_string(mesh.nodes(b[0], 0)) + ", " + std::to_string(mesh.nodes(b[0], 1)) + ", " +
                   std::to_string(mesh.nodes(b[0], 2)) + "); expected a direction across the beam (the section's x2)");
    mesh.beam_property[static_cast<std::size_t>(e)] = beam_of[static_cast<std::size_t>(grp)];
    mesh.beam_x2[static_cast<std::size_t>(e)] = r->orientation;
  }
  for (const auto& m : g.masses) {
    PointMass pm;
    // At the nearest node (contracts.md): its mass and inertia act there.
    pm.node = mesh.nearestNode(m.at);
    pm.point = mesh.nodes.row(pm.node).transpose();
    pm.mass = m.mass;
    pm.inertia = m.inertia;
    mesh.point_masses.push_back(pm);
  }
}

Eigen::MatrixXd triangleMaterialAxes(const Mesh& mesh) {
  const long nt = static_cast<long>(mesh.triangles.size());
  Eigen::MatrixXd a(nt, 3);
  for (long e = 0; e < nt; ++e)
    a.row(e) = fe::shellFrame(triangleXyz(mesh, e), mesh.triangle_axis[static_cast<std::size_t>(e)]).R.row(0);
  return a;
}

}  // namespace fc::feprep
