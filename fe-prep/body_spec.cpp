#include "fe-prep/body_spec.h"

#include <algorithm>
#include <set>

#include "common/files.h"
#include "common/flexbody.h"
#include "common/h5error.h"
#include "common/materials.h"
#include "common/units.h"
#include "fe-prep/io/file_io.h"
#include "fe-prep/mesh_files/nastran.h"

namespace fc::feprep {
namespace {

// Lengths in SI units (InputNode::asLength: beyond these a value is a unit mistake).
// A 1e6 m beam was accepted and failed only when its inertia was checked on write,
// an error naming the body but no key (fuzz campaign, session 6). Sections as in
// section-prep (1 um .. 100 m); bodies up to 10 km.
constexpr double kMinLength = 1e-6;
constexpr double kMaxSectionLength = 100.0;
constexpr double kMaxBodyLength = 1e4;

const char* const kEdges[] = {"edge_xmin", "edge_xmax", "edge_ymin", "edge_ymax"};
const char* const kEnds[] = {"end_min", "end_max"};

// The material of an inline beam section: closed forms need an isotropic solid.
const Material& isotropicMaterial(const MaterialLibrary& lib, const InputNode& node) {
  const Material& m = lookupMaterial(lib, node);
  if (m.kind != Material::Kind::Isotropic)
    node.fail("inline beam sections need an isotropic material; '" + m.name +
              "' is not (give a section-prep file instead: section: {file: SECTION.h5})");
  return m;
}

// The section of a shell (shell: or a shell region): laminate, or material +
// thickness; element kind; shear correction. The caller checks the keys.
ShellProperty parseShellSection(const InputNode& s, const MaterialLibrary& materials, const LaminateLibrary& laminates) {
  ShellProperty p;
  // Given, a factor on the summed ply shear stiffness; else As from the stacking.
  std::optional<double> kappa;
  if (s.has("shear_correction")) kappa = s["shear_correction"].asPositive();
  if (s.has("laminate")) {
    if (s.has("material") || s.has("thickness"))
      s["laminate"].fail("give either laminate: NAME or material: and thickness:, not both");
    const InputNode ln = s["laminate"];
    const std::string name = ln.asString();
    auto it = laminates.find(name);
    if (it == laminates.end()) {
      std::vector<std::string> names;
      for (const auto& kv : laminates) names.push_back(kv.first);
      ln.fail("unknown laminate '" + name + "'" + didYouMean(name, names) +
              "; expected a name from the laminates: block");
    }
    p.laminate = laminateStiffness(it->second, materials, kappa);
    p.laminate_name = name;
    p.plies = plyTable(it->second, materials);
  } else if (s.has("material")) {
    const Material& m = lookupMaterial(materials, s["material"]);
    const double t = s["thickness"].asLength(1e-7, 1.0);  // as a ply (common/laminate.cpp)
    p.laminate = laminateStiffness(homogeneousLaminate(m.name, t), materials, kappa);
    p.laminate_name = m.name;
    p.plies = plyTable(homogeneousLaminate(m.name, t), materials);
  } else {
    s.fail("missing the shell's section: expected laminate: NAME, or material: NAME with thickness: T");
  }

  const std::string el = s.string("element", "dst");
  if (el == "dst") p.kind = fe::ShellKind::DST;
  else if (el == "dkt") p.kind = fe::ShellKind::DKT;
  else s["element"].fail("unknown element '" + el + "', expected dst or dkt");
  return p;
}

ShellSpec parseShell(const InputNode& s, const MaterialLibrary& materials, const LaminateLibrary& laminates,
                     BodySpec& body) {
  s.allowKeys({"rectangle", "laminate", "material", "thickness", "element", "mesh", "shear_correction"});
  ShellSpec shell;
  {
    const ShellProperty p = parseShellSection(s, materials, laminates);
    shell.laminate = p.laminate;
    shell.laminate_name = p.laminate_name;
    shell.plies = p.plies;
    shell.kind = p.kind;
  }

  const InputNode mesh = s["mesh"];
  shell.mesh_node = mesh;
  mesh.allowKeys({"triangles", "size", "file", "max_triangles", "graded_from"});
  if (mesh.has("max_triangles")) {
    shell.max_triangles = mesh["max_triangles"].asInt();
    if (shell.max_triangles < 2) mesh["max_triangles"].fail("expected a triangle count of at least 2");
  }
  if (mesh.has("triangles") && mesh.has("size"))
    mesh.fail("give either triangles: N or size: H, not both");
  if (mesh.has("triangles")) {
    const long n = mesh["triangles"].asInt();
    if (n < 2) mesh["triangles"].fail("expected at least 2 triangles, got " + std::to_string(n));
    shell.triangles = n;
  }
  if (mesh.has("size")) shell.size = mesh["size"].asLength(kMinLength, kMaxBodyLength);
  if (mesh.has("graded_from")) shell.graded_from = mesh["graded_from"].asLength(kMinLength, kMaxBodyLength);

  if (mesh.has("file")) {
    if (s.has("rectangle")) mesh["file"].fail("give either rectangle: or mesh: {file: ...}, not both");
    shell.rectangle = false;
    // The mesh file's coordinates are metres: `units:` converts this file's numbers only.
    if (mesh.units())
      mesh["file"].fail("a shell mesh file is read in metres; with units: " + mesh.units()->name +
                        " its coordinates would be taken as metres (write the mesh in metres, or this file in m-kg-s)");
    shell.geo_file = resolveRelativeTo(s.file(), mesh["file"].asString());
    try {
      if (readTextFile(shell.geo_file).empty()) mesh["file"].fail("mesh file '" + shell.geo_file + "' is empty");
    } catch (const InputError&) {
      throw;
    } catch (const std::exception&) {
      mesh["file"].fail("cannot read mesh file '" + shell.geo_file + "'; expected a gmsh .geo or .msh file");
    }
    body.input_files.push_back(shell.geo_file);
    if (shell.triangles > 0) mesh["triangles"].fail("a triangle count applies to rectangles; use size: with a mesh file");
    if (shell.graded_from > 0) mesh["graded_from"].fail("graded_from applies to the box patches of a rectangle, not to a mesh file");
  } else {
    const InputNode r = s["rectangle"];
    r.allowKeys({"length", "width"});
    shell.length = r["length"].asLength(kMinLength, kMaxBodyLength);
    shell.width = r["width"].asLength(kMinLength, kMaxBodyLength);
    if (shell.triangles == 0 && shell.size == 0.0)
      mesh.fail("expected triangles: N (approximate count) or size: H (element size)");
  }
  return shell;
}

// A beam section (section: {file: ...} or an inline shape) into Ks, Ms and its source.
void parseBeamSection(const InputNode& sec, const MaterialLibrary& materials, BodySpec& body, Matrix6d& Ks,
                      Matrix6d& Ms, std::string& source, SectionStressBasis* basis = nullptr) {
  if (sec.has("file")) {
    sec.allowKeys({"file"});
    const std::string path = resolveRelativeTo(sec.file(), sec["file"].asString());
    try {
      SectionFile f = fileIO().read_section(path, basis != nullptr);
      Ks = f.stiffness;
      Ms = f.mass;
      // A beam needs a positive-definite section stiffness and a positive mass.
      Eigen::LLT<Matrix6d> llt(0.5 * (Ks + Ks.transpose()));
      if (llt.info() != Eigen::Success)
        throw H5Error(path + ": /stiffness/timoshenko is not positive definite");
      if (!(Ms(0, 0) > 0)) throw H5Error(path + ": /mass/matrix has no positive mass per length");
      // The section's stresses per unit resultant (its /recovery/), for ply stresses at stations.
      if (basis) *basis = std::move(f.stress_basis);
    } catch (const std::bad_alloc&) {
      throw;  // out of memory is no input error
    } catch (const std::exception& e) {
      sec["file"].fail(std::string("cannot use section file: ") + e.what() +
                       "; expected a section-prep output (format section/1)");
    }
    source = path;
    body.input_files.push_back(path);
    return;
  }
  const InputNode shape = sec["shape"];
  const std::string kind = shape.asString();
  SectionMatrices s;
  if (kind == "solid_circle") {
    sec.allowKeys({"shape", "diameter", "material"});
    const Material& m = isotropicMaterial(materials, sec["material"]);
    s = solidCircleSection(sec["diameter"].asLength(kMinLength, kMaxSectionLength), m.E1, m.nu12, m.rho);
  } else if (kind == "tube") {
    sec.allowKeys({"shape", "outer_diameter", "wall", "material"});
    const InputNode wall = sec["wall"];
    wall.allowKeys({"thickness", "material"});
    const InputNode mat = wall.has("material") ? wall["material"] : sec["material"];
    const Material& m = isotropicMaterial(materials, mat);
    const double D = sec["outer_diameter"].asLength(kMinLength, kMaxSectionLength),
                 t = wall["thickness"].asLength(kMinLength, kMaxSectionLength);
    if (2 * t >= D) wall["thickness"].fail("wall thickness must be less than half the outer diameter");
    s = tubeSection(D, t, m.E1, m.nu12, m.rho);
  } else if (kind == "rectangle") {
    sec.allowKeys({"shape", "width", "height", "material"});
    const Material& m = isotropicMaterial(materials, sec["material"]);
    s = rectangleSection(sec["width"].asLength(kMinLength, kMaxSectionLength),
                         sec["height"].asLength(kMinLength, kMaxSectionLength), m.E1, m.nu12, m.rho);
  } else {
    shape.fail("unknown inline section shape '" + kind +
               "', expected solid_circle, tube or rectangle (or section: {file: SECTION.h5} from section-prep)");
  }
  Ks = s.K;
  Ms = s.M;
  source = kind;
}

BeamSpec parseBeam(const InputNode& b, const MaterialLibrary& materials, BodySpec& body) {
  b.allowKeys({"length", "section", "elements"});
  BeamSpec beam;
  beam.length = b["length"].asLength(kMinLength, kMaxBodyLength);
  if (b.has("elements")) {
    beam.elements = b["elements"].asInt();
    if (beam.elements < 1) b["elements"].fail("expected a positive number of elements");
  }
  parseBeamSection(b["section"], materials, body, beam.Ks, beam.Ms, beam.section_source, &beam.section_basis);
  return beam;
}

MaterialAxis parseAxis(const InputNode& a) {
  MaterialAxis axis;
  if (a.isSequence()) {
    axis.vector = a.asVector(3);
    if (!(axis.vector.norm() > 0)) a.fail("expected a non-zero vector");
    axis.vector.normalize();
    return axis;
  }
  a.allowKeys({"cylindrical", "along"});
  const InputNode c = a["cylindrical"];
  c.allowKeys({"origin", "direction"});
  axis.kind = MaterialAxis::Kind::Cylindrical;
  axis.origin = c["origin"].asVector(3);
  axis.direction = c["direction"].asVector(3);
  if (!(axis.direction.norm() > 0)) c["direction"].fail("expected a non-zero vector (the cylinder's axis)");
  axis.direction.normalize();
  const std::string along = a["along"].asString();
  if (along == "hoop") axis.hoop = true;
  else if (along != "axial") a["along"].fail("unknown direction '" + along + "', expected axial or hoop");
  return axis;
}

GeneralMeshSpec parseIgnore(const InputNode& b, GeneralMeshSpec& g) {
  if (b.has("ignore")) {
    const InputNode ig = b["ignore"];
    g.ignore_node = ig;
    if (!ig.isSequence()) ig.fail(g.nastran ? "expected a list of card names (and PID<n> properties)" : "expected a list of physical group names");
    for (std::size_t i = 0; i < ig.size(); ++i) g.ignore.push_back(ig.at(i).asString());
  }
  return g;
}

// body.mesh: {file: F, size: h}, units:, regions:, ignore:.
GeneralMeshSpec parseGeneral(const InputNode& b, const MaterialLibrary& materials, const LaminateLibrary& laminates,
                             BodySpec& body) {
  GeneralMeshSpec g;
  const InputNode mesh = b["mesh"];
  mesh.allowKeys({"file", "size", "max_triangles"});
  g.file_node = mesh["file"];
  g.file = resolveRelativeTo(mesh.file(), mesh["file"].asString());
  try {
    if (readTextFile(g.file).empty()) g.file_node.fail("mesh file '" + g.file + "' is empty");
  } catch (const InputError&) {
    throw;
  } catch (const std::exception&) {
    g.file_node.fail("cannot read mesh file '" + g.file + "'; expected a gmsh .msh or .geo file");
  }
  body.input_files.push_back(g.file);
  const std::string f = g.file;
  auto ends = [&](const std::string& e) { return f.size() >= e.size() && f.compare(f.size() - e.size(), e.size(), e) == 0; };
  g.nastran = isNastranFile(f);
  if (!ends(".msh") && !ends(".geo") && !g.nastran)
    g.file_node.fail("unknown mesh file type '" + f + "'; expected a gmsh .msh (format 2.2 or 4.x) or .geo file, "
                     "or a Nastran bulk-data deck (.bdf, .dat, .nas, .bulk)");
  if (g.nastran)
    for (const char* k : {"size", "max_triangles"})
      if (mesh.has(k)) mesh[k].fail(std::string(k) + " is for gmsh files; a Nastran deck is read as meshed");
  if (mesh.has("size")) g.size = mesh["size"].asLength(kMinLength, kMaxBodyLength);
  if (mesh.has("max_triangles")) {
    g.max_triangles = mesh["max_triangles"].asInt();
    if (g.max_triangles < 2) mesh["max_triangles"].fail("expected a triangle count of at least 2");
  }
  if (b.has("units")) {
    g.units = b["units"].asString();
    const UnitSystem* u = findUnitSystem(g.units);
    if (!u) {
      std::string all;
      for (const auto& n : unitSystemNames()) all += (all.empty() ? "" : ", ") + n;
      b["units"].fail("unknown unit system '" + g.units + "'" + didYouMean(g.units, unitSystemNames()) +
                      "; expected one of " + all);
    }
    g.length_scale = u->length;
  }
  // A Nastran deck carries its own properties: regions: only override them (PID<n>).
  if (g.nastran && !b.has("regions")) return parseIgnore(b, g);
  const InputNode regions = b["regions"];
  if (!regions.isMap() || regions.keys().empty())
    regions.fail("expected a map GROUP: {shell: {...}} or GROUP: {beam: {...}}, one entry per physical group");
  for (const auto& name : regions.keys()) {
    const InputNode r = regions[name];
    r.allowKeys({"shell", "beam", "non_structural_mass"});
    RegionSpec reg;
    reg.name = name;
    reg.node = r;
    if (r.has("shell") == r.has("beam")) r.fail("expected exactly one of shell: {...} or beam: {...}");
    if (r.has("shell")) {
      const InputNode s = r["shell"];
      s.allowKeys({"laminate", "material", "thickness", "element", "shear_correction", "axis"});
      reg.shell = true;
      reg.shell_property = parseShellSection(s, materials, laminates);
      reg.shell_property.name = name;
      if (s.has("axis")) reg.axis = parseAxis(s["axis"]);
      if (r.has("non_structural_mass")) {
        const double nsm = r["non_structural_mass"].asInRange(0.0, 1e4, "kg/m^2");
        reg.shell_property.non_structural_mass = nsm;
        reg.shell_property.laminate.mass_per_area += nsm;  // at the mid-surface
      }
    } else {
      if (r.has("non_structural_mass"))
        r["non_structural_mass"].fail("non_structural_mass is per area, for shell regions (a beam's section carries its mass)");
      const InputNode bm = r["beam"];
      bm.allowKeys({"section", "orientation"});
      parseBeamSection(bm["section"], materials, body, reg.beam_property.Ks, reg.beam_property.Ms,
                       reg.beam_property.source, &reg.section_basis);
      reg.beam_property.name = name;
      reg.orientation = bm["orientation"].asVector(3);
      if (!(reg.orientation.norm() > 0)) bm["orientation"].fail("expected a non-zero vector (the section's x2 direction)");
    }
    g.regions.push_back(reg);
  }
  return parseIgnore(b, g);
}

// body.interfaces, a deck's entry: {grid: ID} or {rbe: EID}; point, coupling
// and patch come from the deck.
InterfaceSpec parseDeckInterface(const std::string& key, const InputNode& entry, const BodySpec& spec) {
  entry.allowKeys({"grid", "rbe"});
  if (!spec.general || !spec.general->nastran)
    entry.fail("{grid: ID} and {rbe: EID} name a Nastran deck's grids and rigid elements; this body has no deck "
               "(mesh: {file: DECK.bdf})");
  if (entry.has("grid") == entry.has("rbe")) entry.fail("expected one of grid: ID or rbe: EID");
  InterfaceSpec i;
  i.name = key;
  i.node = entry;
  const InputNode id = entry.has("grid") ? entry["grid"] : entry["rbe"];
  const long v = id.asInt();
  if (v <= 0) id.fail("expected an identification number > 0");
  (entry.has("grid") ? i.grid : i.rbe) = v;
  return i;
}

// An interface's patch: nodes: {within: R | edge: NAME | set: NAME | box: [[...], [...]]}.
void parsePatch(const InputNode& nodes, const BodySpec& spec, InterfaceSpec& i) {
  nodes.allowKeys({"within", "edge", "box", "set"});
  if (nodes.keys().size() != 1) nodes.fail("expected exactly one of within: R, edge: NAME, set: NAME or box: [[x0, y0, z0], [x1, y1, z1]]");
  if (nodes.has("within")) {
    i.select = PatchSelect::Within;
    i.within = nodes["within"].asLength(1e-9, kMaxBodyLength);
  } else if (nodes.has("set")) {
    // A node set of the mesh (a physical group); checked once the mesh is read.
    i.select = PatchSelect::Set;
    i.edge = nodes["set"].asString();
  } else if (nodes.has("edge")) {
    i.select = PatchSelect::Edge;
    i.edge = nodes["edge"].asString();
    std::vector<std::string> sets;
    if (spec.beam) sets.assign(std::begin(kEnds), std::end(kEnds));
    else if (spec.shell && spec.shell->rectangle) sets.assign(std::begin(kEdges), std::end(kEdges));
    if (!sets.empty() && std::find(sets.begin(), sets.end(), i.edge) == sets.end())
      nodes["edge"].fail("unknown edge '" + i.edge + "', expected " +
                         (spec.beam ? "end_min or end_max" : "edge_xmin, edge_xmax, edge_ymin or edge_ymax"));
  } else {
    i.select = PatchSelect::Box;
    const InputNode box = nodes["box"];
    if (box.size() != 2) box.fail("expected two corners [[x0, y0, z0], [x1, y1, z1]]");
    i.box_lo = box.at(0).asVector(3);
    i.box_hi = box.at(1).asVector(3);
    if ((i.box_hi.array() < i.box_lo.array()).any()) box.fail("expected the lower corner first (x0 <= x1, y0 <= y1, z0 <= z1)");
  }
}

// body.interfaces, a point: NAME: [x, y, z] or NAME: {point, coupling, nodes}.
InterfaceSpec parsePointInterface(const std::string& key, const InputNode& entry, const BodySpec& spec) {
  const InputNode p = entry.isMap() ? entry["point"] : entry;
  InterfaceSpec i;
  i.name = key;
  i.position = p.asVector(3);
  i.node = entry;
  // Bodies are far smaller than a kilometre: 1.7e308 made the shapes infinite.
  if (i.position.cwiseAbs().maxCoeff() > 1e3)
    p.fail("expected coordinates within 1000 m of the body's origin (SI units)");
  if (entry.isMap()) {
    entry.allowKeys({"point", "coupling", "nodes", "bracket"});
    if (entry.has("bracket")) {
      if (!(spec.shell && spec.shell->rectangle))
        entry["bracket"].fail("a bracket belongs to an interface of a rectangular panel (shell: {rectangle: ...})");
      if (entry.has("coupling") || entry.has("nodes"))
        entry["bracket"].fail("a bracket carries the point on one node; a patch (coupling, nodes) carries it already");
      const Eigen::VectorXd b = entry["bracket"].asVector(2);
      i.bracket = Eigen::Vector2d(b(0), b(1));
      if (std::abs(b(0)) > spec.shell->length / 2 * (1 + 1e-9) || std::abs(b(1)) > spec.shell->width / 2 * (1 + 1e-9))
        entry["bracket"].fail("the bracket's panel point (x, y) is outside the rectangle centred on the origin");
      return i;
    }
    const std::string c = entry["coupling"].asString();
    if (c == "rigid") i.coupling = Coupling::Rigid;
    else if (c == "distributing") i.coupling = Coupling::Distributing;
    else entry["coupling"].fail("unknown coupling '" + c + "', expected distributing (RBE3) or rigid (RBE2)");
    i.nodes_node = entry["nodes"];
    parsePatch(entry["nodes"], spec, i);
  }
  if (spec.beam && (std::abs(i.position.x()) > spec.beam->length / 2 * (1 + 1e-9)))
    p.fail("the point's projection on the beam axis, x = " + std::to_string(i.position.x()) +
           ", is outside the beam [-length/2, length/2]");
  // A patch's point is its bracket's pin and may stand off the panel: its nodes are the patch's.
  if (spec.shell && spec.shell->rectangle && i.coupling == Coupling::Node &&
      (std::abs(i.position.x()) > spec.shell->length / 2 * (1 + 1e-9) ||
       std::abs(i.position.y()) > spec.shell->width / 2 * (1 + 1e-9)))
    p.fail("the point's projection on the panel, (x, y), is outside the rectangle centred on the origin "
           "(a point off the panel needs a bracket: {point: [x, y, z], bracket: [x0, y0]} on a panel point)");
  return i;
}

void parseInterfaces(const InputNode& b, BodySpec& spec, std::set<std::string>& names) {
  if (!b.has("interfaces")) return;
  const InputNode in = b["interfaces"];
  if (!in.isMap()) in.fail("expected a map NAME: [x, y, z] or NAME: {point, coupling, nodes}");
  for (const auto& key : in.keys()) {
    const InputNode entry = in[key];
    const bool deck = entry.isMap() && (entry.has("grid") || entry.has("rbe"));
    spec.interfaces.push_back(deck ? parseDeckInterface(key, entry, spec) : parsePointInterface(key, entry, spec));
    names.insert(key);
  }
}

// masses: [{at: [x, y, z] | INTERFACE, mass: m, inertia: [[...]]}]
void parseMasses(const InputNode& b, BodySpec& spec, const std::set<std::string>& names) {
  if (!b.has("masses")) return;
  if (!spec.general) b["masses"].fail("masses: belong to a body from a mesh file (mesh: {file: ...})");
  const InputNode ms = b["masses"];
  if (!ms.isSequence()) ms.fail("expected a list of {at: [x, y, z] or INTERFACE, mass: M, inertia: [[...], [...], [...]]}");
  for (std::size_t k = 0; k < ms.size(); ++k) {
    const InputNode m = ms.at(k);
    m.allowKeys({"at", "mass", "inertia"});
    MassSpec ma;
    ma.node = m;
    const InputNode at = m["at"];
    if (at.isScalar()) {
      ma.interface = at.asString();
      if (!names.count(ma.interface)) {
        at.fail("no interface '" + ma.interface + "'" +
                didYouMean(ma.interface, std::vector<std::string>(names.begin(), names.end())) +
                "; expected a point [x, y, z] or an interface name");
      }
      for (const auto& i : spec.interfaces)
        if (i.name == ma.interface) ma.at = i.position;
    } else {
      ma.at = at.asVector(3);
      if (ma.at.cwiseAbs().maxCoeff() > 1e3) at.fail("expected coordinates within 1000 m of the body's origin (SI units)");
    }
    ma.mass = m["mass"].asInRange(0.0, 1e9, "kg");
    if (m.has("inertia")) {
      ma.inertia = m["inertia"].asMatrix(3, 3);
      if ((ma.inertia - ma.inertia.transpose()).cwiseAbs().maxCoeff() > 1e-9 * ma.inertia.cwiseAbs().maxCoeff())
        m["inertia"].fail("expected a symmetric inertia tensor");
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(ma.inertia);
      if (es.eigenvalues().minCoeff() < -1e-12 * es.eigenvalues().cwiseAbs().maxCoeff())
        m["inertia"].fail("expected a positive semi-definite inertia tensor (kg m^2, about the point)");
    }
    spec.general->masses.push_back(ma);
  }
}

// reference: free | {clamp: [...], pin: [...]}
void parseReference(const InputNode& b, BodySpec& spec, const std::set<std::string>& names) {
  if (!b.has("reference")) return;
  const InputNode r = b["reference"];
  if (r.isScalar()) {
    if (r.asString() != "free") r.fail("expected free, or a map {clamp: [SETS], pin: [SETS]}");
  } else {
    r.allowKeys({"clamp", "pin", "free"});
    std::vector<std::string> known(names.begin(), names.end());
    if (spec.shell && spec.shell->rectangle) known.insert(known.end(), std::begin(kEdges), std::end(kEdges));
    if (spec.beam) known.insert(known.end(), std::begin(kEnds), std::end(kEnds));
    for (const char* kind : {"clamp", "pin"}) {
      if (!r.has(kind)) continue;
      const InputNode list = r[kind];
      for (std::size_t i = 0; i < list.size(); ++i) {
        const InputNode item = list.at(i);
        const std::string set = item.asString();
        // Geo files define their own sets (physical groups); checked after meshing.
        const bool open_set = (spec.shell && !spec.shell->rectangle) || spec.general || spec.matrices;
        if (!open_set && std::find(known.begin(), known.end(), set) == known.end()) {
          item.fail("unknown set '" + set + "'" + didYouMean(set, known) +
                    "; expected an interface name" +
                    (spec.beam ? ", end_min or end_max" : ", edge_xmin, edge_xmax, edge_ymin or edge_ymax"));
        }
        spec.reference.push_back({set, std::string(kind) == "clamp", item});
      }
    }
  }
}

// modes: N | {count: N | keep: [...] | static_error: E, static_correction: ...} | max_frequency_hz: F
void parseModes(const InputNode& b, BodySpec& spec) {
  if (b.has("modes") && b.has("max_frequency_hz")) b.fail("give either modes: N or max_frequency_hz: F, not both");
  if (b.has("modes") && b["modes"].isMap()) {
    const InputNode m = b["modes"];
    m.allowKeys({"static_error", "count", "keep", "static_correction"});
    if (int(m.has("static_error")) + int(m.has("count")) + int(m.has("keep")) != 1)
      m.fail("expected one of count: N, keep: [mode numbers] or static_error: E in modes: {...}");
    if (m.has("keep")) {
      const InputNode k = m["keep"];
      if (!k.isSequence() || k.size() == 0) k.fail("expected a list of mode numbers, e.g. keep: [1, 2, 5, 7]");
      for (std::size_t i = 0; i < k.size(); ++i) {
        const long j = k.at(i).asInt();
        if (j < 1) k.at(i).fail("expected a mode number >= 1 (modes are numbered from 1 by ascending frequency)");
        if (!spec.keep_modes.empty() && j <= spec.keep_modes.back())
          k.at(i).fail("expected ascending mode numbers without repeats (got " + std::to_string(j) + " after " +
                       std::to_string(spec.keep_modes.back()) + ")");
        spec.keep_modes.push_back(j);
      }
      spec.modes_node = k;
      spec.modes = static_cast<long>(spec.keep_modes.size());
    } else if (m.has("count")) {
      spec.modes_node = m["count"];
      spec.modes = m["count"].asInt();
      if (spec.modes < 1) m["count"].fail("expected a positive number of modes");
    } else {
      spec.modes_node = m;
      spec.static_error = m["static_error"].asPositive();
      if (spec.static_error >= 1) m["static_error"].fail("expected a share below 1 (e.g. 0.01 for 1 %)");
    }
    if (m.has("static_correction")) {
      const InputNode c = m["static_correction"];
      spec.static_correction_node = c;
      if (c.isSequence()) {
        if (c.size() == 0) c.fail("expected true, false or a list of interface names");
        for (std::size_t i = 0; i < c.size(); ++i) {
          const std::string name = c.at(i).asString();
          if (std::none_of(spec.interfaces.begin(), spec.interfaces.end(), [&](const InterfaceSpec& f) { return f.name == name; })) {
            std::vector<std::string> known;
            for (const auto& f : spec.interfaces) known.push_back(f.name);
            c.at(i).fail("no interface '" + name + "'" + didYouMean(name, known));
          }
          spec.static_correction_interfaces.push_back(name);
        }
        spec.static_correction = true;
      } else {
        spec.static_correction = c.asBool();
      }
    }
  } else if (b.has("modes")) {
    spec.modes_node = b["modes"];
    spec.modes = b["modes"].asInt();
    if (spec.modes < 1) b["modes"].fail("expected a positive number of modes, or {static_error: E}");
  } else if (b.has("max_frequency_hz")) {
    spec.max_frequency_hz = b["max_frequency_hz"].asPositive();
  } else {
    b.fail("missing the mode selection: expected modes: N or max_frequency_hz: F");
  }
}

// mass:, reduction:, geometric_stiffness: and what they ask of the rest.
void parseMassAndReduction(const InputNode& b, BodySpec& spec) {
  // Default lumped_moments: the simulated body then has the exact mass, centre and
  // inertia (docs/fe-prep.md, "Mass and inertia"); plain row sums only when asked.
  const std::string mass = b.string("mass", "lumped_moments");
  if (mass == "lumped") spec.lumped = true, spec.moment_lumping = false;
  else if (mass == "lumped_moments") spec.lumped = spec.moment_lumping = true;
  else if (mass == "consistent") spec.lumped = false, spec.moment_lumping = true;
  else b["mass"].fail("unknown mass '" + mass + "', expected lumped, lumped_moments or consistent");
  const std::string reduction = b.string("reduction", "free");
  if (reduction == "craig_bampton") spec.craig_bampton = true;
  else if (reduction != "free") b["reduction"].fail("unknown reduction '" + reduction + "', expected free or craig_bampton");
  if (spec.craig_bampton && spec.static_error > 0)
    b["modes"].fail("static_error chooses free (constrained) modes; a craig_bampton basis is statically complete at its boundary already");
  if (spec.static_error > 0 && spec.interfaces.empty())
    b["modes"].fail("static_error needs interfaces: the unit loads act there");
  if (spec.static_correction && spec.craig_bampton)
    spec.static_correction_node.fail("static_correction augments free (constrained) modes; a craig_bampton basis is statically complete at its boundary already");
  if (spec.static_correction && spec.interfaces.empty())
    spec.static_correction_node.fail("static_correction needs interfaces: the unit loads act there");
  if (spec.craig_bampton && spec.reference.empty())
    b["reduction"].fail("craig_bampton needs its boundary in reference: (clamp: or pin: the interfaces where the body is joined)");
  if (b.has("geometric_stiffness")) {
    spec.geometric_stiffness_node = b["geometric_stiffness"];
    spec.geometric_stiffness = b["geometric_stiffness"].asBool();
    if (spec.geometric_stiffness && spec.reference.empty())
      b["geometric_stiffness"].fail("geometric stiffness needs a reference that holds the body (reference: {clamp: [...]}): "
                                    "the stress of the inertial loads is the static response of the held body");
  }
}

// body: shell: | beam: | mesh: | matrices: and what each excludes.
void parseBodyKind(const InputNode& b, const MaterialLibrary& materials, const LaminateLibrary& laminates, BodySpec& spec) {
  if (int(b.has("shell")) + int(b.has("beam")) + int(b.has("mesh")) + int(b.has("matrices")) != 1)
    b.fail("expected exactly one of shell:, beam:, mesh: {file: ...} (with regions:) or matrices:");
  if (!b.has("mesh"))
    for (const char* k : {"regions", "masses", "ignore"})
      if (b.has(k)) b[k].fail(std::string(k) + " belongs to a body from a mesh file (mesh: {file: ...})");
  if (b.has("units") && !b.has("mesh") && !b.has("matrices"))
    b["units"].fail("body.units gives the units of a mesh file or of imported matrices; a shell: or beam: body "
                    "is read in the units of its YAML file (units: at the top of the file)");
  if (b.has("shell")) spec.shell = parseShell(b["shell"], materials, laminates, spec);
  else if (b.has("beam")) spec.beam = parseBeam(b["beam"], materials, spec);
  else if (b.has("mesh")) spec.general = parseGeneral(b, materials, laminates, spec);
  else spec.matrices = parseMatricesSpec(b, spec.input_files);
  if (spec.matrices && b.has("mass"))
    b["mass"].fail("an imported body uses its mass matrix as given (the nodal masses of /mass/nodal are fitted to it); drop mass:");
  if (spec.matrices && b.has("geometric_stiffness"))
    b["geometric_stiffness"].fail("geometric stiffness needs fe-prep's own elements; an imported body has only its matrices");
}

}  // namespace

BodySpec parseBodySpec(const InputNode& root) {
  root.allowKeys({"units", "materials", "laminates", "body"});
  BodySpec spec;
  MaterialLibrary materials;
  LaminateLibrary laminates;
  auto includeFile = [&](const char* block) {
    if (root.has(block) && root[block].has("include"))
      spec.input_files.push_back(resolveRelativeTo(root.file(), root[block]["include"].asString()));
  };
  includeFile("materials");
  includeFile("laminates");
  if (root.has("materials")) materials = readMaterials(root["materials"]);
  if (root.has("laminates")) laminates = readLaminates(root["laminates"], materials);

  const InputNode b = root["body"];
  b.allowKeys({"name", "shell", "beam", "mesh", "matrices", "units", "regions", "masses", "ignore", "interfaces",
               "reference", "modes", "max_frequency_hz", "mass", "reduction", "geometric_stiffness"});
  spec.name = b.has("name") ? b["name"].asName() : std::string("body");
  parseBodyKind(b, materials, laminates, spec);
  std::set<std::string> names;  // the interfaces' names, for masses: and reference:
  parseInterfaces(b, spec, names);
  parseMasses(b, spec, names);
  parseReference(b, spec, names);
  parseModes(b, spec);
  parseMassAndReduction(b, spec);
  if (spec.general && spec.general->nastran) applyNastranDeck(spec);
  return spec;
}

BodySpec readBodySpec(const std::string& path) {
  BodySpec spec = parseBodySpec(InputNode::loadFile(path));
  spec.input_files.insert(spec.input_files.begin(), path);
  return spec;
}

}  // namespace fc::feprep
