#include "fe-prep/ritz_basis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace fc::feprep {

namespace {

// Columns of V (an orthonormal eigenvector matrix) whose eigenvalue is above / below `cut`.
void split(const Eigen::VectorXd& ev, const Eigen::MatrixXd& V, double cut, Eigen::MatrixXd& above, Eigen::MatrixXd& below) {
  std::vector<long> a, b;
  for (long k = 0; k < ev.size(); ++k) (ev(k) > cut ? a : b).push_back(k);
  above.resize(V.rows(), static_cast<long>(a.size()));
  below.resize(V.rows(), static_cast<long>(b.size()));
  for (std::size_t k = 0; k < a.size(); ++k) above.col(static_cast<long>(k)) = V.col(a[k]);
  for (std::size_t k = 0; k < b.size(); ++k) below.col(static_cast<long>(k)) = V.col(b[k]);
}

}  // namespace

RitzSolution ritzEigen(const Eigen::MatrixXd& Kr_in, const Eigen::MatrixXd& Mr_in, double tol) {
  const long m = Kr_in.rows();
  const Eigen::MatrixXd Kr = 0.5 * (Kr_in + Kr_in.transpose()), Mr = 0.5 * (Mr_in + Mr_in.transpose());
  // Scaling: s_j = 1 / sqrt(m_jj / m_max + k_jj / k_max); a column with neither is a zero vector.
  const double mmax = std::max(Mr.diagonal().maxCoeff(), 1e-300), kmax = std::max(Kr.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  Eigen::VectorXd s(m);
  for (long j = 0; j < m; ++j) {
    const double w = Mr(j, j) / mmax + std::abs(Kr(j, j)) / kmax;
    s(j) = w > tol ? 1.0 / std::sqrt(w) : 0.0;
  }
  const Eigen::MatrixXd Ms = s.asDiagonal() * Mr * s.asDiagonal(), Ks = s.asDiagonal() * Kr * s.asDiagonal();
  RitzSolution out;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> em(Ms);
  Eigen::MatrixXd Y, Z;
  split(em.eigenvalues(), em.eigenvectors(), tol * std::max(em.eigenvalues().maxCoeff(), 1e-300), Y, Z);
  Eigen::MatrixXd T = Y;  // the coordinates kept, in the scaled basis
  if (Z.cols() > 0) {
    const Eigen::MatrixXd Kzz = Z.transpose() * Ks * Z;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ek(0.5 * (Kzz + Kzz.transpose()));
    Eigen::MatrixXd U, dropped;
    split(ek.eigenvalues(), ek.eigenvectors(), tol * std::max(Ks.diagonal().cwiseAbs().maxCoeff(), 1e-300), U, dropped);
    out.massless = U.cols();
    out.dependent = dropped.cols();
    if (U.cols() > 0) {
      const Eigen::MatrixXd Zs = Z * U;
      const Eigen::MatrixXd kzz = Zs.transpose() * Ks * Zs;
      T = Y - Zs * kzz.ldlt().solve(Zs.transpose() * Ks * Y);
    }
  }
  if (T.cols() == 0) throw std::runtime_error("the Ritz basis carries no mass");
  Eigen::MatrixXd Kt = T.transpose() * Ks * T, Mt = T.transpose() * Ms * T;
  Kt = 0.5 * (Kt + Kt.transpose()).eval();
  Mt = 0.5 * (Mt + Mt.transpose()).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kt, Mt);
  if (es.info() != Eigen::Success) throw std::runtime_error("the reduced eigenproblem of the Ritz basis failed");
  out.eigenvalues = es.eigenvalues();
  out.X = s.asDiagonal() * T * es.eigenvectors();
  return out;
}

}  // namespace fc::feprep
