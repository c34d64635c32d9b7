#include "fe-prep/region_records.h"

#include <set>

namespace fc::feprep {
namespace {

// The printed line of region `name` ("name: ..."), and its material-axis part.
std::string lineOf(const std::vector<std::string>& summary, const std::string& name) {
  for (const std::string& l : summary)
    if (l.rfind(name + ": ", 0) == 0) return l;
  return "";
}
std::string tailFrom(const std::string& line, const std::string& marker) {
  const auto at = line.find(marker);
  return at == std::string::npos ? "" : line.substr(at + 2);
}

// The elements of property p (property_of[e] == p, e < count): members,
// their summed mass (mass_of(e)) and their axes (axis_of[e]).
template <class MassOf>
void addMembers(FlexRegion& r, std::size_t count, const std::vector<int>& property_of, std::size_t p, MassOf mass_of,
                const std::vector<Eigen::Vector3d>& axis_of) {
  for (std::size_t e = 0; e < count; ++e) {
    if (property_of[e] != static_cast<int>(p)) continue;
    r.mass += mass_of(e);
    r.members.push_back(static_cast<long>(e));
  }
  r.axes.resize(static_cast<long>(r.members.size()), 3);
  for (std::size_t k = 0; k < r.members.size(); ++k)
    r.axes.row(static_cast<long>(k)) = axis_of[static_cast<std::size_t>(r.members[k])].transpose();
}

}  // namespace

std::vector<FlexRegion> regionRecords(const Mesh& mesh, const std::vector<std::string>& summary) {
  std::vector<FlexRegion> out;
  std::set<std::string> names;
  // A shell or beam region with its printed line and the axis part of it.
  auto keep = [&](FlexRegion& r, const std::string& axis_marker) {
    r.summary = lineOf(summary, r.name);
    r.axis = tailFrom(r.summary, axis_marker);
    names.insert(r.name);
    out.push_back(std::move(r));
  };
  for (std::size_t p = 0; p < mesh.shell_properties.size(); ++p) {
    const ShellProperty& sp = mesh.shell_properties[p];
    FlexRegion r;
    r.name = sp.name;
    r.kind = "shell";
    r.members_of = "triangles";
    r.property = sp.laminate_name;
    r.element = sp.kind == fe::ShellKind::DST ? "dst" : "dkt";
    auto mass = [&](std::size_t e) {
      const auto& t = mesh.triangles[e];
      const Eigen::Vector3d x0 = mesh.nodes.row(t[0]), x1 = mesh.nodes.row(t[1]), x2 = mesh.nodes.row(t[2]);
      return 0.5 * (x1 - x0).cross(x2 - x0).norm() * sp.laminate.mass_per_area;
    };
    addMembers(r, mesh.triangles.size(), mesh.triangle_property, p, mass, mesh.triangle_axis);
    keep(r, ", fibre ");
  }
  for (std::size_t p = 0; p < mesh.beam_properties.size(); ++p) {
    const BeamProperty& bp = mesh.beam_properties[p];
    FlexRegion r;
    r.name = bp.name;
    r.kind = "beam";
    r.members_of = "beams";
    r.property = bp.source;
    r.element = "timoshenko";
    auto mass = [&](std::size_t e) {
      const auto& b = mesh.beams[e];
      return (mesh.nodes.row(b[1]) - mesh.nodes.row(b[0])).norm() * bp.Ms(0, 0);
    };
    addMembers(r, mesh.beams.size(), mesh.beam_property, p, mass, mesh.beam_x2);
    keep(r, ", x2 ");
  }
  // Node sets (physical groups, Nastran sets) that are no region of their own.
  for (const auto& [name, nodes] : mesh.sets) {
    if (names.count(name) || nodes.empty()) continue;
    FlexRegion r;
    r.name = name;
    r.kind = "set";
    r.members_of = "nodes";
    r.members = nodes;
    r.summary = name + ": " + std::to_string(nodes.size()) + " nodes";
    out.push_back(std::move(r));
  }
  if (!mesh.point_masses.empty()) {
    FlexRegion r;
    r.name = "masses";  // a group of that name keeps it: the record gets a free one
    while (names.count(r.name) || mesh.sets.count(r.name)) r.name += "_";
    r.kind = "masses";
    r.members_of = "nodes";
    for (const auto& pm : mesh.point_masses) {
      r.members.push_back(pm.node);
      r.mass += pm.mass;
    }
    r.summary = lineOf(summary, "masses");
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace fc::feprep
