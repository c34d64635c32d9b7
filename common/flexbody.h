#pragma once
// The reduced flexible body: what fe-prep writes and mbs-run reads (format
// "flexbody/1", layout in ../shared/contracts.md and docs/body-file.md), and the
// inertia invariants of the floating-frame-of-reference formulation with lumped
// nodal masses (Ambrosio & Goncalves, Multibody Syst. Dyn. 6 (2001) 163-182;
// Shabana, Dynamics of Multibody Systems, 3rd ed., ch. 5, sec. 5.5 "inertia
// shape integrals", here as sums over lumped nodes instead of volume integrals).
//
// Kinematics the invariants serve (body frame, undeformed node position s0_k):
//   node displacement  u_k  = Phi_k w      (Phi_k: rows 0-2 of the node's 6 shape rows)
//   node rotation      th_k = Theta_k w    (Theta_k: rows 3-5)
//   deformed position  s_k  = s0_k + Phi_k w
// Kinetic energy (omega' the body angular velocity in body axes, V = A^T rdot):
//   T = 1/2 sum_k m_k |V + omega' x s_k + Phi_k wdot|^2
//     + 1/2 sum_k (omega' + Theta_k wdot)^T J_k (omega' + Theta_k wdot),
// J_k = diag(nodal rotary inertias), kept fixed in body axes (the small elastic
// rotation of a node's own inertia is neglected, as in a lumped-mass FE model).
// Every term of the mass matrix and of the quadratic velocity vector is a
// polynomial in w whose coefficients are the sums below; mbs-run loops over the
// nodes only for the terms quadratic in w of a body with more modes than nodal
// rows, where that is cheaper (mbs-run/mechanics/flexible/nodal_inertia.h). The kernel
// that uses them: mbs-run/mechanics/flexible/flexible_inertia.h.
#include <Eigen/Dense>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "common/stress_data.h"

namespace fc {

using IndexMatrix = Eigen::Matrix<long, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Where a body file came from (root attributes of the file).
struct Provenance {
  std::string tool = "fe-prep";
  std::string version;        // tool version; empty -> fc::version() on write
  std::string inputs_sha256;  // SHA-256 of the inputs (fc::sha256Files)
  std::string format;         // filled on read: the file's "flexbody/N"
};

// A named point of the body where joints and forces attach.
struct FlexInterface {
  std::string name;
  long node = -1;                 // index into FlexBody::nodes it is rigidly attached to
  Eigen::Vector3d position;       // undeformed body-frame position (may be off the node)
  Eigen::MatrixXd shapes;         // (n_modes, 6): the point's u1 u2 u3 theta1 theta2 theta3 per mode
  // Static truncation (fe-prep, bodies whose reference holds every rigid motion;
  // empty otherwise): per unit force x y z / moment x y z at the point, the
  // exact static deflection, each mode's share of it, and the share all the
  // file's modes miss (docs/fe-prep.md, "Modes chosen by error").
  Eigen::VectorXd static_compliance;   // (6)
  Eigen::MatrixXd static_participation;// (n_modes, 6)
  Eigen::VectorXd static_error;        // (6)
  // fe-prep geometric_stiffness: true, interfaces the reference does not hold:
  // the modal geometric stiffness (n_modes, n_modes) of a unit force x, y, z and
  // moment x, y, z (body axes) at the point; empty otherwise. Written as
  // /geometric_stiffness/interfaces/NAME/matrices (docs/body-file.md).
  std::vector<Eigen::MatrixXd> geometric_stiffness;
};

// The unit load cases of FlexBody::geometric_stiffness, in order (the load
// parameters p of fe-prep/geometric_stiffness.h: frame origin acceleration minus
// gravity, products of angular velocity, angular acceleration, all in body axes).
constexpr int kGeometricStiffnessCaseCount = 12;
extern const std::array<const char*, kGeometricStiffnessCaseCount> kGeometricStiffnessCases;

// One region of a general body (fe-prep's `regions:`, a Nastran property, a
// node set, the concentrated masses), written under /regions/NAME so that
// `--inspect` can say what the body is made of (docs/body-file.md, "Regions").
struct FlexRegion {
  std::string name;
  std::string kind;         // "shell", "beam", "set" or "masses"
  std::string members_of;   // the /mesh dataset the members index: "triangles", "beams" or "nodes"
  std::vector<long> members;// 0-based rows of /mesh/<members_of>
  double mass = 0.0;        // [kg]; 0 for sets
  std::string property;     // laminate name or section source; empty for sets and masses
  std::string element;      // "dst" / "dkt" for shells, "timoshenko" for beams
  std::string axis;         // the material axes in words (fibre reference axis, or the section's x2)
  std::string summary;      // the line fe-prep printed for it
  Eigen::MatrixXd axes;     // (n_members, 3): each triangle's fibre (0 deg) axis or each beam's x2; empty else
};

struct FlexBody {
  std::string name;
  Eigen::MatrixXd nodes;                        // (n_nodes, 3) undeformed, body frame [m]
  std::map<std::string, IndexMatrix> elements;  // "triangles" (ne,3), "beams" (ne,2): 0-based node indices
  Eigen::MatrixXd nodal_mass;                   // (n_nodes, 4): lumped mass [kg], rotary inertias about body x,y,z [kg m^2]
  Eigen::VectorXd eigenvalues;                  // (n_modes) omega^2 [rad^2/s^2], ascending
  Eigen::VectorXd frequencies_hz;               // (n_modes) omega / (2 pi)
  // (6 n_nodes, n_modes), node-major: row 6k+d is dof d (u1 u2 u3 th1 th2 th3) of
  // node k, column j is mode j, normalised to unit modal mass.
  Eigen::MatrixXd shapes;
  std::vector<FlexInterface> interfaces;
  double mass = 0.0;                            // [kg]
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();    // body frame [m]
  Eigen::Matrix3d inertia_tensor = Eigen::Matrix3d::Zero();    // about the body origin, undeformed [kg m^2]
  // The three above are the simulated body's (what the invariants imply). The exact
  // continuum values, written under /inertia/exact/ when they differ from those.
  // Which basis the shapes are (root attribute `reduction`): "free: N shapes" or
  // "craig_bampton: ... = N shapes" (docs/fe-prep.md); empty when unknown.
  std::string reduction;
  // /reduction/ (docs/body-file.md): the eigenmodes the basis keeps (1-based
  // numbers by ascending frequency of the constrained, for craig_bampton the
  // fixed-interface, eigenproblem; all the lowest unless fe-prep's
  // modes: {keep: [...]} chose them) and their eigenvalues [rad^2/s^2]; for a
  // craig_bampton basis also the (n_modes, n_kept) fixed-interface amplitudes
  // of each unit shape (craig_bampton.h), from which mbs-run reports each
  // fixed-interface mode's strain energy. Empty when the file predates them.
  std::vector<long> kept_modes;
  Eigen::VectorXd kept_eigenvalues;
  Eigen::MatrixXd fixed_interface_coordinates;
  bool has_exact_inertia = false;
  double exact_mass = 0.0;
  Eigen::Vector3d exact_center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d exact_inertia_tensor = Eigen::Matrix3d::Zero();
  // fe-prep geometric_stiffness: true: per unit inertial load case (the 12 of
  // fe-prep/geometric_stiffness.h, in that order) the modal geometric stiffness
  // (n_modes, n_modes); written as /geometric_stiffness/matrices (docs/body-file.md).
  std::vector<Eigen::MatrixXd> geometric_stiffness;
  // Stress recovery data (/mesh/centroids, /stress/): written when not empty,
  // never read by readFlexBody (mbs-run reads it with readStressData when asked).
  StressRecoveryData stress;
  // General bodies: their regions (/regions/NAME); written when not empty,
  // never read by readFlexBody (files without them stay readable).
  std::vector<FlexRegion> regions;

  long nodeCount() const { return static_cast<long>(nodes.rows()); }
  int modeCount() const { return static_cast<int>(eigenvalues.size()); }
  const FlexInterface& interface(const std::string& name) const;  // throws naming the body and the known names
};

// The inertia invariants (sums over the lumped nodes k; a, b in {x, y, z};
// Phi_a = row a of Phi_k, a 1 x nm row; J_k = diag of nodal_mass(k, 1:3)):
struct InertiaInvariants {
  int n_modes = 0;
  double mass = 0.0;                                          // m      = sum m_k
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();     // S0     = sum m_k s0_k
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();    // E0     = sum m_k s0_k s0_k^T
  Eigen::Matrix3d rotary_inertia = Eigen::Matrix3d::Zero();   // Jr     = sum J_k
  Eigen::MatrixXd modal_first_moment;   // (3, nm)   S1      = sum m_k Phi_k
  Eigen::MatrixXd modal_second_moment;  // (9, nm)   C, row 3a+b = sum m_k s0_k,a Phi_k,b
  std::array<Eigen::MatrixXd, 9> modal_products;  // [3a+b] (nm, nm): S_ab = sum m_k Phi_k,a^T Phi_k,b
  Eigen::MatrixXd rotary_modal;         // (3, nm)   Jt      = sum J_k Theta_k
  Eigen::MatrixXd rotary_modal_mass;    // (nm, nm)  Jtt     = sum Theta_k^T J_k Theta_k

  // Undeformed inertia tensor about the body origin: tr(E0) I - E0 + Jr.
  Eigen::Matrix3d inertiaAboutOrigin() const;
  Eigen::Vector3d centerOfMass() const { return first_moment / mass; }
  // Modal mass matrix sum_a S_aa + Jtt (the identity for modes normalised with the lumped mass).
  Eigen::MatrixXd modalMass() const;
  // The same invariants restricted to the first n modes (n <= n_modes).
  InertiaInvariants truncated(int n) const;
};

// Throws std::invalid_argument naming WHERE and the body when its arrays disagree
// in size (nodes, nodal masses, shapes, interfaces, elements, invariants if given).
void checkFlexBodySizes(const FlexBody& body, const InertiaInvariants* invariants, const std::string& where);

// Invariants of `body` from its lumped nodal masses and its first n_modes modes
// (-1: all). Throws std::invalid_argument on inconsistent sizes.
InertiaInvariants computeInertiaInvariants(const FlexBody& body, int n_modes = -1);

// Invariants of a rigid body (no modes) of mass m, centre of mass c (body frame)
// and inertia tensor J_c about the centre of mass, in body axes: S0 = m c,
// E0 = m c c^T, Jr = J_c, so that tr(E0) I - E0 + Jr = J_c + m (c.c I - c c^T).
InertiaInvariants rigidInvariants(double mass, const Eigen::Vector3d& center_of_mass,
                                  const Eigen::Matrix3d& inertia_about_com);

// Sets body.mass, center_of_mass and inertia_tensor from the lumped nodal masses.
void setRigidPropertiesFromLumpedMasses(FlexBody& body);

// Writes the contract layout ("flexbody/1") and the invariants under /invariants/
// atomically: the file appears whole or not at all. Throws fc::H5Error or
// std::invalid_argument (inconsistent sizes) naming the file.
// Why a body cannot be simulated (non-positive mass, singular or impossible
// inertia about the centre of mass), or "". writeFlexBody refuses such a body
// (std::invalid_argument naming it and the cause) and readFlexBody such a file.
std::string flexBodyPhysicalProblem(const FlexBody& body);

// "mode_NN" (NN from 01, by ascending frequency): /view/mode_NN and /view/mode_NN_rotation
// are the (n_nodes, 3) translations and rotations of mode NN, virtual views of
// /modes/shapes written for ParaView (BODY.xdmf); /view/nodal_mass views /mass/nodal[:, 0].
std::string modeViewName(int mode_index);

void writeFlexBody(const std::string& path, const FlexBody& body,
                   const InertiaInvariants& invariants, const Provenance& provenance);

enum class FlexBodyParts {
  Dynamics,  // what mbs-run needs: modes' eigenvalues/frequencies, interfaces, rigid
             // properties, invariants; no mesh, nodal masses or nodal shapes
  All        // everything, including the mesh and the (first n_modes) nodal shapes
};

struct FlexBodyFile {
  FlexBody body;                  // first n_modes modes only
  InertiaInvariants invariants;   // restricted to the first n_modes modes
  Provenance provenance;
  int modes_in_file = 0;
};

// Number of modes a body file holds (checks the format first; errors as readFlexBody).
int flexBodyModeCount(const std::string& path);

// Reads the first n_modes modes (-1: all) of a body file, by hyperslab so that the
// rest is never read. Errors (fc::H5Error) name the file and say what is wrong:
// not a flexbody file, a newer format version, fewer modes than asked, a missing
// or mis-shaped dataset.
FlexBodyFile readFlexBody(const std::string& path, int n_modes = -1,
                          FlexBodyParts parts = FlexBodyParts::Dynamics);

// The stress recovery data of a body file for its first n_modes modes:
// /mesh/centroids, and for shells /stress/strains (leading n_modes only) and
// /stress/plies/*, for beams /stress/section_resultants (leading n_modes
// only). H5Error naming the file when it has none (written before stress
// recovery existed) or when a dataset is mis-shaped or not finite.
StressRecoveryData readStressData(const std::string& path, int n_modes);

// The stress recovery basis of a section-prep file (section/1 with
// /recovery/ply_stress, /mesh/*, /materials/*); empty when the file has none.
// H5Error naming the file when it is mis-shaped.
SectionStressBasis readSectionStressBasis(const std::string& section_path);

}  // namespace fc
