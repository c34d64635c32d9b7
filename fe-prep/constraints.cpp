#include "fe-prep/constraints.h"

#include <algorithm>
#include <map>

namespace fc::feprep {

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

namespace {

// Orthonormal null-space basis of C (m x 6) with a relative rank tolerance.
// Rotation columns are scaled by `length` so that translations and rotations
// weigh alike in the rank decision.
Eigen::MatrixXd nullSpace(const Eigen::MatrixXd& C, double length) {
  Eigen::Matrix<double, 6, 6> S = Eigen::Matrix<double, 6, 6>::Identity();
  S.bottomRightCorner<3, 3>() /= length;
  const Eigen::MatrixXd Cs = C * S;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Cs, Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  const double tol = 1e-10 * std::max(1.0, sv.size() ? sv(0) : 1.0);
  int rank = 0;
  for (int i = 0; i < sv.size(); ++i) rank += sv(i) > tol ? 1 : 0;
  Eigen::MatrixXd N = S * svd.matrixV().rightCols(6 - rank);
  // Back in unscaled variables, re-orthonormalise (QR keeps the span).
  if (N.cols() > 0) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(N);
    N = qr.householderQ() * Eigen::MatrixXd::Identity(6, N.cols());
  }
  return N;
}

// Rows [I, -skew(d)] (pin) and [0, I] (clamp) on a node's DOF.
Eigen::MatrixXd conditionRows(const PointConstraint& c, const Eigen::Vector3d& d) {
  Eigen::MatrixXd C(c.clamp ? 6 : 3, 6);
  C.setZero();
  C.topLeftCorner<3, 3>().setIdentity();
  C.topRightCorner<3, 3>() = -skew(d);
  if (c.clamp) C.bottomRightCorner<3, 3>().setIdentity();
  return C;
}

}  // namespace

DofMap buildDofMap(const Mesh& mesh, const std::vector<PointConstraint>& constraints) {
  const long n = mesh.nodeCount();
  const double length = std::max(mesh.characteristicLength(), 1e-12);
  std::map<long, Eigen::MatrixXd> rows;
  for (const auto& c : constraints) {
    const Eigen::Vector3d d = c.point - mesh.nodes.row(c.node).transpose();
    Eigen::MatrixXd C = conditionRows(c, d);
    auto it = rows.find(c.node);
    if (it == rows.end()) {
      rows.emplace(c.node, C);
    } else {
      Eigen::MatrixXd S(it->second.rows() + C.rows(), 6);
      S << it->second, C;
      it->second = S;
    }
  }
  DofMap map;
  map.T.resize(static_cast<std::size_t>(n));
  map.offset.resize(static_cast<std::size_t>(n));
  map.unconstrained.assign(static_cast<std::size_t>(n), 0);
  long next = 0;
  for (long i = 0; i < n; ++i) {
    auto it = rows.find(i);
    Eigen::MatrixXd T;
    if (it == rows.end()) {
      T = Eigen::MatrixXd::Identity(6, 6);
      map.unconstrained[static_cast<std::size_t>(i)] = 1;
    } else if (it->second.rows() == 3 && it->second.topRightCorner(3, 3).norm() == 0.0) {
      // A pin on the node itself: exactly the three rotations (no SVD round-off).
      T = Eigen::MatrixXd::Zero(6, 3);
      T.bottomRows(3).setIdentity();
    } else {
      T = nullSpace(it->second, length);
    }
    map.offset[static_cast<std::size_t>(i)] = next;
    next += T.cols();
    map.T[static_cast<std::size_t>(i)] = std::move(T);
  }
  map.reduced = next;
  return map;
}

Eigen::VectorXd DofMap::expand(const Eigen::VectorXd& r) const {
  const long n = static_cast<long>(T.size());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6 * n);
  for (long i = 0; i < n; ++i) {
    const auto& Ti = T[static_cast<std::size_t>(i)];
    if (Ti.cols() == 0) continue;
    q.segment<6>(6 * i) = Ti * r.segment(offset[static_cast<std::size_t>(i)], Ti.cols());
  }
  return q;
}

Eigen::VectorXd DofMap::restrict(const Eigen::VectorXd& q) const {
  Eigen::VectorXd r(reduced);
  const long n = static_cast<long>(T.size());
  for (long i = 0; i < n; ++i) {
    const auto& Ti = T[static_cast<std::size_t>(i)];
    if (Ti.cols() == 0) continue;
    r.segment(offset[static_cast<std::size_t>(i)], Ti.cols()) = Ti.transpose() * q.segment<6>(6 * i);
  }
  return r;
}

Eigen::MatrixXd admissibleRigidModes(const Mesh& mesh, const std::vector<PointConstraint>& constraints) {
  const double length = std::max(mesh.characteristicLength(), 1e-12);
  Eigen::MatrixXd C(0, 6);
  for (const auto& c : constraints) {
    // Rigid motion (t, omega) seen at P: t + omega x P; a clamp also needs omega = 0.
    const Eigen::MatrixXd rows = conditionRows(c, c.point);
    Eigen::MatrixXd S(C.rows() + rows.rows(), 6);
    S << C, rows;
    C = S;
  }
  const Eigen::MatrixXd A = C.rows() ? nullSpace(C, length) : Eigen::MatrixXd::Identity(6, 6);
  const long n = mesh.nodeCount();
  Eigen::MatrixXd R(6 * n, A.cols());
  for (long i = 0; i < n; ++i) {
    const Eigen::Vector3d X = mesh.nodes.row(i).transpose();
    Eigen::Matrix<double, 6, 6> G = Eigen::Matrix<double, 6, 6>::Identity();
    G.topRightCorner<3, 3>() = -skew(X);
    R.middleRows<6>(6 * i) = G * A;
  }
  return R;
}

void reduceElement(const DofMap& map, const std::vector<long>& nodes, const Eigen::MatrixXd& Ke,
                   Eigen::MatrixXd& Kr, std::vector<long>& indices) {
  const int a = static_cast<int>(nodes.size());
  // Most elements touch no constrained node: T is the identity, skip the products.
  if (std::all_of(nodes.begin(), nodes.end(), [&](long n) { return map.unconstrained[static_cast<std::size_t>(n)] != 0; })) {
    Kr = Ke;
    indices.clear();
    for (long n : nodes)
      for (long j = 0; j < 6; ++j) indices.push_back(map.offset[static_cast<std::size_t>(n)] + j);
    return;
  }
  int k = 0;
  for (long n : nodes) k += map.count(n);
  Eigen::MatrixXd Tb = Eigen::MatrixXd::Zero(6 * a, k);
  indices.clear();
  int col = 0;
  for (int i = 0; i < a; ++i) {
    const auto& Ti = map.T[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])];
    Tb.block(6 * i, col, 6, Ti.cols()) = Ti;
    for (long j = 0; j < Ti.cols(); ++j) indices.push_back(map.offset[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])] + j);
    col += static_cast<int>(Ti.cols());
  }
  Kr = Tb.transpose() * Ke * Tb;
}

}  // namespace fc::feprep
