#pragma once
// Modal geometric stiffness of the body's inertial load cases
// (docs/body-file.md "Geometric stiffness" for the derivation and sources).
//
// A body whose frame moves with origin acceleration a0 (body axes, gravity
// folded in as a0 - g), angular velocity omega and angular acceleration alpha
// (body axes) carries at node k (undeformed position s_k, lumped mass m_k) the
// inertial load f_k = -m_k (a0 + alpha x s_k + omega x (omega x s_k)), linear in
// the 12 load parameters
//   p = [a0_x a0_y a0_z, w_x^2 w_y^2 w_z^2, w_x w_y, w_y w_z, w_z w_x, alpha_x alpha_y alpha_z]
// (omega x (omega x s) = omega (omega . s) - s |omega|^2: the case w_x^2 is the
// acceleration (0, -s_y, -s_z), the case w_x w_y is (s_y, s_x, 0)). For each unit
// case c fe-prep solves the static response of the body held by its reference
// condition, K u_c = f_c, takes the stress state it causes (beams: the axial
// force N_e = axial end force of K_e u_e; shells: the membrane resultants
// [N_xx N_yy N_xy] of every triangle), and projects the element geometric
// stiffness of that stress state on the modes: K_c = Phi^T K_G(sigma_c) Phi.
// mbs-run adds sum_c p_c(t) K_c to the modal stiffness (mbs-run/mechanics/flexible/
// geometric_stiffening.h). This is SIMPACK's first-order SID term (Wallrapp,
// Nonlinear Dyn. 5 (1994) 451: the geometric stiffness of unit inertia loads)
// and MBDyn's modal stress-stiffening per load case.
#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "common/flexbody.h"
#include "common/laminate.h"
#include "common/materials.h"
#include "fe-prep/elements/shell_triangle.h"
#include "fe-prep/mesh.h"
#include "fe-prep/reference_conditions.h"
#include "la_backend.h"

namespace fc::feprep {

// The cases in the file's order: fc::kGeometricStiffnessCases (common/flexbody.h).
constexpr int kInertialCases = kGeometricStiffnessCaseCount;

// Unit-case accelerations of a material point at s (3, kInertialCases): column c
// is the acceleration that unit p_c gives it.
Eigen::Matrix<double, 3, kInertialCases> inertialCaseAccelerations(const Eigen::Vector3d& s);

// Nodal loads (6 n, kInertialCases) of the unit cases on the lumped translational
// masses (lumped: 6 n, as the assembly's; the rotary inertias' moments bend
// only, they do not load a beam axially, and are left out).
Eigen::MatrixXd inertialLoadCases(const Eigen::MatrixXd& nodes, const Eigen::VectorXd& lumped);

// Axial force of every beam element (n_beams, n_cases) under the nodal
// displacements u (6 n, n_cases).
Eigen::MatrixXd beamAxialForces(const Mesh& mesh, const Eigen::Vector3d& section_x2, const Matrix6d& Ks,
                                const Eigen::MatrixXd& u);

// K_c = Phi^T K_G(N_c) Phi for each column of axial forces (n_beams, n_cases);
// shapes: (6 n, n_modes). Returns n_cases symmetric (n_modes, n_modes) matrices.
std::vector<Eigen::MatrixXd> projectBeamGeometricStiffness(const Mesh& mesh, const Eigen::Vector3d& section_x2,
                                                           const Matrix6d& Ks, const Eigen::MatrixXd& axial,
                                                           const Eigen::MatrixXd& shapes);

// What the stress state and the geometric stiffness need of the body's
// elements: the beams' section stiffness and axes, the shells' laminate.
struct StressStiffnessModel {
  const Matrix6d* Ks = nullptr;  // beams (required when the mesh has beams)
  Eigen::Vector3d section_x2 = Eigen::Vector3d::UnitY();
  const LaminateStiffness* laminate = nullptr;  // shells (required when the mesh has triangles)
  fe::ShellKind kind = fe::ShellKind::DST;
  Eigen::Vector3d material_x = Eigen::Vector3d::UnitX();
};

// Membrane resultants of every triangle (3 n_tri, n_cases): rows 3e..3e+2 are
// [N_xx N_yy N_xy] of triangle e in its laminate axes, under u (6 n, n_cases).
Eigen::MatrixXd shellMembraneForces(const Mesh& mesh, const StressStiffnessModel& model, const Eigen::MatrixXd& u);

// K_c = Phi^T K_G(N_c) Phi of the shell triangles (shell_geometric_stiffness.h)
// for each case's membrane resultants (3 n_tri, n_cases).
std::vector<Eigen::MatrixXd> projectShellGeometricStiffness(const Mesh& mesh, const StressStiffnessModel& model,
                                                            const Eigen::MatrixXd& membrane,
                                                            const Eigen::MatrixXd& shapes);

// The static response of the reference-held body (K, map) to the load cases
// (6 n, n_cases), its stress state and the projection on the shapes (6 n,
// n_modes), beams and shells summed. Returns n_cases symmetric matrices.
std::vector<Eigen::MatrixXd> loadCaseGeometricStiffness(Comm comm, const Mesh& mesh, const DofMap& map, SystemMatrix K,
                                                        const Eigen::MatrixXd& loads, const StressStiffnessModel& model,
                                                        const Eigen::MatrixXd& shapes);

// The same from static responses already solved (u: full nodal displacements,
// 6 n x n_cases, e.g. the interface unit-load responses fe-prep solves for the
// static truncation error): the stress state and the projection only.
std::vector<Eigen::MatrixXd> responseGeometricStiffness(const Mesh& mesh, const Eigen::MatrixXd& u,
                                                        const StressStiffnessModel& model, const Eigen::MatrixXd& shapes);

// The inertial cases: unit inertial loads on the lumped masses (6 n).
std::vector<Eigen::MatrixXd> modalGeometricStiffness(Comm comm, const Mesh& mesh, const DofMap& map, SystemMatrix K,
                                                     const Eigen::VectorXd& lumped, const StressStiffnessModel& model,
                                                     const Eigen::MatrixXd& shapes);

// The geometric stiffness of loads applied at an interface (joint reactions,
// force elements): the six unit cases force x, y, z and moment x, y, z in body
// axes at the interface's reference point, reaching the nodes through its
// coupling as f = L^T e_k (interfaceLoads, the same loads as static_response),
// then the same static solve, stress state and projection as the inertial
// cases. loads: (6 n, 6). Returns 6 symmetric (n_modes, n_modes) matrices.
std::vector<Eigen::MatrixXd> interfaceGeometricStiffness(Comm comm, const Mesh& mesh, const DofMap& map, SystemMatrix K,
                                                         const Eigen::MatrixXd& loads, const StressStiffnessModel& model,
                                                         const Eigen::MatrixXd& shapes);

}  // namespace fc::feprep
