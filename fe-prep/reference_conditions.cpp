#include "fe-prep/reference_conditions.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace fc::feprep {

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

Eigen::Matrix<double, 6, 6> rigidTransfer(const Eigen::Vector3d& d) {
  Eigen::Matrix<double, 6, 6> G = Eigen::Matrix<double, 6, 6>::Identity();
  G.topRightCorner<3, 3>() = -skew(d);
  return G;
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
Eigen::MatrixXd conditionRows(const PointCondition& c, const Eigen::Vector3d& d) {
  Eigen::MatrixXd C(c.clamp ? 6 : 3, 6);
  C.setZero();
  C.topLeftCorner<3, 3>().setIdentity();
  C.topRightCorner<3, 3>() = -skew(d);
  if (c.clamp) C.bottomRightCorner<3, 3>().setIdentity();
  return C;
}

enum class Role : char { Free, Conditioned, Slave, Patch };

std::string nodeName(long k) { return "node " + std::to_string(k); }

// The rows of the point conditions, stacked per node.
std::map<long, Eigen::MatrixXd> conditionRowsByNode(const Mesh& mesh, const std::vector<PointCondition>& conditions) {
  std::map<long, Eigen::MatrixXd> rows;
  for (const auto& c : conditions) {
    if (c.node < 0) continue;
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
  return rows;
}

// What each node's DOF are: its own (free, or reduced by its conditions), a
// rigid slave's master's, or a patch's; for an eliminated patch, which of its
// components are dependent.
struct NodeRoles {
  std::vector<Role> role;
  std::vector<long> master_of;
  std::vector<std::array<char, 6>> dependent;
};

NodeRoles conditionedAndSlaves(long n, const std::map<long, Eigen::MatrixXd>& rows,
                               const std::vector<RigidCoupling>& rigid) {
  NodeRoles r;
  r.role.assign(static_cast<std::size_t>(n), Role::Free);
  for (const auto& kv : rows) r.role[static_cast<std::size_t>(kv.first)] = Role::Conditioned;
  r.master_of.assign(static_cast<std::size_t>(n), -1);
  for (const auto& rc : rigid)
    for (long s : rc.slaves) {
      if (s == rc.master) continue;
      if (r.role[static_cast<std::size_t>(s)] != Role::Free)
        throw std::invalid_argument(nodeName(s) +
                                    " of a rigid interface patch is also held by a reference condition or another "
                                    "patch; patches must not overlap each other or the reference sets");
      r.role[static_cast<std::size_t>(s)] = Role::Slave;
      r.master_of[static_cast<std::size_t>(s)] = rc.master;
    }
  for (const auto& rc : rigid)
    if (r.role[static_cast<std::size_t>(rc.master)] == Role::Slave)
      throw std::invalid_argument("rigid interface patches overlap at " + nodeName(rc.master));
  r.dependent.assign(static_cast<std::size_t>(n), std::array<char, 6>{0, 0, 0, 0, 0, 0});
  return r;
}

struct PatchElimination {
  std::vector<long> nodes;
  Eigen::MatrixXd P;  // (6 p, n_independent): q_patch = P r_I
  std::vector<std::pair<long, int>> independent;  // (node, component) of each column of P
};

// An eliminated patch: its dependent DOF (marked in r.dependent) from the
// column-pivoted QR's pivots, expressed through the independent ones.
PatchElimination eliminatePatch(const PatchCondition& pc, const Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& qr,
                                NodeRoles& r) {
  const long p = static_cast<long>(pc.nodes.size());
  const long c = pc.C.rows();
  std::vector<char> is_dep(static_cast<std::size_t>(6 * p), 0);
  for (long i = 0; i < c; ++i) is_dep[static_cast<std::size_t>(qr.colsPermutation().indices()(i))] = 1;
  std::vector<long> dep, ind;
  for (long j = 0; j < 6 * p; ++j) (is_dep[static_cast<std::size_t>(j)] ? dep : ind).push_back(j);
  Eigen::MatrixXd CD(c, c), CI(c, static_cast<long>(ind.size()));
  for (long i = 0; i < c; ++i) CD.col(i) = pc.C.col(dep[static_cast<std::size_t>(i)]);
  for (std::size_t i = 0; i < ind.size(); ++i) CI.col(static_cast<long>(i)) = pc.C.col(ind[i]);
  const Eigen::MatrixXd X = -CD.partialPivLu().solve(CI);
  PatchElimination e;
  e.nodes = pc.nodes;
  e.P = Eigen::MatrixXd::Zero(6 * p, static_cast<long>(ind.size()));
  for (std::size_t i = 0; i < ind.size(); ++i) {
    e.P(ind[i], static_cast<long>(i)) = 1.0;
    e.independent.emplace_back(pc.nodes[static_cast<std::size_t>(ind[i] / 6)], static_cast<int>(ind[i] % 6));
  }
  for (long i = 0; i < c; ++i) {
    e.P.row(dep[static_cast<std::size_t>(i)]) = X.row(i);
    r.dependent[static_cast<std::size_t>(pc.nodes[static_cast<std::size_t>(dep[static_cast<std::size_t>(i)] / 6)])]
               [static_cast<std::size_t>(dep[static_cast<std::size_t>(i)] % 6)] = 1;
  }
  for (long k : pc.nodes) r.role[static_cast<std::size_t>(k)] = Role::Patch;
  return e;
}

// Held distributing patches: checked independent by a column-pivoted QR, then
// eliminated (elim) or held by multipliers (held).
void distributingPatches(const std::vector<PatchCondition>& patches, PatchHold hold, double length, NodeRoles& r,
                         std::vector<PatchElimination>& elim, std::vector<HeldPatch>& held) {
  for (const auto& pc : patches) {
    const long p = static_cast<long>(pc.nodes.size());
    for (long k : pc.nodes)
      if (r.role[static_cast<std::size_t>(k)] != Role::Free)
        throw std::invalid_argument(nodeName(k) + " of a held distributing interface patch is also held otherwise or in "
                                                  "another patch; patches must not overlap each other or the reference sets");
    // Scale rotation columns by the body size so the pivoting compares like with like.
    Eigen::MatrixXd Cs = pc.C;
    for (long k = 0; k < p; ++k) Cs.middleCols(6 * k + 3, 3) *= 1.0 / length;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Cs);
    qr.setThreshold(1e-10);
    const long c = pc.C.rows();
    if (qr.rank() < c)
      throw std::invalid_argument("the conditions on a distributing interface are not independent (rank " +
                                  std::to_string(qr.rank()) + " of " + std::to_string(c) + ")");
    if (hold == PatchHold::Multipliers) {
      // The patch nodes keep their own six DOF; the rows join as multipliers.
      for (long k : pc.nodes) r.role[static_cast<std::size_t>(k)] = Role::Patch;
      held.push_back({pc.nodes, pc.C});
      continue;
    }
    elim.push_back(eliminatePatch(pc, qr, r));
  }
}

// Own DOF of every node, contiguous per node; returns their count.
long ownDofs(long n, const NodeRoles& r, const std::map<long, Eigen::MatrixXd>& rows, double length, DofMap& map) {
  map.T.resize(static_cast<std::size_t>(n));
  map.idx.resize(static_cast<std::size_t>(n));
  map.own.resize(static_cast<std::size_t>(n));
  map.offset.resize(static_cast<std::size_t>(n));
  map.unconstrained.assign(static_cast<std::size_t>(n), 0);
  long next = 0;
  for (long i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    map.offset[ui] = next;
    switch (r.role[ui]) {
      case Role::Free:
        map.own[ui] = Eigen::MatrixXd::Identity(6, 6);
        map.unconstrained[ui] = 1;
        break;
      case Role::Conditioned: {
        const Eigen::MatrixXd& C = rows.at(i);
        Eigen::MatrixXd T;
        if (C.rows() == 3 && C.topRightCorner(3, 3).norm() == 0.0) {
          // A pin on the node itself: exactly the three rotations (no SVD round-off).
          T = Eigen::MatrixXd::Zero(6, 3);
          T.bottomRows(3).setIdentity();
        } else {
          T = nullSpace(C, length);
        }
        map.own[ui] = T.transpose();
        break;
      }
      case Role::Slave:
        map.own[ui].resize(0, 6);
        break;
      case Role::Patch: {
        int k = 0;
        for (int d = 0; d < 6; ++d) k += r.dependent[ui][static_cast<std::size_t>(d)] ? 0 : 1;
        map.own[ui] = Eigen::MatrixXd::Zero(k, 6);
        int row = 0;
        for (int d = 0; d < 6; ++d)
          if (!r.dependent[ui][static_cast<std::size_t>(d)]) map.own[ui](row++, d) = 1.0;
        map.unconstrained[ui] = k == 6 ? 1 : 0;  // a node of a patch held by multipliers
        break;
      }
    }
    next += map.own[ui].rows();
  }
  return next;
}

// T and idx of an eliminated patch's nodes with dependent DOF: through P.
void expressThroughPatch(const PatchElimination& e, const NodeRoles& r, DofMap& map) {
  // Reduced index of each independent column.
  std::vector<long> col_index;
  for (const auto& [node, comp] : e.independent) {
    const auto un = static_cast<std::size_t>(node);
    int k = 0;
    for (int d = 0; d < comp; ++d) k += r.dependent[un][static_cast<std::size_t>(d)] ? 0 : 1;
    col_index.push_back(map.offset[un] + k);
  }
  for (std::size_t a = 0; a < e.nodes.size(); ++a) {
    const auto ua = static_cast<std::size_t>(e.nodes[a]);
    const auto& dep = r.dependent[ua];
    if (std::none_of(dep.begin(), dep.end(), [](char c) { return c != 0; })) continue;  // own DOF only
    const Eigen::MatrixXd rowsP = e.P.middleRows(6 * static_cast<long>(a), 6);
    std::vector<long> cols;
    for (long j = 0; j < rowsP.cols(); ++j)
      if (rowsP.col(j).cwiseAbs().maxCoeff() > 0.0) cols.push_back(j);
    map.T[ua].resize(6, static_cast<long>(cols.size()));
    map.idx[ua].clear();
    for (std::size_t j = 0; j < cols.size(); ++j) {
      map.T[ua].col(static_cast<long>(j)) = rowsP.col(cols[j]);
      map.idx[ua].push_back(col_index[static_cast<std::size_t>(cols[j])]);
    }
  }
}

// T and idx: own DOF first, then patches through P, slaves through their masters.
void expressNodes(const Mesh& mesh, const NodeRoles& r, const std::vector<PatchElimination>& elim, DofMap& map) {
  const long n = static_cast<long>(r.role.size());
  for (long i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (r.role[ui] == Role::Free || r.role[ui] == Role::Conditioned || r.role[ui] == Role::Patch) {
      map.T[ui] = map.own[ui].transpose();
      for (long j = 0; j < map.own[ui].rows(); ++j) map.idx[ui].push_back(map.offset[ui] + j);
    }
  }
  for (const auto& e : elim) expressThroughPatch(e, r, map);
  for (long i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (r.role[ui] != Role::Slave) continue;
    const long m = r.master_of[ui];
    const Eigen::Vector3d d = (mesh.nodes.row(i) - mesh.nodes.row(m)).transpose();
    map.T[ui] = rigidTransfer(d) * map.T[static_cast<std::size_t>(m)];
    map.idx[ui] = map.idx[static_cast<std::size_t>(m)];
  }
}

}  // namespace

// The stages: the conditions' rows per node, the rigid slaves, the
// distributing patches (eliminated or held), each node's own DOF, the
// multipliers after them, then every node's T and reduced indices.
DofMap buildDofMap(const Mesh& mesh, const std::vector<PointCondition>& conditions,
                   const std::vector<RigidCoupling>& rigid, const std::vector<PatchCondition>& patches,
                   PatchHold hold) {
  const long n = mesh.nodeCount();
  const double length = std::max(mesh.characteristicLength(), 1e-12);
  const std::map<long, Eigen::MatrixXd> rows = conditionRowsByNode(mesh, conditions);
  NodeRoles roles = conditionedAndSlaves(n, rows, rigid);
  std::vector<PatchElimination> elim;
  std::vector<HeldPatch> held;
  distributingPatches(patches, hold, length, roles, elim, held);
  DofMap map;
  const long next = ownDofs(n, roles, rows, length, map);
  // The multipliers after every nodal reduced DOF.
  for (const auto& h : held) map.multipliers += h.C.rows();
  map.held = std::move(held);
  map.reduced = next + map.multipliers;
  expressNodes(mesh, roles, elim, map);
  return map;
}

Eigen::VectorXd DofMap::expand(const Eigen::VectorXd& r) const {
  const long n = static_cast<long>(T.size());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6 * n);
  for (long i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const auto& ix = idx[ui];
    if (ix.empty()) continue;
    Eigen::VectorXd ri(static_cast<long>(ix.size()));
    for (std::size_t j = 0; j < ix.size(); ++j) ri(static_cast<long>(j)) = r(ix[j]);
    q.segment<6>(6 * i) = T[ui] * ri;
  }
  return q;
}

Eigen::VectorXd DofMap::restrict(const Eigen::VectorXd& q) const {
  Eigen::VectorXd r(reduced);
  r.tail(multipliers).setZero();
  const long n = static_cast<long>(T.size());
  for (long i = 0; i < n; ++i) {
    const auto& Oi = own[static_cast<std::size_t>(i)];
    if (Oi.rows() == 0) continue;
    r.segment(offset[static_cast<std::size_t>(i)], Oi.rows()) = Oi * q.segment<6>(6 * i);
  }
  return r;
}

MultiplierRows multiplierRows(const DofMap& map, std::size_t k) {
  MultiplierRows out;
  out.first_row = map.firstMultiplier();
  for (std::size_t j = 0; j < k; ++j) out.first_row += map.held[j].C.rows();
  const HeldPatch& h = map.held[k];
  // C T on the patch nodes: column c of node a's T feeds reduced DOF idx_a[c].
  std::map<long, Eigen::VectorXd> cols;
  for (std::size_t a = 0; a < h.nodes.size(); ++a) {
    const auto un = static_cast<std::size_t>(h.nodes[a]);
    const Eigen::MatrixXd CT = h.C.middleCols(6 * static_cast<long>(a), 6) * map.T[un];
    for (std::size_t c = 0; c < map.idx[un].size(); ++c) {
      auto it = cols.find(map.idx[un][c]);
      if (it == cols.end()) it = cols.emplace(map.idx[un][c], Eigen::VectorXd::Zero(h.C.rows())).first;
      it->second += CT.col(static_cast<long>(c));
    }
  }
  for (auto it = cols.begin(); it != cols.end();)
    it = it->second.cwiseAbs().maxCoeff() > 0.0 ? std::next(it) : cols.erase(it);
  out.values.resize(h.C.rows(), static_cast<long>(cols.size()));
  for (const auto& [g, v] : cols) {
    out.values.col(static_cast<long>(out.indices.size())) = v;
    out.indices.push_back(g);
  }
  return out;
}

Eigen::MatrixXd admissibleRigidModes(const Mesh& mesh, const std::vector<PointCondition>& conditions) {
  const double length = std::max(mesh.characteristicLength(), 1e-12);
  Eigen::MatrixXd C(0, 6);
  for (const auto& c : conditions) {
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
    R.middleRows<6>(6 * i) = rigidTransfer(X) * A;
  }
  return R;
}

void reduceElement(const DofMap& map, const std::vector<long>& nodes, const Eigen::MatrixXd& Ke,
                   Eigen::MatrixXd& Kr, std::vector<long>& indices) {
  const int a = static_cast<int>(nodes.size());
  indices.clear();
  // Most elements touch no constrained node: T is the identity, skip the products.
  if (std::all_of(nodes.begin(), nodes.end(), [&](long n) { return map.unconstrained[static_cast<std::size_t>(n)] != 0; })) {
    Kr = Ke;
    for (long n : nodes)
      for (long j = 0; j < 6; ++j) indices.push_back(map.offset[static_cast<std::size_t>(n)] + j);
    return;
  }
  // The union of the reduced DOF the element's nodes depend on (a slave and its
  // master, or two nodes of one patch, share columns).
  std::unordered_map<long, int> where;
  for (long n : nodes)
    for (long g : map.idx[static_cast<std::size_t>(n)])
      if (where.emplace(g, static_cast<int>(indices.size())).second) indices.push_back(g);
  Eigen::MatrixXd Tb = Eigen::MatrixXd::Zero(6 * a, static_cast<long>(indices.size()));
  for (int i = 0; i < a; ++i) {
    const auto un = static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)]);
    const auto& ix = map.idx[un];
    for (std::size_t j = 0; j < ix.size(); ++j) Tb.block(6 * i, where.at(ix[j]), 6, 1) += map.T[un].col(static_cast<long>(j));
  }
  Kr = Tb.transpose() * Ke * Tb;
}

std::vector<std::vector<long>> nodeSources(const DofMap& map, long n_nodes) {
  std::vector<long> owner_node(static_cast<std::size_t>(map.reduced), -1);
  for (long i = 0; i < n_nodes; ++i)
    for (int k = 0; k < map.count(i); ++k) owner_node[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] + k)] = i;
  std::vector<std::vector<long>> sources(static_cast<std::size_t>(n_nodes));
  for (long i = 0; i < n_nodes; ++i) {
    auto& s = sources[static_cast<std::size_t>(i)];
    for (long g : map.idx[static_cast<std::size_t>(i)]) s.push_back(owner_node[static_cast<std::size_t>(g)]);
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
  }
  return sources;
}

void elementSources(const std::vector<std::vector<long>>& sources, const long* nodes, int count,
                    std::vector<long>& out) {
  out.clear();
  for (int i = 0; i < count; ++i) {
    const auto& s = sources[static_cast<std::size_t>(nodes[i])];
    out.insert(out.end(), s.begin(), s.end());
  }
}

bool sameNodalDofs(const DofMap& held, const DofMap& free) {
  if (free.multipliers != 0 || free.reduced != held.firstMultiplier()) return false;
  if (held.offset != free.offset || held.idx != free.idx || held.unconstrained != free.unconstrained) return false;
  if (held.T.size() != free.T.size() || held.own.size() != free.own.size()) return false;
  for (std::size_t k = 0; k < held.T.size(); ++k)
    if (held.T[k].rows() != free.T[k].rows() || held.T[k].cols() != free.T[k].cols() || held.T[k] != free.T[k])
      return false;
  for (std::size_t k = 0; k < held.own.size(); ++k)
    if (held.own[k].rows() != free.own[k].rows() || held.own[k].cols() != free.own[k].cols() || held.own[k] != free.own[k])
      return false;
  return true;
}

}  // namespace fc::feprep
