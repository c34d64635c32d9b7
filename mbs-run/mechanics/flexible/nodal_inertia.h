#pragma once
// The node form of the second-order inertia terms of a reduced flexible body
// (cost linear in the modes kept). The invariants of
// common/flexbody.h carry the terms quadratic in w as nine nm x nm matrices
// S_ab = sum_k m_k Phi_k,a^T Phi_k,b: per evaluation that is O(nm^2) work and
// 6 nm^2 doubles read (2.9 MB for all nine at 200 modes: out of cache). The same
// sums taken over the lumped nodes (Shabana, Dynamics of Multibody Systems,
// 3rd ed., sec. 5.5, lumped-mass form; Exudyn's ObjectFFRFreducedOrder keeps
// the nodal mode basis the same way) cost O(r nm), r the number of nodal shape
// rows Phi_k,a that are not zero for every kept mode:
//   u_k = Phi_k w, ud_k = Phi_k wdot                          (two passes over Phi)
//   w^T S_ab   = sum_k m_k u_k,a Phi_k,b                       (the B rows)
//   w^T S_ab w = sum_k m_k u_k,a u_k,b                         (the E entries)
//   sum_{a<b} 2 omega~_ab (S_ab - S_ab^T) wdot
//              = sum_k m_k Phi_k^T (2 omega~ ud_k)              (the Coriolis rows)
// Both forms are the same sums in another order: identical to rounding
// (tests/mbs-run/flexible/test_nodal_inertia.cpp). Which one a body uses is
// decided once at load time by the measured cost of each (nodalFormCheaper,
// docs/benchmarks.md "Modes kept").
#include <Eigen/Dense>
#include <array>

#include "common/flexbody.h"

namespace fc::mbs {

struct NodalInertia {
  int n_modes = 0;
  int n_nodes = 0;
  Eigen::VectorXd mass;                      // (n_nodes) lumped masses m_k
  std::array<Eigen::MatrixXd, 3> shapes;     // [b] (nm, r_b): column i = Phi_k,b^T, k = node[b][i]
  std::array<Eigen::VectorXi, 3> node;       // [b] (r_b) node of each column
  long rows() const { return shapes[0].cols() + shapes[1].cols() + shapes[2].cols(); }
};

// The node form of `body`'s first n_modes modes (body.shapes and nodal_mass
// must hold them: readFlexBody with FlexBodyParts::All). Rows of nodes without
// mass and rows that vanish for every kept mode are left out (exactly zero
// terms of the sums).
NodalInertia nodalInertia(const FlexBody& body, int n_modes);

// The measured per-evaluation cost model: true when the node form of a body
// with `rows` nonzero nodal rows is cheaper than the nm x nm invariants.
bool nodalFormCheaper(long rows, int n_modes);

// The second-order sums of the header, added to what the caller holds:
// B (9, nm) row 3a+b += w^T S_ab; E (3x3) (a,b) += w^T S_ab w; and, when
// coriolis is not null, *coriolis (nm) += sum_k m_k Phi_k^T (2 omega~ ud_k).
void addNodalSecondOrder(const NodalInertia& n, const Eigen::VectorXd& w, const Eigen::VectorXd* wdot,
                         const Eigen::Vector3d& omega, Eigen::MatrixXd& B, Eigen::Matrix3d& E,
                         Eigen::VectorXd* coriolis);

}  // namespace fc::mbs
