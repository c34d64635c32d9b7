#include "fe-prep/craig_bampton.h"

#include "fe-prep/static_response.h"

#include "fe-prep/petsc_handles.h"
#include "fe-prep/ritz_basis.h"

#include <stdexcept>
#include <string>

namespace fc::feprep {

void appendLifts(long n_nodes, const std::vector<long>& nodes, const Eigen::MatrixXd& C, std::vector<Eigen::VectorXd>& lifts) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  for (long k = 0; k < s.size(); ++k) {
    if (s(k) <= 1e-10 * s(0)) break;
    // The k-th independent boundary combination: C l = u_k, l = v_k / s_k.
    const Eigen::VectorXd l = svd.matrixV().col(k) / s(k);
    Eigen::VectorXd full = Eigen::VectorXd::Zero(6 * n_nodes);
    for (std::size_t i = 0; i < nodes.size(); ++i) full.segment<6>(6 * nodes[i]) = l.segment<6>(6 * static_cast<long>(i));
    lifts.push_back(full);
  }
}

CraigBamptonResult craigBampton(MPI_Comm comm, const CraigBamptonInput& in) {
  const long nb = in.lifts.cols(), nk = in.normal.cols(), N = in.lifts.rows();
  CraigBamptonResult out;
  // Constraint modes: one factorisation of the fixed-interface K, nb solves.
  out.constraint_modes.resize(N, nb);
  {
    OwnedKsp ksp = choleskySolver(comm, in.K_fixed);
    OwnedVec b, x;
    check(MatCreateVecs(in.K_fixed, &x, &b), "MatCreateVecs");
    for (long j = 0; j < nb; ++j) {
      setLocal(b, -reduceForce(*in.fixed, in.K_lifts.col(j)));
      check(KSPSolve(ksp, b, x), "KSPSolve");
      KSPConvergedReason why;
      check(KSPGetConvergedReason(ksp, &why), "KSPGetConvergedReason");
      if (why < 0)
        throw std::runtime_error("craig_bampton: the fixed-interface stiffness is singular (the reference leaves "
                                 "rigid motions free: clamp the boundary interfaces, or pin at least three)");
      out.constraint_modes.col(j) = in.lifts.col(j) + in.fixed->expand(gatherAll(x));
    }
  }
  // The basis in the free body's DOF, the reduced matrices, their eigenvectors.
  Eigen::MatrixXd B(N, nb + nk);
  B << out.constraint_modes, in.normal;
  Eigen::MatrixXd Bf(in.free->reduced, nb + nk), KB(in.free->reduced, nb + nk), MB(in.free->reduced, nb + nk);
  for (long j = 0; j < nb + nk; ++j) {
    Bf.col(j) = in.free->restrict(B.col(j));
    KB.col(j) = multiply(in.K_free, Bf.col(j));
    MB.col(j) = multiply(in.M_free, Bf.col(j));
  }
  // Massless boundary DOF (a clamped shell node's drilling rotation) are
  // condensed, dependent vectors dropped (ritz_basis.h).
  const RitzSolution es = ritzEigen(Bf.transpose() * KB, Bf.transpose() * MB);
  out.massless_condensed = es.massless;
  // Rigid share of each eigenvector: b^T G^-1 b, b = R^T M (B x), G = R^T M R.
  const long r = in.rigid.cols();
  Eigen::MatrixXd MRf(in.free->reduced, r), Rf(in.free->reduced, r);
  for (long j = 0; j < r; ++j) {
    Rf.col(j) = in.free->restrict(in.rigid.col(j));
    MRf.col(j) = multiply(in.M_free, Rf.col(j));
  }
  const Eigen::MatrixXd G = Rf.transpose() * MRf;
  const Eigen::MatrixXd Ginv = G.ldlt().solve(Eigen::MatrixXd::Identity(r, r));
  const Eigen::MatrixXd& X = es.X;  // X^T Mr X = I
  const Eigen::MatrixXd BtMR = Bf.transpose() * MRf;  // (nb + nk, r)
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
