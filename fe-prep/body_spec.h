#pragma once
// The body YAML of contracts.md (fe-prep section) as checked data. Every
// value keeps the InputNode it came from so that problems found later (a set
// name the mesh does not have, a point outside the panel) still name the
// file, line and key.
#include <Eigen/Dense>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/input.h"
#include "common/laminate.h"
#include "common/stress_data.h"
#include "fe-prep/elements/shell_triangle.h"
#include "fe-prep/import/matrices_spec.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

struct ShellSpec {
  bool rectangle = true;
  double length = 0.0, width = 0.0;  // rectangle
  std::string geo_file;              // mesh: {file: ...} (resolved path)
  LaminateStiffness laminate;
  std::string laminate_name;
  PlyTable plies;  // the laminate's plies for stress recovery (/stress/plies)
  fe::ShellKind kind = fe::ShellKind::DST;
  long triangles = 0;  // mesh: {triangles: N}
  double size = 0.0;   // mesh: {size: h}
  long max_triangles = 500000;  // mesh: {max_triangles: N}, refused above (panel_mesher.h)
  double graded_from = 0.0;     // mesh: {graded_from: H}: box patches refined with h below H (panel_mesher.h)
  InputNode mesh_node;
};

struct BeamSpec {
  double length = 0.0;
  long elements = 2;
  Matrix6d Ks = Matrix6d::Zero();  // section stiffness, VABS order
  Matrix6d Ms = Matrix6d::Zero();  // section mass per length
  std::string section_source;      // file path or inline shape name
  SectionStressBasis section_basis;  // the section file's /recovery/ (empty for inline shapes)
};

// The fibre reference axis (0 deg) of a shell region, as CalculiX's
// *ORIENTATION or Nastran's MCID: a fixed vector projected on each element, or
// a cylindrical system whose axial or hoop direction at the element's centroid
// is projected (element_properties.h).
struct MaterialAxis {
  enum class Kind { Vector, Cylindrical };
  Kind kind = Kind::Vector;
  Eigen::Vector3d vector = Eigen::Vector3d::UnitX();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), direction = Eigen::Vector3d::UnitZ();  // cylindrical
  bool hoop = false;  // along: hoop (else axial)
};

// One entry of body.regions: a physical group (or Nastran PID<n>) and its
// shell or beam property.
struct RegionSpec {
  std::string name;
  InputNode node;
  bool shell = false;  // else beam
  ShellProperty shell_property;
  MaterialAxis axis;
  BeamProperty beam_property;
  Eigen::Vector3d orientation = Eigen::Vector3d::UnitY();  // beams: the section x2 direction
  SectionStressBasis section_basis;  // beams: the section file's /recovery/ (empty for inline shapes)
};

// A concentrated mass (body.masses): at a point (nearest node) or an interface's point.
struct MassSpec {
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  std::string interface;  // non-empty: at this interface's point (its node)
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the point
  InputNode node;
};

// A body from a mesh file with regions (contracts.md, "General bodies").
struct GeneralMeshSpec {
  std::string file;  // resolved path
  InputNode file_node;
  double size = 0.0;            // .geo: element size cap
  double length_scale = 1.0;    // units: the file's length unit in metres
  std::string units = "m-kg-s";
  std::vector<RegionSpec> regions;
  std::vector<std::string> ignore;  // groups (or cards) the body leaves out
  InputNode ignore_node;
  std::vector<MassSpec> masses;
  long max_triangles = 500000;
  // A Nastran deck (.bdf, .dat, .nas, .bulk): read while the YAML is parsed, its
  // mesh with every element's property, sets and masses (fe-prep/mesh_files/nastran.h).
  bool nastran = false;
  std::shared_ptr<const Mesh> deck_mesh;
  std::map<std::string, int> deck_element_counts;  // CQUAD4, CTRIA3, CBAR... as in the deck
};

// How an interface point is attached (contracts.md, fe-prep "Distributed interfaces").
enum class Coupling { Node, Rigid, Distributing };  // Node: rigidly to the one node at its projection
enum class PatchSelect { Within, Edge, Box, Set };  // Set: nodes: {set: GROUP} (a mesh node set)

struct InterfaceSpec {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // the (reference) point
  InputNode node;
  Coupling coupling = Coupling::Node;
  PatchSelect select = PatchSelect::Within;
  double within = 0.0;          // nodes: {within: r}
  std::string edge;             // nodes: {edge: NAME} or {set: NAME}
  Eigen::Vector3d box_lo = Eigen::Vector3d::Zero(), box_hi = Eigen::Vector3d::Zero();  // nodes: {box: [lo, hi]}
  InputNode nodes_node;
  // A single-node interface on a rectangular panel carried by a bracket: the node at the panel point
  // `bracket: [x, y]` carries the point rigidly, so the point may stand off the panel's edge (a hinge
  // pin beyond it). Without it the node is the one at the point's projection.
  std::optional<Eigen::Vector2d> bracket;
  // A Nastran deck's own: {grid: ID} (the grid's node) or {rbe: EID} (an RBE2's
  // rigid or an RBE3's distributing patch, its point the GN / REFGRID), resolved
  // with the deck (applyNastranDeck); an RBE3's weights as the deck gives them.
  long grid = 0, rbe = 0;
  Eigen::VectorXd given_weights;
};

struct ReferenceEntry {
  std::string set;
  bool clamp = false;
  InputNode node;
};

struct BodySpec {
  std::string name;
  std::optional<ShellSpec> shell;
  std::optional<BeamSpec> beam;
  std::optional<MatricesSpec> matrices;  // a body from another FE code's matrices (fe-prep/import/)
  std::optional<GeneralMeshSpec> general;  // body.mesh: {file: ...} with regions
  std::vector<InterfaceSpec> interfaces;
  std::vector<ReferenceEntry> reference;  // empty: free
  long modes = 0;
  InputNode modes_node;  // where `modes:` was given, for errors found once the mesh is known
  double static_error = 0.0;  // modes: {static_error: e}: the fewest modes that miss at most e (static_response.h)
  double max_frequency_hz = 0.0;
  // modes: {keep: [1, 2, 5, 7]}: these eigenmodes (1-based, by ascending
  // frequency) and no others, e.g. the ones a run excited (mbs-run reports
  // each fixed-interface mode's peak strain energy); `modes` is then their
  // count. Ascending, without repeats.
  std::vector<long> keep_modes;
  // modes: {count: N, static_correction: true | [interfaces]}: the kept modes
  // augmented with the residual static responses (attachment modes) to unit
  // loads at the interfaces, re-diagonalised (residual_flexibility.h).
  bool static_correction = false;
  std::vector<std::string> static_correction_interfaces;  // empty: every interface the reference does not hold
  InputNode static_correction_node;
  bool lumped = true;  // false (mass: consistent): consistent mass in the eigenproblem
  // mass: lumped_moments (default) and consistent: the nodal masses (/mass/nodal,
  // the invariants) moved between nodes so that the body's mass, first and second
  // moments are exact (mass_lumping.h); with lumped_moments also in the eigenproblem.
  bool moment_lumping = true;
  // reduction: craig_bampton: constraint modes of the boundary (the reference
  // conditions) plus `modes` fixed-interface modes, diagonalised (craig_bampton.h).
  bool craig_bampton = false;
  // geometric_stiffness: true: the modal geometric stiffness of the unit inertial
  // load cases (geometric_stiffness.h), for mbs-run's geometric_stiffening.
  bool geometric_stiffness = false;
  InputNode geometric_stiffness_node;
  std::vector<std::string> input_files;  // the YAML and every file it uses (for the SHA-256)
};

// Reads and checks a body YAML file; InputError on any problem.
BodySpec readBodySpec(const std::string& path);
BodySpec parseBodySpec(const InputNode& root);

// Closed-form isotropic sections for inline beam input (VABS order):
// solid_circle {diameter}, tube {outer_diameter, wall: {thickness}}, rectangle {width, height}.
// Shear correction factors of Cowper (J. Appl. Mech. 33, 1966).
struct SectionMatrices {
  Matrix6d K, M;
};
SectionMatrices solidCircleSection(double diameter, double E, double nu, double rho);
SectionMatrices tubeSection(double outer_diameter, double wall, double E, double nu, double rho);
SectionMatrices rectangleSection(double width, double height, double E, double nu, double rho);

}  // namespace fc::feprep
