#pragma once
// Two-node 3-D Timoshenko beam with a fully coupled 6x6 cross-section stiffness
// (as section-prep computes it, VABS order [extension, shear x2, shear x3,
// torsion, bending about x2, bending about x3]) and 6x6 section mass matrix.
// Degrees of freedom, 6 per node, in the BODY frame: [u1 u2 u3 theta1 theta2 theta3].
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "common/materials.h"

namespace fc::fe {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

struct BeamMatrices {
  Matrix12d K;       // stiffness
  Matrix12d M;       // consistent mass
  Vector12d lumped;  // diagonal (lumped) mass: 3 translational + 3 rotary per node
};

// The element's section axes as rows e1 (xa to xb), e2 (section_x2 orthogonalised),
// e3 = e1 x e2, so that v_local = R v_body; L returns the length. Throws on
// coincident nodes or a section_x2 parallel to the axis.
Eigen::Matrix3d beamSectionAxes(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                                const Eigen::Vector3d& section_x2, double& L);

// R on each of the four 3-vectors of the 12 nodal DOF (u_a, theta_a, u_b, theta_b).
Matrix12d beamBlockRotation(const Eigen::Matrix3d& R);

// xa, xb: end nodes (body frame); section_x2: direction of the section's x2 axis
// (any vector not parallel to the beam; it is orthogonalised). Ks, Ms: section
// stiffness and mass per unit length about the section origin on the beam axis.
BeamMatrices timoshenkoBeam(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                            const Eigen::Vector3d& section_x2, const Matrix6d& Ks,
                            const Matrix6d& Ms);

// Section resultants at the element midpoint, [N, V2, V3, T, M2, M3] in the
// element's section axes (x1 from xa to xb, x2 = section_x2 orthogonalised,
// x3 = x1 x x2), as a linear map of the 12 body-frame nodal DOF (node a then b,
// [u1 u2 u3 theta1 theta2 theta3] each). The element's own equilibrium carries
// the end load its stiffness implies to the midpoint (UniformBeam::sectionForces),
// so they are exact for loads applied at the nodes; rigid motions give zero.
Eigen::Matrix<double, 6, 12> beamMidpointResultants(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                                                    const Eigen::Vector3d& section_x2, const Matrix6d& Ks);

// The midpoint resultants of every beam element for every mode: nodes
// (n_nodes, 3), shapes (6 n_nodes, n_modes) node-major as FlexBody::shapes.
// Returns (6 n_beams, n_modes): row 6e + c is component c of element e per unit
// modal coordinate (what fe-prep writes to /stress/section_resultants).
Eigen::MatrixXd beamModalResultants(const Eigen::MatrixXd& nodes, const std::vector<std::array<long, 2>>& beams,
                                    const Eigen::Vector3d& section_x2, const Matrix6d& Ks,
                                    const Eigen::MatrixXd& shapes);

}  // namespace fc::fe
