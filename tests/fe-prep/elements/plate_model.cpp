#include "plate_model.h"

#include <cmath>
#include <stdexcept>

namespace fc::fe::test {

PlateMesh rectangleMesh(double a, double b, int nx, int ny) {
  PlateMesh m;
  m.nx = nx;
  m.ny = ny;
  m.a = a;
  m.b = b;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.nodes.emplace_back(a * i / nx, b * j / ny, 0.0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int n00 = m.node(i, j), n10 = m.node(i + 1, j), n01 = m.node(i, j + 1),
                n11 = m.node(i + 1, j + 1);
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({n00, n10, n11});
        m.triangles.push_back({n00, n11, n01});
      } else {
        m.triangles.push_back({n00, n10, n01});
        m.triangles.push_back({n10, n11, n01});
      }
    }
  }
  return m;
}

Assembled assembleShell(const PlateMesh& mesh, const LaminateStiffness& lam, ShellKind kind,
                        bool lumped, double drilling, const Eigen::Vector3d& material_x) {
  const int n = 6 * static_cast<int>(mesh.nodes.size());
  Assembled s{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  for (const auto& t : mesh.triangles) {
    Eigen::Matrix3d xyz;
    for (int i = 0; i < 3; ++i) xyz.row(i) = mesh.nodes[t[i]].transpose();
    const ShellMatrices e = shellTriangle(xyz, lam, kind, material_x, drilling);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        s.K.block<6, 6>(6 * t[i], 6 * t[j]) += e.K.block<6, 6>(6 * i, 6 * j);
        if (!lumped) s.M.block<6, 6>(6 * t[i], 6 * t[j]) += e.M.block<6, 6>(6 * i, 6 * j);
      }
    if (lumped)
      for (int i = 0; i < 3; ++i)
        for (int d = 0; d < 6; ++d) s.M(6 * t[i] + d, 6 * t[i] + d) += e.lumped(6 * i + d);
  }
  return s;
}

Eigen::VectorXd eigenvalues(const Assembled& sys, const std::vector<int>& keep) {
  const int m = static_cast<int>(keep.size());
  Eigen::MatrixXd K(m, m), M(m, m);
  for (int r = 0; r < m; ++r)
    for (int c = 0; c < m; ++c) {
      K(r, c) = sys.K(keep[r], keep[c]);
      M(r, c) = sys.M(keep[r], keep[c]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) throw std::runtime_error("eigen solver failed");
  return es.eigenvalues();
}

std::vector<int> plateBendingDofs(const PlateMesh& mesh, char support) {
  std::vector<int> keep;
  for (int j = 0; j <= mesh.ny; ++j) {
    for (int i = 0; i <= mesh.nx; ++i) {
      const int n = mesh.node(i, j);
      bool w = true, tx = true, ty = true;
      if (support == 'S') {
        const bool xedge = (i == 0 || i == mesh.nx), yedge = (j == 0 || j == mesh.ny);
        if (xedge || yedge) w = false;
        // On x = const the Navier field has beta_y = -theta_x = 0 (no tilt along
        // the edge); on y = const beta_x = theta_y = 0.
        if (xedge) tx = false;
        if (yedge) ty = false;
      } else if (support == 'A') {
        if (i == 0 || i == mesh.nx || j == 0 || j == mesh.ny) w = tx = ty = false;
      } else if (support == 'C') {
        if (i == 0) w = tx = ty = false;
      } else {
        throw std::invalid_argument("unknown support");
      }
      if (w) keep.push_back(6 * n + 2);
      if (tx) keep.push_back(6 * n + 3);
      if (ty) keep.push_back(6 * n + 4);
    }
  }
  return keep;
}

std::vector<double> lowestOmegasSparse(const PlateMesh& mesh, const LaminateStiffness& lam,
                                       ShellKind kind, const std::vector<int>& keep, int count) {
  const int n = 6 * static_cast<int>(mesh.nodes.size()), m = static_cast<int>(keep.size());
  std::vector<int> reduced(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < m; ++k) reduced[static_cast<std::size_t>(keep[static_cast<std::size_t>(k)])] = k;
  std::vector<Eigen::Triplet<double>> kt, mt;
  for (const auto& t : mesh.triangles) {
    Eigen::Matrix3d xyz;
    for (int i = 0; i < 3; ++i) xyz.row(i) = mesh.nodes[t[i]].transpose();
    const ShellMatrices e = shellTriangle(xyz, lam, kind, Eigen::Vector3d::UnitX());
    for (int r = 0; r < 18; ++r)
      for (int c = 0; c < 18; ++c) {
        const int R = reduced[static_cast<std::size_t>(6 * t[r / 6] + r % 6)],
                  C = reduced[static_cast<std::size_t>(6 * t[c / 6] + c % 6)];
        if (R < 0 || C < 0) continue;
        kt.emplace_back(R, C, e.K(r, c));
        mt.emplace_back(R, C, e.M(r, c));
      }
  }
  Eigen::SparseMatrix<double> K(m, m), M(m, m);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(K);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("sparse K not factorised");
  const int block = 2 * count + 4;
  Eigen::MatrixXd X = Eigen::MatrixXd::Ones(m, block);
  for (int c = 0; c < block; ++c)
    for (int r = 0; r < m; ++r) X(r, c) = std::sin(0.7 * (r + 1) * (c + 1) + 0.3 * c);
  Eigen::VectorXd previous = Eigen::VectorXd::Zero(block);
  for (int it = 0; it < 500; ++it) {
    const Eigen::MatrixXd Y = ldlt.solve(M * X);
    const Eigen::MatrixXd Ks = Y.transpose() * (K * Y), Ms = Y.transpose() * (M * Y);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ks, Ms);
    X = Y * es.eigenvectors();
    const Eigen::VectorXd lam_now = es.eigenvalues();
    const double change =
        ((lam_now.head(count) - previous.head(count)).array().abs() / lam_now.head(count).array()).maxCoeff();
    previous = lam_now;
    if (it > 3 && change < 1e-12) {
      std::vector<double> w;
      for (int i = 0; i < count; ++i) w.push_back(std::sqrt(lam_now(i)));
      return w;
    }
  }
  throw std::runtime_error("subspace iteration did not converge");
}

}  // namespace fc::fe::test
