#include "fe-prep/build_body.h"
#include "fe-prep/stress_recovery_data.h"
#include "fe-prep/region_records.h"

#include <sys/resource.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "common/memory.h"
#include "common/progress.h"
#include "fe-prep/assembly.h"
#include "fe-prep/beam_mesher.h"
#include "fe-prep/body_inertia.h"
#include "fe-prep/craig_bampton.h"
#include "fe-prep/element_properties.h"
#include "fe-prep/gmsh_mesh.h"
#include "fe-prep/geometric_stiffness.h"
#include "fe-prep/import/import_stage.h"
#include <optional>
#include "fe-prep/interfaces.h"
#include "fe-prep/reference_conditions.h"
#include "fe-prep/residual_flexibility.h"
#include "fe-prep/static_response.h"
#include "fe-prep/elements/beam_element.h"
#include "fe-prep/elements/shell_triangle.h"
#include "fe-prep/mass_lumping.h"
#include "fe-prep/modal_solver.h"

namespace fc::feprep {
namespace {

void broadcastMesh(Comm comm, Mesh& mesh) {
  const int rank = commRank(comm);
  long sizes[3] = {mesh.nodeCount(), static_cast<long>(mesh.triangles.size()), static_cast<long>(mesh.beams.size())};
  broadcast(comm, sizes, 3);
  if (rank != 0) {
    mesh.nodes.resize(sizes[0], 3);
    mesh.triangles.resize(static_cast<std::size_t>(sizes[1]));
    mesh.beams.resize(static_cast<std::size_t>(sizes[2]));
  }
  broadcast(comm, mesh.nodes.data(), static_cast<long>(mesh.nodes.size()));
  broadcast(comm, mesh.triangles.data()->data(), static_cast<long>(3 * sizes[1]));
  broadcast(comm, mesh.beams.data()->data(), static_cast<long>(2 * sizes[2]));
  // Each element's group (mesh files with regions): the properties follow on every rank.
  long has_groups = mesh.triangle_group.size() == mesh.triangles.size() && mesh.beam_group.size() == mesh.beams.size() &&
                    !mesh.groups.empty();
  broadcast(comm, &has_groups, 1);
  if (has_groups) {
    mesh.triangle_group.resize(static_cast<std::size_t>(sizes[1]));
    mesh.beam_group.resize(static_cast<std::size_t>(sizes[2]));
    broadcast(comm, mesh.triangle_group.data(), static_cast<long>(sizes[1]));
    broadcast(comm, mesh.beam_group.data(), static_cast<long>(sizes[2]));
    std::string gnames;
    for (const auto& g : mesh.groups) gnames += g + "\n";
    long glen = static_cast<long>(gnames.size());
    broadcast(comm, &glen, 1);
    gnames.resize(static_cast<std::size_t>(glen));
    broadcast(comm, gnames.data(), static_cast<long>(glen));
    mesh.groups.clear();
    std::istringstream gin(gnames);
    for (std::string g; std::getline(gin, g);) mesh.groups.push_back(g);
  }
  // Sets as "name\n" strings plus their index lists.
  std::string names;
  std::vector<long> counts, members;
  for (const auto& [name, list] : mesh.sets) {
    names += name + "\n";
    counts.push_back(static_cast<long>(list.size()));
    members.insert(members.end(), list.begin(), list.end());
  }
  long lens[3] = {static_cast<long>(names.size()), static_cast<long>(counts.size()), static_cast<long>(members.size())};
  broadcast(comm, lens, 3);
  names.resize(static_cast<std::size_t>(lens[0]));
  counts.resize(static_cast<std::size_t>(lens[1]));
  members.resize(static_cast<std::size_t>(lens[2]));
  broadcast(comm, names.data(), static_cast<long>(lens[0]));
  broadcast(comm, counts.data(), static_cast<long>(lens[1]));
  broadcast(comm, members.data(), static_cast<long>(lens[2]));
  if (rank != 0) {
    mesh.sets.clear();
    std::istringstream in(names);
    std::string name;
    std::size_t k = 0, at = 0;
    while (std::getline(in, name)) {
      const long c = counts[k++];
      mesh.sets[name].assign(members.begin() + static_cast<long>(at), members.begin() + static_cast<long>(at) + c);
      at += static_cast<std::size_t>(c);
    }
  }
}

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Wall and CPU time of a stage: on a shared machine the CPU time is the stable one.
class Stopwatch {
 public:
  void start() {
    t0_ = std::chrono::steady_clock::now();
    c0_ = processCpuSeconds();
  }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
  double cpu() const { return processCpuSeconds() - c0_; }

 private:
  std::chrono::steady_clock::time_point t0_;
  double c0_ = 0.0;
};

// The recovery basis of a mesh-file body's beams: that of the section file all
// its used beam regions share; none (with `note` saying why) when they use
// different sections and any of them has a basis.
SectionStressBasis regionsSectionBasis(const GeneralMeshSpec& g, const Mesh& mesh, std::string& note) {
  const RegionSpec* first = nullptr;
  bool any_basis = false, same = true;
  std::string names;
  for (const auto& r : g.regions) {
    if (r.shell) continue;
    const bool used = std::any_of(mesh.beam_properties.begin(), mesh.beam_properties.end(),
                                  [&](const auto& p) { return p.name == r.name; });
    if (!used) continue;
    any_basis = any_basis || !r.section_basis.empty();
    names += (names.empty() ? "" : ", ") + r.name + " (" + r.beam_property.source + ")";
    if (!first) first = &r;
    else if (r.beam_property.source != first->beam_property.source) same = false;
  }
  if (!first || !any_basis) return {};
  if (!same) {
    note = "no beam ply stress recovery: the beam regions use different sections [" + names +
           "] and the body file holds one section basis; section forces only";
    return {};
  }
  return first->section_basis;
}

// The shell part: every triangle's centroid and generalised strains per mode,
// and the one ply table; false (with `note`) when the shell regions differ in plies.
bool shellStressData(const Mesh& mesh, const Eigen::MatrixXd& shapes, StressRecoveryData& d, std::string& note) {
  for (const auto& p : mesh.shell_properties)
    if (p.plies.z_mid != mesh.shell_properties.front().plies.z_mid ||
        p.plies.angle_deg != mesh.shell_properties.front().plies.angle_deg ||
        p.plies.stiffness != mesh.shell_properties.front().plies.stiffness ||
        p.plies.strength != mesh.shell_properties.front().plies.strength) {
      note = "no stress recovery data: the shell regions have different ply tables (the body file holds one)";
      return false;
    }
  const long nm = shapes.cols();
  const long ne = static_cast<long>(mesh.triangles.size());
  d.centroids.resize(ne, 3);
  d.shell_strains.resize(6 * ne, nm);
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
  Eigen::Matrix<double, 18, Eigen::Dynamic> q(18, nm);
  for (long e = 0; e < ne; ++e) {
    const auto& t = mesh.triangles[static_cast<std::size_t>(e)];
    Eigen::Matrix3d xyz;
    for (int i = 0; i < 3; ++i) {
      xyz.row(i) = mesh.nodes.row(t[static_cast<std::size_t>(i)]);
      q.middleRows<6>(6 * i) = shapes.middleRows<6>(6 * t[static_cast<std::size_t>(i)]);
    }
    d.centroids.row(e) = xyz.colwise().mean();
    const ShellProperty& p = mesh.shellProperty(e);
    d.shell_strains.middleRows<6>(6 * e) =
        fe::shellStrainOperator(xyz, p.laminate, p.kind, mesh.triangle_axis[static_cast<std::size_t>(e)], centre) * q;
  }
  d.plies = mesh.shell_properties.front().plies;
  return true;
}

// The beam part: every beam's midpoint (into `midpoints`), its section
// resultants per mode and, where the sections have one, the recovery basis.
void beamStressData(const Mesh& mesh, const BodySpec& spec, const Eigen::MatrixXd& shapes, StressRecoveryData& d,
                    Eigen::MatrixXd& midpoints, std::string& note) {
  const long nm = shapes.cols();
  const long ne = static_cast<long>(mesh.beams.size());
  midpoints.resize(ne, 3);
  for (long e = 0; e < ne; ++e) {
    const auto& b = mesh.beams[static_cast<std::size_t>(e)];
    midpoints.row(e) = 0.5 * (mesh.nodes.row(b[0]) + mesh.nodes.row(b[1]));
  }
  // Section resultants at the midpoints per mode, by the element's own
  // equilibrium (fc::fe::beamMidpointResultants, docs/elements.md).
  if (mesh.beam_properties.size() == 1 &&
      std::all_of(mesh.beam_x2.begin(), mesh.beam_x2.end(), [&](const Eigen::Vector3d& v) { return v == mesh.beam_x2.front(); })) {
    d.beam_resultants = fe::beamModalResultants(mesh.nodes, mesh.beams, mesh.beam_x2.front(),
                                                mesh.beam_properties.front().Ks, shapes);
  } else {
    d.beam_resultants.resize(6 * ne, nm);
    for (long e = 0; e < ne; ++e) {
      const auto& b = mesh.beams[static_cast<std::size_t>(e)];
      Eigen::Matrix<double, 12, Eigen::Dynamic> q(12, nm);
      q.topRows<6>() = shapes.middleRows<6>(6 * b[0]);
      q.bottomRows<6>() = shapes.middleRows<6>(6 * b[1]);
      d.beam_resultants.middleRows<6>(6 * e) =
          fe::beamMidpointResultants(mesh.nodes.row(b[0]).transpose(), mesh.nodes.row(b[1]).transpose(),
                                     mesh.beam_x2[static_cast<std::size_t>(e)], mesh.beamProperty(e).Ks) * q;
    }
  }
  // The section's stresses per unit resultant, for ply stresses at stations:
  // a beam: body's, or the one section file every beam region of a
  // mesh-file body uses (the body file holds one basis).
  if (spec.beam) d.section = spec.beam->section_basis;
  if (spec.general) d.section = regionsSectionBasis(*spec.general, mesh, note);
  if (d.section.empty()) return;
  d.beam_lengths.resize(ne);
  d.beam_stations.resize(3 * ne, 3);
  for (long e = 0; e < ne; ++e) {
    const auto& b = mesh.beams[static_cast<std::size_t>(e)];
    d.beam_lengths(e) = (mesh.nodes.row(b[1]) - mesh.nodes.row(b[0])).norm();
    d.beam_stations.row(3 * e) = mesh.nodes.row(b[0]);
    d.beam_stations.row(3 * e + 1) = midpoints.row(e);
    d.beam_stations.row(3 * e + 2) = mesh.nodes.row(b[1]);
  }
}

}  // namespace

// What stress recovery needs (docs/stresses.md): every element's centroid
// (beams: midpoint) and, for shells, the generalised strains at the centroid
// per mode, through the element's own strain operator (the one its stiffness
// integrates, with its own laminate, kind and material axis), plus the ply
// table; for beams, the section resultants at the midpoint per mode, each with
// its own section and x2 axis; a body of both gets both. The body file holds
// one ply table: a body whose shell regions have different plies gets none
// (`note` says so).
StressRecoveryData stressRecoveryData(const Mesh& mesh, const BodySpec& spec, const Eigen::MatrixXd& shapes, std::string& note) {
  StressRecoveryData d;
  if (!mesh.triangles.empty() && !shellStressData(mesh, shapes, d, note)) return {};
  if (mesh.beams.empty()) return d;
  Eigen::MatrixXd midpoints;
  beamStressData(mesh, spec, shapes, d, midpoints, note);
  if (mesh.triangles.empty()) {
    d.centroids = std::move(midpoints);
    return d;
  }
  // A body of both (a stiffened panel, docs/stresses.md "Mixed bodies"): the
  // triangles' centroids, then the beams' midpoints, as /mesh/centroids.
  Eigen::MatrixXd all(d.centroids.rows() + midpoints.rows(), 3);
  all << d.centroids, midpoints;
  d.centroids = std::move(all);
  return d;
}

namespace {

// "skin: 648 triangles (dst), 1.36 kg, laminate skin_layup, fibre axis [1, 0, 0]" per property.
std::vector<std::string> regionSummary(const BodySpec& spec, const Mesh& mesh) {
  auto vec = [](const Eigen::Vector3d& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "[%.4g, %.4g, %.4g]", v.x(), v.y(), v.z());
    return std::string(buf);
  };
  std::vector<std::string> lines;
  for (std::size_t p = 0; p < mesh.shell_properties.size(); ++p) {
    long n = 0;
    double mass = 0.0;
    for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
      if (mesh.triangle_property[e] != static_cast<int>(p)) continue;
      const auto& t = mesh.triangles[e];
      const Eigen::Vector3d x0 = mesh.nodes.row(t[0]), x1 = mesh.nodes.row(t[1]), x2 = mesh.nodes.row(t[2]);
      mass += 0.5 * (x1 - x0).cross(x2 - x0).norm() * mesh.shell_properties[p].laminate.mass_per_area;
      ++n;
    }
    const ShellProperty& sp = mesh.shell_properties[p];
    std::string axis = "fibre axis [1, 0, 0] (body x)";
    if (spec.general && spec.general->nastran) {
      // The deck's THETA/MCID per element: say whether they agree.
      Eigen::Vector3d first = Eigen::Vector3d::Zero();
      bool same = true, any = false;
      for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
        if (mesh.triangle_property[e] != static_cast<int>(p)) continue;
        if (!any) first = mesh.triangle_axis[e], any = true;
        same = same && (mesh.triangle_axis[e] - first).norm() < 1e-9;
      }
      axis = same ? "fibre axis " + vec(first) + " (the deck's THETA/MCID)" : "fibre axes per element (the deck's THETA/MCID)";
    }
    if (spec.general)
      for (const auto& r : spec.general->regions)
        if (r.name == sp.name && r.shell)
          axis = r.axis.kind == MaterialAxis::Kind::Vector
                     ? "fibre axis " + vec(r.axis.vector) + " projected"
                     : std::string("fibre axis ") + (r.axis.hoop ? "hoop" : "axial") + " of the cylinder through " +
                           vec(r.axis.origin) + " along " + vec(r.axis.direction);
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s: %ld triangles (%s), %.6g kg, laminate %s, %s", sp.name.c_str(), n,
                  sp.kind == fe::ShellKind::DST ? "dst" : "dkt", mass, sp.laminate_name.c_str(), axis.c_str());
    lines.push_back(buf);
  }
  for (std::size_t p = 0; p < mesh.beam_properties.size(); ++p) {
    long n = 0;
    double mass = 0.0;
    Eigen::Vector3d x2 = Eigen::Vector3d::UnitY();
    for (std::size_t e = 0; e < mesh.beams.size(); ++e) {
      if (mesh.beam_property[e] != static_cast<int>(p)) continue;
      const auto& b = mesh.beams[e];
      mass += (mesh.nodes.row(b[1]) - mesh.nodes.row(b[0])).norm() * mesh.beam_properties[p].Ms(0, 0);
      x2 = mesh.beam_x2[e];
      ++n;
    }
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s: %ld beam elements, %.6g kg, section %s, x2 %s", mesh.beam_properties[p].name.c_str(),
                  n, mass, mesh.beam_properties[p].source.c_str(), vec(x2).c_str());
    lines.push_back(buf);
  }
  if (spec.general && !spec.general->deck_element_counts.empty()) {
    std::string t = "deck elements:";
    for (const auto& [card, n] : spec.general->deck_element_counts) t += " " + card + " " + std::to_string(n);
    if (spec.general->deck_element_counts.count("CQUAD4")) t += " (each CQUAD4 two triangles)";
    lines.push_back(t);
  }
  if (!mesh.point_masses.empty()) {
    double m = 0.0;
    for (const auto& pm : mesh.point_masses) m += pm.mass;
    char buf[128];
    std::snprintf(buf, sizeof buf, "masses: %zu concentrated, %.6g kg", mesh.point_masses.size(), m);
    lines.push_back(buf);
  }
  return lines;
}

// The node sets a body's input names (interfaces' patches, reference sets):
// physical groups used so need no region.
std::vector<std::string> namedSets(const BodySpec& spec) {
  std::vector<std::string> sets;
  for (const auto& i : spec.interfaces)
    if (i.coupling != Coupling::Node && (i.select == PatchSelect::Set || i.select == PatchSelect::Edge)) sets.push_back(i.edge);
  for (const auto& r : spec.reference) sets.push_back(r.set);
  return sets;
}

// " (modes 1, 2, 5)" for the reduction attribute when keep: chose them; empty
// when the basis keeps the lowest modes.
std::string keptText(const std::vector<long>& keep) {
  if (keep.empty()) return "";
  std::string t = " (modes";
  for (std::size_t j = 0; j < keep.size(); ++j) t += (j ? ", " : " ") + std::to_string(keep[j]);
  return t + ")";
}

}  // namespace

Mesh meshBody(Comm comm, const BodySpec& spec, bool quiet) {
  // A Nastran deck was read with the YAML, on every rank, properties and all.
  if (spec.general && spec.general->deck_mesh) return *spec.general->deck_mesh;
  const int rank = commRank(comm);
  Mesh mesh;
  std::string error;
  int out_of_memory = 0;
  if (rank == 0) {
    try {
      if (spec.beam) {
        std::vector<double> xs;
        for (const auto& i : spec.interfaces) xs.push_back(i.position.x());
        mesh = meshBeam(spec.beam->length, spec.beam->elements, xs);
      } else {
        // A rectangle, a .geo or a .msh through gmsh (gmsh_mesh.h; the program
        // fe-prep-mpi only, backend_choice.h).
        mesh = meshWithGmsh(spec, namedSets(spec), quiet);
      }
    } catch (const std::bad_alloc& e) {
      // Said as what it is on every rank, not as a mesh error (common/memory.h).
      const std::size_t asked = lastFailedAllocation();
      error = dynamic_cast<const OutOfMemory*>(&e) ? std::string(e.what())
              : asked ? "the mesh's allocation of " + formatMegabytes(static_cast<double>(asked) / 1048576.0) + " failed"
                      : std::string("the mesher's allocation failed");
      out_of_memory = 1;
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  broadcast(comm, &out_of_memory, 1);
  long len = static_cast<long>(error.size());
  broadcast(comm, &len, 1);
  error.resize(static_cast<std::size_t>(len));
  broadcast(comm, error.data(), static_cast<long>(len));
  if (!error.empty()) {
    if (out_of_memory) throw OutOfMemory(error);
    if (spec.general) spec.general->file_node.fail(error);
    if (spec.shell) spec.shell->mesh_node.fail("meshing failed: " + error);
    throw std::runtime_error("meshing failed: " + error);
  }
  broadcastMesh(comm, mesh);
  assignElementProperties(spec, mesh);
  return mesh;
}

Eigen::MatrixXd interfaceShapes(const Eigen::MatrixXd& node_shapes, long node, const Eigen::Vector3d& d) {
  const long nm = node_shapes.cols();
  Eigen::MatrixXd s(nm, 6);
  for (long j = 0; j < nm; ++j) {
    const Eigen::Vector3d u = node_shapes.block<3, 1>(6 * node, j);
    const Eigen::Vector3d th = node_shapes.block<3, 1>(6 * node + 3, j);
    s.block<1, 3>(j, 0) = (u + th.cross(d)).transpose();
    s.block<1, 3>(j, 3) = th.transpose();
  }
  return s;
}

double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

namespace {

// Everything buildFlexBody's stages hand to one another, in the order the
// stages fill it. One per build, never copied (the element kernel refers to it).
struct BuildState {
  BuildState(Comm c, const BodySpec& s, const BuildOptions& o) : comm(c), spec(s), options(o) {
    rank = commRank(comm);
    quiet = options.quiet || rank != 0;
  }
  BuildState(const BuildState&) = delete;
  BuildState& operator=(const BuildState&) = delete;

  Comm comm;
  const BodySpec& spec;
  const BuildOptions& options;
  int rank = 0;
  bool quiet = true;
  BuildResult res;
  Stopwatch sw;

  // 1. the mesh (or the imported model, whose mesh it is)
  std::optional<ImportedModel> imported;
  Mesh mesh;
  // The assembly's mesh: for an imported body its coupled node pairs are the "elements".
  const Mesh& assemblyMesh() const { return imported ? imported->pairs : mesh; }
  // Lumped and point masses are node-local: M gets its own pattern (an
  // imported M may couple nodes).
  bool nodalMass() const { return spec.lumped && !imported; }

  // 2. interfaces and reference conditions: on an interface's point (through its
  // node, its rigid patch's master, or its distributing patch), or on every node of a set
  std::vector<MeshInterface> interfaces;
  std::vector<PointCondition> conditions, rigid_conditions;
  std::vector<RigidCoupling> couplings;
  std::vector<PatchCondition> patch_conditions;
  DofMap map;
  Eigen::MatrixXd rigid;  // the rigid motions the reference leaves, reduced DOF

  // 3. assembly: each element with its own property and frame (mesh.h); point masses last
  long n_tri = 0, n_beam = 0, n_el = 0;
  ElementKernel kernel;
  AssembledSystem sys;
  Eigen::VectorXd mass_moved;  // the moment correction added to the translational masses (lumped_moments)

  // 4. static responses and eigenmodes
  bool inertia_relief = false, static_check = false;
  std::vector<Eigen::VectorXd> compliance;
  Eigen::MatrixXd loads, u;  // unit loads at every interface and the body's static responses (full DOF)
  Eigen::Vector2d compliance_scale = Eigen::Vector2d::Zero();
  ModalResult modal;
};

// ---- 1. mesh

void meshStage(BuildState& s) {
  s.sw.start();
  Progress pmesh("meshing", 1.0, s.quiet);
  pmesh.update(0.0);
  // An imported body (matrices:) reads its model instead of meshing (fe-prep/import/).
  if (s.spec.matrices) s.imported = importStage(s.comm, s.spec, s.quiet);
  s.mesh = s.imported ? s.imported->mesh : meshBody(s.comm, s.spec, s.quiet);
  const Mesh& mesh = s.mesh;
  std::ostringstream mdesc;
  if (s.imported) mdesc << "(" << mesh.nodeCount() << " nodes, " << s.imported->source_dofs << " imported DOF)";
  else {
    mdesc << "(" << mesh.nodeCount() << " nodes";
    if (!mesh.triangles.empty()) mdesc << ", " << mesh.triangles.size() << " triangles";
    if (!mesh.beams.empty()) mdesc << ", " << mesh.beams.size() << " beam elements";
    mdesc << ")";
  }
  pmesh.finish(mdesc.str());
  s.res.stages.push_back({"meshing", s.sw.seconds(), s.sw.cpu(), peakRssMb(), 0.0});
}

// ---- 2. interfaces and reference conditions

void resolveInterfaces(BuildState& s) {
  const BodySpec& spec = s.spec;
  FlexBody& body = s.res.body;
  body.name = spec.name;
  body.nodes = s.mesh.nodes;
  for (const auto& i : spec.interfaces) {
    Eigen::Vector3d projection = i.position;
    if (spec.beam) projection = Eigen::Vector3d(i.position.x(), 0, 0);
    else if (spec.shell && spec.shell->rectangle) projection = i.bracket ? Eigen::Vector3d(i.bracket->x(), i.bracket->y(), 0.0)
                                                                         : Eigen::Vector3d(i.position.x(), i.position.y(), 0.0);
    s.interfaces.push_back(resolveInterface(s.mesh, i, projection));
    if (s.imported) {
      const std::string note = checkImportedInterface(*s.imported, s.interfaces.back(), i);
      if (!note.empty() && !s.quiet && s.rank == 0) std::printf("  %s\n", note.c_str());
    }
    FlexInterface fi;
    fi.name = i.name;
    fi.node = s.interfaces.back().node;
    fi.position = i.position;
    body.interfaces.push_back(fi);
  }
}

void referenceStage(BuildState& s) {
  s.sw.start();
  resolveInterfaces(s);
  const BodySpec& spec = s.spec;
  const Mesh& mesh = s.mesh;
  const std::vector<MeshInterface>& mesh_interfaces = s.interfaces;
  std::map<std::string, bool> held_distributing;  // name -> clamp
  for (const auto& mi : mesh_interfaces)
    if (mi.coupling == Coupling::Rigid) {
      RigidCoupling rc{mi.node, {}};
      for (long k : mi.nodes)
        if (k != mi.node) rc.slaves.push_back(k);
      s.couplings.push_back(rc);
    }
  for (const auto& r : spec.reference) {
    auto it = std::find_if(mesh_interfaces.begin(), mesh_interfaces.end(),
                           [&](const MeshInterface& f) { return f.name == r.set; });
    if (it != mesh_interfaces.end()) {
      if (it->coupling == Coupling::Distributing) {
        held_distributing[it->name] = held_distributing[it->name] || r.clamp;
      } else {
        s.conditions.push_back({it->node, it->point, r.clamp});
        s.rigid_conditions.push_back(s.conditions.back());
      }
      continue;
    }
    auto set = mesh.sets.find(r.set);
    if (set == mesh.sets.end() || set->second.empty()) {
      std::vector<std::string> known;
      for (const auto& kv : mesh.sets) known.push_back(kv.first);
      for (const auto& f : s.res.body.interfaces) known.push_back(f.name);
      r.node.fail("the mesh has no node set or interface '" + r.set + "'" + didYouMean(r.set, known));
    }
    for (long n : set->second) {
      // A solid node's rotations are no DOF: clamping it is pinning it.
      s.conditions.push_back({n, mesh.nodes.row(n).transpose(), r.clamp && !(s.imported && s.imported->solid[static_cast<std::size_t>(n)])});
      s.rigid_conditions.push_back(s.conditions.back());
    }
  }
  for (const auto& [name, clamp] : held_distributing) {
    const MeshInterface& mi = *std::find_if(mesh_interfaces.begin(), mesh_interfaces.end(),
                                            [&](const MeshInterface& f) { return f.name == name; });
    s.patch_conditions.push_back({mi.nodes, clamp ? mi.W : Eigen::MatrixXd(mi.W.topRows(3))});
    s.rigid_conditions.push_back({-1, mi.point, clamp});
  }
  try {
    s.map = buildDofMap(mesh, s.conditions, s.couplings, s.patch_conditions, s.options.patch_hold);
    if (s.imported) holdSolidRotations(s.map, s.imported->solid);
  } catch (const std::invalid_argument& e) {
    const InputNode where = spec.reference.empty() ? spec.interfaces.front().node : spec.reference.front().node;
    where.fail(std::string("cannot apply the interfaces and reference conditions: ") + e.what());
  }
  const Eigen::MatrixXd rigid_full = admissibleRigidModes(mesh, s.rigid_conditions);
  s.rigid.resize(s.map.reduced, rigid_full.cols());
  for (long j = 0; j < rigid_full.cols(); ++j) s.rigid.col(j) = s.map.restrict(rigid_full.col(j));
  s.res.dofs = 6 * mesh.nodeCount();
  s.res.reduced_dofs = s.map.constrainedDofs();
  s.res.rigid_removed = s.rigid.cols();
}

// ---- 3. assembly

// The element kernel of the assembly (and of the Craig-Bampton lifts' K l_j):
// element e's matrices, its property and frame from the mesh.
void elementMatrices(const BuildState& s, long e, ElementResult& out) {
  const Mesh& mesh = s.mesh;
  const long n_tri = s.n_tri, n_beam = s.n_beam;
  if (s.imported) {
    s.imported->pairMatrices(e, out);
  } else if (e < n_tri) {
    const auto& t = mesh.triangles[static_cast<std::size_t>(e)];
    Eigen::Matrix3d xyz;
    for (int i = 0; i < 3; ++i) xyz.row(i) = mesh.nodes.row(t[static_cast<std::size_t>(i)]);
    const ShellProperty& p = mesh.shellProperty(e);
    const fe::ShellMatrices m =
        fe::shellTriangle(xyz, p.laminate, p.kind, mesh.triangle_axis[static_cast<std::size_t>(e)]);
    out.nodes.assign(t.begin(), t.end());
    out.K = m.K;
    out.M = s.spec.lumped ? Eigen::MatrixXd(m.lumped.asDiagonal()) : Eigen::MatrixXd(m.M);
    out.lumped = m.lumped;
  } else if (e < n_tri + n_beam) {
    const long k = e - n_tri;
    const auto& b = mesh.beams[static_cast<std::size_t>(k)];
    const BeamProperty& p = mesh.beamProperty(k);
    const fe::BeamMatrices m = fe::timoshenkoBeam(mesh.nodes.row(b[0]).transpose(), mesh.nodes.row(b[1]).transpose(),
                                                  mesh.beam_x2[static_cast<std::size_t>(k)], p.Ks, p.Ms);
    out.nodes.assign(b.begin(), b.end());
    out.K = m.K;
    out.M = s.spec.lumped ? Eigen::MatrixXd(m.lumped.asDiagonal()) : Eigen::MatrixXd(m.M);
    out.lumped = m.lumped;
  } else {
    // A concentrated mass at its node: m on the translations, its inertia
    // tensor (about the node) on the rotations, in full in both mass kinds;
    // the lumped diagonal keeps the inertia's diagonal (/mass/nodal).
    const PointMass& pm = mesh.point_masses[static_cast<std::size_t>(e - n_tri - n_beam)];
    out.nodes = {pm.node};
    out.K = Eigen::MatrixXd::Zero(6, 6);
    out.M = Eigen::MatrixXd::Zero(6, 6);
    out.M.topLeftCorner(3, 3).diagonal().setConstant(pm.mass);
    out.M.bottomRightCorner(3, 3) = pm.inertia;
    out.lumped = out.M.diagonal();
  }
}

// mass: lumped_moments: row-sum nodal masses moved to reproduce the exact
// second moments (mass_lumping.h), in the eigenproblem and in /mass/nodal;
// mass: consistent: in /mass/nodal only (the invariants), M stays consistent.
void lumpNodalMasses(BuildState& s) {
  const Mesh& mesh = s.mesh;
  AssembledSystem& sys = s.sys;
  BuildResult& res = s.res;
  if (s.imported) {
    // The imported M stays as given in the eigenproblem; the nodal masses of
    // /mass/nodal are fitted to its rigid-body projection (imported_body.h).
    const ImportedLumping il = importedLumping(s.comm, *s.imported, s.quiet);
    res.moment_lumping = il.applied;
    res.lumping_min_ratio = il.min_ratio;
    for (long k = 0; k < mesh.nodeCount(); ++k) {
      sys.lumped.segment<3>(6 * k).setConstant(il.nodal(k, 0));
      sys.lumped.segment<3>(6 * k + 3) = il.nodal.block<1, 3>(k, 1).transpose();
    }
  } else if (s.spec.moment_lumping) {
    const long n = mesh.nodeCount();
    Eigen::VectorXd m0(n);
    for (long k = 0; k < n; ++k) m0(k) = sys.lumped(6 * k);
    // Through-thickness and section terms belong to the rotary inertias.
    const RigidProperties mid = meshProperties(mesh, true);
    const MomentLumping ml = momentConsistentMasses(mesh.nodes, m0, mid.mass, mid.first_moment, mid.second_moment);
    res.moment_lumping = ml.applied;
    if (!ml.applied && s.rank == 0)
      std::fprintf(stderr, "fe-prep: warning: mass: lumped_moments not applied (a nodal mass would fall to %.2f of its row-sum value); row-sum lumped masses kept\n", ml.min_ratio);
    res.lumping_min_ratio = ml.min_ratio;
    if (ml.applied) {
      const Eigen::VectorXd dm = ml.masses - m0;
      if (s.spec.lumped) addNodalTranslationalMass(s.comm, mesh, s.map, dm, sys.M);
      if (s.spec.lumped) s.mass_moved = dm;
      for (long k = 0; k < n; ++k) sys.lumped.segment<3>(6 * k).array() += dm(k);
    }
  }
}

void assemblyStage(BuildState& s) {
  const Mesh& amesh = s.assemblyMesh();
  s.n_tri = static_cast<long>(amesh.triangles.size());
  s.n_beam = static_cast<long>(amesh.beams.size());
  s.n_el = s.n_tri + s.n_beam + (s.imported ? 0L : static_cast<long>(s.mesh.point_masses.size()));
  s.kernel = [&s](long e, ElementResult& out) { elementMatrices(s, e, out); };
  Progress pasm("assembly", 1.0, s.quiet);
  // Lumped and point masses are node-local: M gets its own, smaller pattern.
  assemble(s.comm, amesh, s.map, s.n_el, s.kernel, s.sys, [&](double f) { pasm.update(f); }, s.nodalMass());
  lumpNodalMasses(s);
  pasm.finish("(" + std::to_string(s.map.constrainedDofs()) + " DOF)");
  s.res.stages.push_back({"assembly", s.sw.seconds(), s.sw.cpu(), peakRssMb(), 0.0});
}

// ---- 4. static responses, eigen-solve and keep:

// Static deflection of every interface under unit loads (static_response.h):
// the yardstick of the modes' truncation. Where the reference holds the body,
// always; where rigid motions are left free, with inertia relief (the
// deflection relative to the rigid motion, the sum over every elastic mode)
// and only when a static_error or static_correction asks for it.
void staticResponses(BuildState& s) {
  const BodySpec& spec = s.spec;
  const Mesh& mesh = s.mesh;
  const std::vector<MeshInterface>& mesh_interfaces = s.interfaces;
  s.inertia_relief = s.rigid.cols() > 0 && (spec.static_error > 0 || spec.static_correction);
  s.static_check = !spec.craig_bampton && !mesh_interfaces.empty() && (s.rigid.cols() == 0 || s.inertia_relief);
  if (s.static_check) {
    s.loads.resize(6 * mesh.nodeCount(), 6 * static_cast<long>(mesh_interfaces.size()));
    for (std::size_t k = 0; k < mesh_interfaces.size(); ++k)
      s.loads.middleCols(6 * static_cast<long>(k), 6) = interfaceLoads(mesh_interfaces[k], mesh);
    s.u = s.inertia_relief ? solveInertiaRelief(s.comm, s.sys.K, s.sys.M, s.map, s.rigid, s.loads)
                           : solveStatic(s.comm, s.sys.K, s.map, s.loads);
    for (std::size_t k = 0; k < mesh_interfaces.size(); ++k)
      s.compliance.push_back(referencePointShapes(mesh_interfaces[k], mesh, s.u.middleCols(6 * static_cast<long>(k), 6)).diagonal());
  } else if (spec.static_error > 0) {
    spec.modes_node.fail("modes: {static_error: ...} needs interfaces: the unit loads act there");
  }
  for (const auto& c : s.compliance)
    s.compliance_scale = s.compliance_scale.cwiseMax(Eigen::Vector2d(c.head<3>().maxCoeff(), c.tail<3>().maxCoeff()));
}

// How much of each interface's static response the modes `m` miss.
std::vector<StaticTruncation> truncations(const BuildState& s, const ModalResult& m) {
  std::vector<StaticTruncation> t;
  for (std::size_t k = 0; k < s.interfaces.size(); ++k) {
    Eigen::MatrixXd full(6 * s.mesh.nodeCount(), m.eigenvalues.size());
    for (long j = 0; j < m.eigenvalues.size(); ++j) full.col(j) = s.map.expand(m.vectors.col(j));
    t.push_back(staticTruncation(s.compliance[k], referencePointShapes(s.interfaces[k], s.mesh, full), m.eigenvalues,
                                 s.compliance_scale));
  }
  return t;
}

// The modes asked (modes: N, keep: [...], or static_error: e, which doubles the
// count until every interface's static response is met).
void solveEigenmodes(BuildState& s, Progress& peig, const std::string& factorisation) {
  const BodySpec& spec = s.spec;
  // More modes than the held body has degrees of freedom that carry mass
  // cannot be had (a massless DOF, a shell's drilling rotation, is an infinite
  // eigenvalue): refuse them here rather than let the eigen-solver search for
  // what does not exist.
  const long massless = masslessDofs(s.sys.M);
  const long flexible = s.map.constrainedDofs() + s.map.multipliers - massless - s.rigid.cols();
  // keep: [...] solves up to the highest mode number asked.
  const long solved = spec.keep_modes.empty() ? spec.modes : spec.keep_modes.back();
  if (solved > flexible)
    spec.modes_node.fail("asked for " + (spec.keep_modes.empty() ? std::to_string(spec.modes) + " modes" : "mode " + std::to_string(solved)) + " but the meshed body has only " +
                         std::to_string(flexible) + " flexible degrees of freedom that carry mass (" +
                         std::to_string(massless) + " more carry none: the shells' drilling rotations); ask for "
                         "fewer modes or refine the mesh");
  ModalRequest req;
  req.modes = spec.static_error > 0 ? 8 : solved;
  req.max_frequency_hz = spec.max_frequency_hz;
  req.tolerance = s.options.tolerance;
  req.multipliers = s.map.multipliers;
  req.keep_factor = spec.craig_bampton;
  // Deflation is kept where it was shown to give the undeflated body to the
  // solver's tolerance: shell meshes (docs/fe-prep.md, the rigid motions
  // deflated). A free Timoshenko beam's elastic pairs came out up to 2e-9
  // apart with and without it, whatever the tolerance: beams, mixed bodies
  // and imported matrices are solved undeflated, as before.
  req.deflate_rigid = s.options.deflate_rigid && s.assemblyMesh().beams.empty() && !s.imported;
  ModalResult& modal = s.modal;
  for (;;) {
    bool solver_limit = false;  // static_error: a doubled count the eigen-solver could not deliver
    try {
      modal = solveModes(s.comm, s.sys.K, s.sys.M, s.rigid, req, [&](long c, long w) {
        peig.update(static_cast<double>(c) / static_cast<double>(std::max<long>(w, 1)), std::to_string(c) + "/" + std::to_string(w) + " modes" + (factorisation.empty() ? "" : "; " + factorisation));
      });
    } catch (const ModeCountError& e) {
      if (spec.static_error <= 0 || modal.eigenvalues.size() == 0) spec.modes_node.fail(e.what());
      if (s.rank == 0)
        std::fprintf(stderr, "fe-prep: warning: modes: {static_error}: %s; keeping the %ld modes found before\n", e.what(),
                     static_cast<long>(modal.eigenvalues.size()));
      solver_limit = true;  // `modal` still holds the previous, smaller set
    }
    if (spec.static_error <= 0) break;
    // modes: {static_error: e}: the fewest leading modes that miss at most e at
    // every interface in every loaded direction; double the count until met.
    const std::vector<StaticTruncation> t = truncations(s, modal);
    double worst = 0.0;
    const long n = modesForStaticError(t, spec.static_error, &worst);
    // At most 512 modes: a load the modes cannot carry statically (an in-plane
    // force on a panel, whose membrane modes lie far up) is reported, not chased.
    const long available = std::min<long>(flexible, 512);
    if (worst <= spec.static_error || req.modes >= available || solver_limit) {
      if (worst > spec.static_error && s.rank == 0)
        std::fprintf(stderr, "fe-prep: warning: modes: {static_error: %g} not reached with %ld modes (%.3g missed); "
                     "the summary and /interfaces/*/static_error say where\n", spec.static_error, n, worst);
      modal.eigenvalues.conservativeResize(n);
      modal.vectors.conservativeResize(Eigen::NoChange, n);
      break;
    }
    req.modes = std::min<long>(2 * req.modes, available);
  }
}

// The eigenmodes the basis keeps: all that were solved, or those asked by
// number (keep: [...]); recorded in /reduction/ (docs/body-file.md).
void keepModes(BuildState& s) {
  const BodySpec& spec = s.spec;
  ModalResult& modal = s.modal;
  std::vector<long> kept(static_cast<std::size_t>(modal.eigenvalues.size()));
  for (std::size_t j = 0; j < kept.size(); ++j) kept[j] = static_cast<long>(j) + 1;
  if (!spec.keep_modes.empty()) {
    const long solved = spec.keep_modes.back();
    if (modal.eigenvalues.size() < solved)
      spec.modes_node.fail("mode " + std::to_string(solved) + " asked but the eigen-solver found " +
                           std::to_string(modal.eigenvalues.size()));
    kept = spec.keep_modes;
    // In place: the numbers ascend, so mode kept[j] - 1 >= j is read before
    // any later column overwrites it.
    for (std::size_t j = 0; j < kept.size(); ++j) {
      modal.eigenvalues(static_cast<long>(j)) = modal.eigenvalues(kept[j] - 1);
      modal.vectors.col(static_cast<long>(j)) = modal.vectors.col(kept[j] - 1);
    }
    modal.eigenvalues.conservativeResize(static_cast<long>(kept.size()));
    modal.vectors.conservativeResize(Eigen::NoChange, static_cast<long>(kept.size()));
  }
  s.res.body.kept_modes = kept;
  s.res.body.kept_eigenvalues = modal.eigenvalues;
}

void eigenStage(BuildState& s) {
  s.sw.start();
  Progress peig("eigen-solve", 1.0, s.quiet);
  // MUMPS's estimate of the factorisation of K (static responses, eigen-solve),
  // before the first one starts; refused when over what is left.
  const std::string factorisation = checkFactorisationMemory(s.sys.K, "the stiffness");
  if (!factorisation.empty()) peig.update(0.0, factorisation);
  staticResponses(s);
  solveEigenmodes(s, peig, factorisation);
  keepModes(s);
  const ModalResult& modal = s.modal;
  char null_residual[64];
  std::snprintf(null_residual, sizeof null_residual, ", ||K r|| / ||K|| ||r|| %.1e", modal.rigid_null_residual);
  peig.finish("(" + std::to_string(modal.eigenvalues.size()) + " modes, " + std::to_string(s.rigid.cols()) +
              (modal.deflated ? " rigid deflated" + std::string(null_residual) : " rigid removed") + ")");
  s.res.stages.push_back({"eigensolve", s.sw.seconds(), s.sw.cpu(), peakRssMb(), modal.factorisation.used_max_rank_mib});
  s.res.stages.back().factor_library = modal.factorisation.library;
  s.res.rigid_eigenvalues = modal.rigid_eigenvalues;
  s.res.rigid_share_removed_min = modal.rigid_projection_min;
  s.res.rigid_share_kept_max = modal.rigid_projection_max;
  s.res.rigid_deflated = modal.deflated;
  s.res.rigid_null_residual = modal.rigid_null_residual;
}

// ---- 5. the basis: Craig-Bampton, static correction, or the modes alone

// Boundary DOF: every reference condition's rows; lifts that give each a
// unit value (rigid patches carry their master's lift to the slaves).
std::vector<Lift> boundaryLifts(const BuildState& s) {
  const Mesh& mesh = s.mesh;
  std::map<long, Eigen::MatrixXd> node_rows;
  for (const auto& c : s.conditions) {
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(c.clamp ? 6 : 3, 6);
    C.leftCols(3).topRows(3).setIdentity();
    C.topRightCorner(3, 3) = -skew(c.point - mesh.nodes.row(c.node).transpose());
    if (c.clamp) C.bottomRightCorner(3, 3).setIdentity();
    auto it = node_rows.find(c.node);
    if (it == node_rows.end()) {
      node_rows.emplace(c.node, C);
    } else {
      Eigen::MatrixXd S(it->second.rows() + C.rows(), 6);
      S << it->second, C;
      it->second = S;
    }
  }
  std::vector<Lift> lifts;
  for (const auto& [node, C] : node_rows) {
    const std::size_t first = lifts.size();
    appendLifts({node}, C, lifts);
    for (const auto& rc : s.couplings) {
      if (rc.master != node) continue;
      for (std::size_t j = first; j < lifts.size(); ++j)
        for (long sl : rc.slaves)
          lifts[j][sl] = rigidTransfer((mesh.nodes.row(sl) - mesh.nodes.row(node)).transpose()) * lifts[j][node];
    }
  }
  for (const auto& pc : s.patch_conditions) appendLifts(pc.nodes, pc.C, lifts);
  return lifts;
}

// K l_j from the element kernel of the assembly, over the elements that touch
// the lifts (every rank, the mesh is whole); point masses carry no stiffness.
NodeRows liftStiffness(const BuildState& s, const NodeRows& lifts, long n_boundary) {
  const Mesh& amesh = s.assemblyMesh();
  const long n_tri = s.n_tri, n_beam = s.n_beam;
  NodeRows K_lifts;
  std::vector<char> support(static_cast<std::size_t>(s.mesh.nodeCount()), 0);
  for (const auto& [node, rows] : lifts) support[static_cast<std::size_t>(node)] = rows.cwiseAbs().maxCoeff() > 0.0;
  ElementResult er;
  for (long e = 0; e < s.n_el; ++e) {
    if (e >= n_tri + n_beam) break;  // point masses: no stiffness
    const bool touches = e < n_tri ? std::any_of(amesh.triangles[static_cast<std::size_t>(e)].begin(), amesh.triangles[static_cast<std::size_t>(e)].end(), [&](long k) { return support[static_cast<std::size_t>(k)] != 0; })
                                   : std::any_of(amesh.beams[static_cast<std::size_t>(e - n_tri)].begin(), amesh.beams[static_cast<std::size_t>(e - n_tri)].end(), [&](long k) { return support[static_cast<std::size_t>(k)] != 0; });
    if (!touches) continue;
    s.kernel(e, er);
    const long a = static_cast<long>(er.nodes.size());
    Eigen::MatrixXd Le = Eigen::MatrixXd::Zero(6 * a, n_boundary);
    for (long i = 0; i < a; ++i) {
      const auto it = lifts.find(er.nodes[static_cast<std::size_t>(i)]);
      if (it != lifts.end()) Le.middleRows(6 * i, 6) = it->second;
    }
    const Eigen::MatrixXd KLe = er.K * Le;
    for (long i = 0; i < a; ++i) {
      auto it = K_lifts.find(er.nodes[static_cast<std::size_t>(i)]);
      if (it == K_lifts.end())
        it = K_lifts.emplace(er.nodes[static_cast<std::size_t>(i)], Eigen::MatrixXd::Zero(6, n_boundary)).first;
      it->second += KLe.middleRows(6 * i, 6);
    }
  }
  return K_lifts;
}

void craigBamptonStage(BuildState& s) {
  BuildResult& res = s.res;
  FlexBody& body = res.body;
  ConstraintModeInput cb;
  {
    std::vector<Lift> lifts = boundaryLifts(s);
    cb.n_nodes = s.mesh.nodeCount();
    cb.n_boundary = static_cast<long>(lifts.size());
    cb.lifts = liftRows(lifts);
  }
  cb.K_lifts = liftStiffness(s, cb.lifts, cb.n_boundary);
  cb.K_fixed = s.sys.K;
  cb.fixed = &s.map;
  cb.normal = &s.modal.vectors;
  Stopwatch swr;
  swr.start();
  // The fixed-interface eigen-solve factorised this same K (shift 0): its
  // factor serves the constraint modes, and is released after them.
  cb.factored = s.modal.factor_of_K;
  CraigBamptonBasis basis = constraintModes(s.comm, cb);
  if (cb.factored) basis.factorisation = s.modal.factorisation;
  s.modal.factor_of_K = FactorHandle();
  res.stages.push_back({"constraints", swr.seconds(), swr.cpu(), peakRssMb(), basis.factorisation.used_max_rank_mib});
  res.stages.back().factor_library = basis.factorisation.library;
  swr.start();
  res.constraint_modes = cb.n_boundary;
  // The free body (its couplings only) for the reduced K and M, after the
  // constraint modes' factorisation is freed: the two never coexist. Where
  // the reference held only distributing patches (by multipliers), the held
  // system's nodal block is that body already; else it is assembled.
  DofMap free_map = buildDofMap(s.mesh, {}, s.couplings, {});
  if (s.imported) holdSolidRotations(free_map, s.imported->solid);
  AssembledSystem free_sys;
  if (!freeBlockOf(s.sys, s.map, free_map, free_sys)) {
    assemble(s.comm, s.assemblyMesh(), free_map, s.n_el, s.kernel, free_sys, {}, s.nodalMass());
    if (s.mass_moved.size()) addNodalTranslationalMass(s.comm, s.mesh, free_map, s.mass_moved, free_sys.M);
  }
  CraigBamptonResult cbr =
      craigBampton(s.comm, std::move(basis), free_sys.K, free_sys.M, free_map, admissibleRigidModes(s.mesh, {}));
  res.stages.push_back({"reduction", swr.seconds(), swr.cpu(), peakRssMb(), 0.0});
  body.eigenvalues = cbr.eigenvalues;
  body.shapes = std::move(cbr.shapes);
  body.fixed_interface_coordinates = cbr.fixed_interface_coordinates;
  res.normal_modes = s.modal.eigenvalues.size();
  res.rigid_removed = cbr.rigid_eigenvalues.size();
  res.rigid_eigenvalues = cbr.rigid_eigenvalues;
  res.rigid_share_removed_min = cbr.rigid_share_removed_min;
  res.rigid_share_kept_max = cbr.rigid_share_kept_max;
  body.reduction = "craig_bampton: " + std::to_string(res.constraint_modes) + " constraint modes + " +
                   std::to_string(res.normal_modes) + " fixed-interface modes" + keptText(s.spec.keep_modes) + " - " +
                   std::to_string(res.rigid_removed) + " rigid" +
                   (cbr.massless_condensed ? " - " + std::to_string(cbr.massless_condensed) + " massless" : "") +
                   " = " + std::to_string(cbr.eigenvalues.size()) + " shapes";
}

// Residual-flexibility correction (residual_flexibility.h): the static
// responses to unit loads at the chosen interfaces, less what the modes
// hold, join the modes; the whole is re-diagonalised.
void staticCorrectionStage(BuildState& s) {
  const BodySpec& spec = s.spec;
  const DofMap& map = s.map;
  const ModalResult& modal = s.modal;
  FlexBody& body = s.res.body;
  std::vector<long> cols;
  for (std::size_t k = 0; k < s.interfaces.size(); ++k) {
    const auto& only = spec.static_correction_interfaces;
    if (!only.empty() && std::find(only.begin(), only.end(), s.interfaces[k].name) == only.end()) continue;
    // Directions the reference holds (a clamped point, a pinned point's
    // translations) have no static response: nothing to add.
    for (long d = 0; d < 6; ++d)
      if (s.compliance[k](d) > 1e-9 * s.compliance_scale(d / 3)) cols.push_back(6 * static_cast<long>(k) + d);
  }
  const long m = static_cast<long>(cols.size()), r = map.reduced, nm = modal.eigenvalues.size();
  Eigen::MatrixXd A(r, m), MA(r, m), KR(r, m), MR(r, m);
  Eigen::VectorXd KA_diag(m);
  for (long j = 0; j < m; ++j) {
    A.col(j) = map.restrict(s.u.col(cols[static_cast<std::size_t>(j)]));
    MA.col(j) = multiply(s.sys.M, A.col(j));
    KA_diag(j) = A.col(j).dot(reduceForce(map, s.loads.col(cols[static_cast<std::size_t>(j)])));  // A^T K A = A^T F
  }
  const Eigen::MatrixXd R = residualVectors(modal.vectors, A, MA);
  for (long j = 0; j < m; ++j) {
    KR.col(j) = multiply(s.sys.K, R.col(j));
    MR.col(j) = multiply(s.sys.M, R.col(j));
  }
  const AugmentedBasis ab = augmentBasis(modal.vectors, modal.eigenvalues, R, KR, MR, KA_diag);
  Eigen::MatrixXd Bred(r, nm + m);
  Bred << modal.vectors, R;
  body.eigenvalues = ab.eigenvalues;
  body.shapes.resize(6 * s.mesh.nodeCount(), ab.eigenvalues.size());
  for (long j = 0; j < ab.eigenvalues.size(); ++j) {
    Eigen::VectorXd x = map.expand(Bred * ab.coefficients.col(j));
    Eigen::Index imax;
    x.cwiseAbs().maxCoeff(&imax);
    if (x(imax) < 0) x = -x;  // the modal solver's sign convention
    body.shapes.col(j) = x;
  }
  s.res.attachment_modes = m - ab.in_span - ab.dependent - ab.massless;
  body.reduction = std::string("free + static correction") + (s.inertia_relief ? " with inertia relief" : "") + ": " +
                   std::to_string(nm) + " modes" + keptText(spec.keep_modes) + " + " + std::to_string(m) +
                   " unit loads - " + std::to_string(ab.in_span + ab.dependent) + " in the span" +
                   (ab.massless ? " - " + std::to_string(ab.massless) + " massless" : "") + " = " +
                   std::to_string(ab.eigenvalues.size()) + " shapes";
}

void modesAloneStage(BuildState& s) {
  FlexBody& body = s.res.body;
  const ModalResult& modal = s.modal;
  body.eigenvalues = modal.eigenvalues;
  body.shapes.resize(6 * s.mesh.nodeCount(), modal.eigenvalues.size());
  for (long j = 0; j < modal.eigenvalues.size(); ++j) body.shapes.col(j) = s.map.expand(modal.vectors.col(j));
  body.reduction = "free: " + std::to_string(modal.eigenvalues.size()) + " shapes" + keptText(s.spec.keep_modes);
}

// ---- 6. geometric stiffness

void geometricStiffnessStage(BuildState& s) {
  const BodySpec& spec = s.spec;
  const Mesh& mesh = s.mesh;
  FlexBody& body = s.res.body;
  // The stress of the inertial loads is the static response of the held body.
  if (s.rigid.cols() > 0)
    spec.geometric_stiffness_node.fail("geometric stiffness needs a reference that holds every rigid motion of the body (clamp an interface or end)");
  // The geometric stiffness kernels take one section: bodies of one shell
  // property with one reference axis, or of one beam section with one x2.
  auto uniform = [](const std::vector<Eigen::Vector3d>& v) {
    return std::all_of(v.begin(), v.end(), [&](const Eigen::Vector3d& a) { return a == v.front(); });
  };
  if (mesh.shell_properties.size() + mesh.beam_properties.size() != 1 || !uniform(mesh.triangle_axis) ||
      !uniform(mesh.beam_x2) || !mesh.point_masses.empty())
    spec.geometric_stiffness_node.fail("geometric stiffness is computed for bodies of one shell or one beam "
                                       "property with one material axis and no point masses; this body has " +
                                       std::to_string(mesh.shell_properties.size() + mesh.beam_properties.size()) +
                                       " properties");
  StressStiffnessModel model;
  if (!mesh.beam_properties.empty()) model.Ks = &mesh.beam_properties.front().Ks;
  if (!mesh.beam_x2.empty()) model.section_x2 = mesh.beam_x2.front();
  if (!mesh.shell_properties.empty()) {
    model.laminate = &mesh.shell_properties.front().laminate;
    model.kind = mesh.shell_properties.front().kind;
    if (!mesh.triangle_axis.empty()) model.material_x = mesh.triangle_axis.front();
  }
  body.geometric_stiffness = modalGeometricStiffness(s.comm, mesh, s.map, s.sys.K, s.sys.lumped, model, body.shapes);
  // Loads applied at the interfaces (joint reactions, force elements); an
  // interface the reference holds passes its loads straight to the support.
  for (std::size_t k = 0; k < s.interfaces.size(); ++k) {
    const bool held = std::any_of(spec.reference.begin(), spec.reference.end(),
                                  [&](const auto& r) { return r.set == s.interfaces[k].name; });
    if (!held)
      // The unit-load responses of the static check are these cases' static
      // solutions (the same loads, interfaceLoads): reused, not solved again.
      body.interfaces[k].geometric_stiffness =
          s.static_check ? responseGeometricStiffness(mesh, s.u.middleCols(6 * static_cast<long>(k), 6), model, body.shapes)
                         : interfaceGeometricStiffness(s.comm, mesh, s.map, s.sys.K, interfaceLoads(s.interfaces[k], mesh),
                                                       model, body.shapes);
  }
}

// ---- 7. the interfaces' shapes and how much of their static response the basis holds

void interfaceStage(BuildState& s) {
  FlexBody& body = s.res.body;
  for (std::size_t k = 0; k < body.interfaces.size(); ++k) {
    body.interfaces[k].shapes = referencePointShapes(s.interfaces[k], s.mesh, body.shapes);
    if (s.static_check) {
      const StaticTruncation t =
          staticTruncation(s.compliance[k], body.interfaces[k].shapes, body.eigenvalues, s.compliance_scale);
      body.interfaces[k].static_compliance = t.compliance;
      body.interfaces[k].static_participation = t.participation;
      body.interfaces[k].static_error = t.error;
    }
  }
}

// ---- 8. elements, nodal masses, stress recovery, inertia

void finishStage(BuildState& s) {
  const Mesh& mesh = s.mesh;
  FlexBody& body = s.res.body;
  IndexMatrix conn;
  if (s.n_tri > 0) {
    conn.resize(s.n_tri, 3);
    for (long e = 0; e < s.n_tri; ++e)
      for (int k = 0; k < 3; ++k) conn(e, k) = mesh.triangles[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
    body.elements["triangles"] = conn;
  }
  if (!mesh.beams.empty()) {
    conn.resize(static_cast<long>(mesh.beams.size()), 2);
    for (long e = 0; e < conn.rows(); ++e)
      for (int k = 0; k < 2; ++k) conn(e, k) = mesh.beams[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
    body.elements["beams"] = conn;
  }
  body.nodal_mass.resize(mesh.nodeCount(), 4);
  for (long i = 0; i < mesh.nodeCount(); ++i) {
    // The three translational lumped entries are equal by construction; their mean is the nodal mass.
    body.nodal_mass(i, 0) = s.sys.lumped.segment<3>(6 * i).mean();
    body.nodal_mass.block<1, 3>(i, 1) = s.sys.lumped.segment<3>(6 * i + 3).transpose();
  }
  std::string stress_note;
  if (!s.imported) body.stress = stressRecoveryData(mesh, s.spec, body.shapes, stress_note);
  if (!stress_note.empty() && s.rank == 0) std::fprintf(stderr, "fe-prep: note: %s\n", stress_note.c_str());
  const RigidProperties rp = s.imported ? importedRigidProperties(*s.imported) : meshProperties(mesh, false);
  if (s.spec.general) {
    s.res.regions = regionSummary(s.spec, mesh);
    body.regions = regionRecords(mesh, s.res.regions);
  }
  // /inertia/ is the simulated body: what the invariants of the nodal masses imply.
  // The exact continuum values go beside it when they differ (row-sum lumping,
  // a moment correction that could not be applied, an asymmetric laminate whose
  // mass-stiffness coupling the nodal masses cannot carry).
  setRigidPropertiesFromLumpedMasses(body);
  body.exact_mass = rp.mass;
  body.exact_center_of_mass = rp.centerOfMass();
  body.exact_inertia_tensor = rp.inertiaAboutOrigin();
  const double size = std::max(mesh.characteristicLength(), 1e-12);
  body.has_exact_inertia =
      std::abs(body.mass - rp.mass) > 1e-12 * rp.mass ||
      (body.center_of_mass - body.exact_center_of_mass).norm() > 1e-12 * size ||
      (body.inertia_tensor - body.exact_inertia_tensor).cwiseAbs().maxCoeff() >
          1e-12 * body.exact_inertia_tensor.cwiseAbs().maxCoeff();
}

}  // namespace

// The build as its stages over one BuildState; each stage's work is in its function above.
BuildResult buildFlexBody(Comm comm, const BodySpec& spec, const BuildOptions& options) {
  BuildState s(comm, spec, options);
  // 1. The mesh: generated from the spec, read from a mesh file or deck, or imported with its matrices.
  meshStage(s);
  // 2. Interfaces (their nodes and patches) and reference conditions: the DOF map T, the rigid motions left.
  referenceStage(s);
  // 3. K and M assembled over the element kernel; the nodal masses of /mass/nodal.
  assemblyStage(s);
  // 4. The interfaces' static responses, the eigen-solve (static_error's doubling) and keep:.
  eigenStage(s);
  // 5. The basis: Craig-Bampton's constraint and fixed-interface modes, the modes with a static
  //    correction, or the modes alone.
  if (spec.craig_bampton) craigBamptonStage(s);
  else if (spec.static_correction) staticCorrectionStage(s);
  else modesAloneStage(s);
  s.res.body.frequencies_hz = s.res.body.eigenvalues.cwiseMax(0.0).cwiseSqrt() / (2 * M_PI);
  // 6. The geometric stiffness of the inertial and interface loads.
  if (spec.geometric_stiffness) geometricStiffnessStage(s);
  // 7. The interfaces' shapes and their static truncation.
  interfaceStage(s);
  // 8. Elements, nodal masses, stress recovery data, inertia.
  finishStage(s);
  return std::move(s.res);
}

}  // namespace fc::feprep
