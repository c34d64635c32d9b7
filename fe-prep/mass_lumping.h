#pragma once
// Moment-consistent lumped masses. Row-sum lumping (each element's mass split
// equally among its nodes) keeps the mass and, for linear elements, the first
// moment exact, but overestimates the second moments: +8 % on Ixx for the
// paper's 86-triangle SAR panel, +50 % on the bending inertia of a two-element
// truss (nodes at -L/2, 0, L/2 with L/4, L/2, L/4 of the mass give m L^2/8
// instead of m L^2/12). mbs-run takes the body's whole inertia from the nodal
// masses (common/flexbody.h invariants), so fe-prep moves the smallest amount of
// mass between nodes that makes the zeroth, first and second moments exact:
//   minimise sum_k (m_k - m0_k)^2 / m0_k  subject to  C m = b,
// C the monomials 1, x, y, z, xx, yy, zz, xy, xz, yz at the nodes and b their
// exact integrals. Lagrange: m = m0 + diag(m0) C^T lambda with
// (C diag(m0) C^T) lambda = b - C m0 (pseudo-inverse: coplanar or collinear
// nodes make rows dependent, and their targets are then consistent by symmetry).
// For two beam elements this is Simpson's rule (L/6, 2L/3, L/6).
#include <Eigen/Dense>

namespace fc::feprep {

struct MomentLumping {
  Eigen::VectorXd masses;   // corrected nodal masses
  double min_ratio = 1.0;   // min m_k / m0_k
  double residual = 0.0;    // relative misfit of the moment equations after correction
  bool applied = false;     // false: the correction would leave a mass below 10 % of m0 (kept m0)
};

// X: (n, 3) node positions; m0: row-sum lumped masses; exact mass, first moment
// (3) and second moment E = int rho x x^T of the translational mass distribution.
MomentLumping momentConsistentMasses(const Eigen::MatrixXd& X, const Eigen::VectorXd& m0, double mass,
                                     const Eigen::Vector3d& first, const Eigen::Matrix3d& second);

}  // namespace fc::feprep
