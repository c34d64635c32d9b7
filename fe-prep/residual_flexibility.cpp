#include "fe-prep/residual_flexibility.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "fe-prep/ritz_basis.h"

namespace fc::feprep {

Eigen::MatrixXd residualVectors(const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& A, const Eigen::MatrixXd& MA) {
  return A - Phi * (Phi.transpose() * MA);
}

AugmentedBasis augmentBasis(const Eigen::MatrixXd& Phi, const Eigen::VectorXd& lambda, const Eigen::MatrixXd& R,
                            const Eigen::MatrixXd& KR, const Eigen::MatrixXd& MR, const Eigen::VectorXd& KA_diag) {
  const long n = Phi.cols(), m = R.cols();
  AugmentedBasis out;
  const double lref = n > 0 ? std::max(lambda.maxCoeff(), 1e-300) : 1.0;
  std::vector<long> keep;
  Eigen::VectorXd scale(m);
  for (long j = 0; j < m; ++j) {
    const double e = R.col(j).dot(KR.col(j));
    if (!(e > 1e-12 * KA_diag(j))) {
      ++out.in_span;
      continue;
    }
    keep.push_back(j);
    scale(j) = std::sqrt(lref / e);
  }
  const long mk = static_cast<long>(keep.size());
  Eigen::MatrixXd Rs(R.rows(), mk), KRs(R.rows(), mk), MRs(R.rows(), mk);
  for (long i = 0; i < mk; ++i) {
    const long j = keep[static_cast<std::size_t>(i)];
    Rs.col(i) = scale(j) * R.col(j);
    KRs.col(i) = scale(j) * KR.col(j);
    MRs.col(i) = scale(j) * MR.col(j);
  }
  // Reduced matrices of [Phi Rs]; the mode-mode block is Lambda and I by
  // construction, the mode-residual blocks vanish up to rounding (kept, not
  // assumed).
  Eigen::MatrixXd Kb = Eigen::MatrixXd::Zero(n + mk, n + mk), Mb = Kb;
  Kb.topLeftCorner(n, n) = lambda.asDiagonal();
  Mb.topLeftCorner(n, n).setIdentity();
  Kb.topRightCorner(n, mk) = Phi.transpose() * KRs;
  Mb.topRightCorner(n, mk) = Phi.transpose() * MRs;
  Kb.bottomLeftCorner(mk, n) = Kb.topRightCorner(n, mk).transpose();
  Mb.bottomLeftCorner(mk, n) = Mb.topRightCorner(n, mk).transpose();
  Kb.bottomRightCorner(mk, mk) = Rs.transpose() * KRs;
  Mb.bottomRightCorner(mk, mk) = Rs.transpose() * MRs;
  const RitzSolution s = ritzEigen(Kb, Mb);
  out.dependent = s.dependent;
  out.massless = s.massless;
  out.eigenvalues = s.eigenvalues;
  // Back to the unscaled residual columns (dropped ones get zero rows).
  out.coefficients = Eigen::MatrixXd::Zero(n + m, s.X.cols());
  out.coefficients.topRows(n) = s.X.topRows(n);
  for (long i = 0; i < mk; ++i) {
    const long j = keep[static_cast<std::size_t>(i)];
    out.coefficients.row(n + j) = scale(j) * s.X.row(n + i);
  }
  return out;
}

}  // namespace fc::feprep
