#include "mbs-run/mechanics/flexible/nodal_inertia.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "common/rotations.h"

namespace fc::mbs {

NodalInertia nodalInertia(const FlexBody& body, int n_modes) {
  const long n = body.nodeCount();
  if (n_modes < 0 || n_modes > body.shapes.cols() || body.shapes.rows() != 6 * n || body.nodal_mass.rows() != n)
    throw std::invalid_argument("flexible body '" + body.name + "': the node form needs the nodal masses and " +
                                std::to_string(n_modes) + " nodal mode shapes of its " + std::to_string(n) + " nodes");
  NodalInertia ni;
  ni.n_modes = n_modes;
  ni.n_nodes = static_cast<int>(n);
  ni.mass = body.nodal_mass.col(0);
  for (int b = 0; b < 3; ++b) {
    std::vector<int> keep;
    for (long k = 0; k < n; ++k)
      if (ni.mass(k) != 0.0 && n_modes > 0 && body.shapes.row(6 * k + b).head(n_modes).cwiseAbs().maxCoeff() > 0.0)
        keep.push_back(static_cast<int>(k));
    ni.node[b].resize(static_cast<Eigen::Index>(keep.size()));
    ni.shapes[b].resize(n_modes, static_cast<Eigen::Index>(keep.size()));
    for (std::size_t i = 0; i < keep.size(); ++i) {
      ni.node[b](static_cast<Eigen::Index>(i)) = keep[i];
      ni.shapes[b].col(static_cast<Eigen::Index>(i)) = body.shapes.row(6 * keep[i] + b).head(n_modes).transpose();
    }
  }
  return ni;
}

bool nodalFormCheaper(long rows, int n_modes) {
  // Per evaluation the invariant form reads the six S_ab (a <= b) once for B
  // and E and the off-diagonal ones once more for the Coriolis rows: up to
  // 9 nm^2 multiply-adds; the node form makes two passes over its r x nm
  // shape rows (u and ud; then B and the Coriolis rows, 4 columns): 6 r nm.
  // Measured (bench_integrators N and AE, docs/benchmarks.md "Modes kept"):
  // from 64 modes the node form costs 0.6-0.75 of the invariants' at
  // 6 r = 9 nm and breaks even near 6 r = 13 nm; at 16 modes both are in
  // cache and the node form's fixed overhead (node tables, three axes) makes
  // it 5-7 % slower even at 6 r = 7.5 nm. Hence the node form from 32 modes
  // on, when it does fewer multiply-adds.
  return n_modes >= 32 && 6 * rows < 9L * n_modes;
}

void addNodalSecondOrder(const NodalInertia& ni, const Eigen::VectorXd& w, const Eigen::VectorXd* wdot,
                         const Eigen::Vector3d& omega, Eigen::MatrixXd& B, Eigen::Matrix3d& E,
                         Eigen::VectorXd* coriolis) {
  const int nm = ni.n_modes;
  if (w.size() != nm || (wdot && wdot->size() != nm))
    throw std::invalid_argument("flexible body: modal coordinates of size " + std::to_string(w.size()) +
                                " for a node form of " + std::to_string(nm) + " modes");
  const bool rates = wdot && coriolis;
  const int nc = rates ? 2 : 1;
  // Pass 1: nodal displacements (and rates) u_k,b = Phi_k,b w, scattered to
  // a node table so that every axis sees the node's three components.
  Eigen::MatrixXd x(nm, nc);
  x.col(0) = w;
  if (rates) x.col(1) = *wdot;
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(ni.n_nodes, 3), Ud;
  if (rates) Ud.setZero(ni.n_nodes, 3);
  for (int b = 0; b < 3; ++b) {
    if (ni.node[b].size() == 0) continue;
    const Eigen::MatrixXd ub = ni.shapes[b].transpose() * x;
    for (Eigen::Index i = 0; i < ub.rows(); ++i) {
      U(ni.node[b](i), b) = ub(i, 0);
      if (rates) Ud(ni.node[b](i), b) = ub(i, 1);
    }
  }
  E.noalias() += U.transpose() * ni.mass.asDiagonal() * U;
  // Pass 2: per axis b, [sum m_k u_k,a Phi_k,b]_a and sum m_k (2 omega~ ud_k)_b Phi_k,b.
  const Eigen::Matrix3d W2 = 2.0 * skew(omega);
  for (int b = 0; b < 3; ++b) {
    const Eigen::Index r = ni.node[b].size();
    if (r == 0) continue;
    Eigen::MatrixXd V(r, rates ? 4 : 3);
    for (Eigen::Index i = 0; i < r; ++i) {
      const int k = ni.node[b](i);
      const double m = ni.mass(k);
      V.block<1, 3>(i, 0) = m * U.row(k);
      if (rates) V(i, 3) = m * W2.row(b).dot(Ud.row(k));
    }
    const Eigen::MatrixXd R = ni.shapes[b] * V;  // (nm, 3 or 4)
    for (int a = 0; a < 3; ++a) B.row(3 * a + b) += R.col(a).transpose();
    if (rates) *coriolis += R.col(3);
  }
}

}  // namespace fc::mbs
