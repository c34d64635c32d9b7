#include "fe-prep/craig_bampton.h"

#include "fe-prep/static_response.h"

#include "fe-prep/ritz_basis.h"

#include <stdexcept>
#include <string>

namespace fc::feprep {

void appendLifts(const std::vector<long>& nodes, const Eigen::MatrixXd& C, std::vector<Lift>& lifts) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  for (long k = 0; k < s.size(); ++k) {
    if (s(k) <= 1e-10 * s(0)) break;
    // The k-th independent boundary combination: C l = u_k, l = v_k / s_k.
    const Eigen::VectorXd l = svd.matrixV().col(k) / s(k);
    Lift lift;
    for (std::size_t i = 0; i < nodes.size(); ++i) lift[nodes[i]] = l.segment<6>(6 * static_cast<long>(i));
    lifts.push_back(std::move(lift));
  }
}

NodeRows liftRows(const std::vector<Lift>& lifts) {
  NodeRows rows;
  const long nb = static_cast<long>(lifts.size());
  for (long j = 0; j < nb; ++j)
    for (const auto& [node, v] : lifts[static_cast<std::size_t>(j)]) {
      auto it = rows.find(node);
      if (it == rows.end()) it = rows.emplace(node, Eigen::MatrixXd::Zero(6, nb)).first;
      it->second.col(j) = v;
    }
  return rows;
}

namespace {

// The free map keeps every node's six DOF as they are (no coupling, no held
// rotation): restrict() is then the identity, and B serves as its own restriction.
bool isIdentity(const DofMap& map, long N) {
  if (map.reduced != N) return false;
  for (std::size_t i = 0; i < map.own.size(); ++i)
    if (map.offset[i] != 6 * static_cast<long>(i) || map.own[i].rows() != 6 || !map.own[i].isIdentity(0.0)) return false;
  return true;
}

}  // namespace

CraigBamptonResult craigBampton(Comm comm, CraigBamptonBasis basis, SystemMatrix K_free, SystemMatrix M_free, const DofMap& free,
                                const Eigen::MatrixXd& rigid) {
  (void)comm;  // the products are the backend's, on K_free's communicator (PETSc) or none (serial)
  const Eigen::MatrixXd& B = basis.B;
  const long N = B.rows(), m = B.cols(), nk = m - basis.n_boundary;
  CraigBamptonResult out;
  // The basis in the free body's DOF (B itself when that map is the identity).
  Eigen::MatrixXd Bf_own;
  if (!isIdentity(free, N)) {
    Bf_own.resize(free.reduced, m);
    for (long j = 0; j < m; ++j) Bf_own.col(j) = free.restrict(B.col(j));
  }
  const Eigen::MatrixXd& Bf = isIdentity(free, N) ? B : Bf_own;
  // K_r and M_r through one work block: K Bf, then M Bf.
  Eigen::MatrixXd Kr, Mr;
  {
    Eigen::MatrixXd W(free.reduced, m);
    for (long j = 0; j < m; ++j) W.col(j) = multiply(K_free, Bf.col(j));
    Kr = Bf.transpose() * W;
    for (long j = 0; j < m; ++j) W.col(j) = multiply(M_free, Bf.col(j));
    Mr = Bf.transpose() * W;
  }
  // Massless boundary DOF (a clamped shell node's drilling rotation) are
  // condensed, dependent vectors dropped (ritz_basis.h).
  const RitzSolution es = ritzEigen(Kr, Mr);
  out.massless_condensed = es.massless;
  // Rigid share of each eigenvector: b^T G^-1 b, b = R^T M (B x), G = R^T M R.
  const long r = rigid.cols();
  Eigen::MatrixXd MRf(free.reduced, r), Rf(free.reduced, r);
  for (long j = 0; j < r; ++j) {
    Rf.col(j) = free.restrict(rigid.col(j));
    MRf.col(j) = multiply(M_free, Rf.col(j));
  }
  const Eigen::MatrixXd G = Rf.transpose() * MRf;
  const Eigen::MatrixXd Ginv = G.ldlt().solve(Eigen::MatrixXd::Identity(r, r));
  const Eigen::MatrixXd& X = es.X;  // X^T Mr X = I
  const Eigen::MatrixXd BtMR = Bf.transpose() * MRf;  // (nb + nk, r)
  Bf_own.resize(0, 0);
  std::vector<long> kept;
  std::vector<double> removed;
  for (long k = 0; k < X.cols(); ++k) {
    const Eigen::VectorXd bk = BtMR.transpose() * X.col(k);
    const double share = bk.dot(Ginv * bk);
    if (share > 0.5) {
      removed.push_back(es.eigenvalues(k));
      out.rigid_share_removed_min = std::min(out.rigid_share_removed_min, share);
    } else {
      kept.push_back(k);
      out.rigid_share_kept_max = std::max(out.rigid_share_kept_max, share);
    }
  }
  out.eigenvalues.resize(static_cast<long>(kept.size()));
  out.shapes.resize(N, static_cast<long>(kept.size()));
  out.fixed_interface_coordinates.resize(static_cast<long>(kept.size()), nk);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    out.eigenvalues(static_cast<long>(i)) = es.eigenvalues(kept[i]);
    Eigen::VectorXd x = B * X.col(kept[i]);
    Eigen::Index imax;
    x.cwiseAbs().maxCoeff(&imax);
    const double sign = x(imax) < 0 ? -1.0 : 1.0;  // the modal solver's sign convention
    out.shapes.col(static_cast<long>(i)) = sign * x;
    out.fixed_interface_coordinates.row(static_cast<long>(i)) = sign * X.col(kept[i]).tail(nk).transpose();
  }
  out.rigid_eigenvalues = Eigen::Map<const Eigen::VectorXd>(removed.data(), static_cast<long>(removed.size()));
  return out;
}

}  // namespace fc::feprep
