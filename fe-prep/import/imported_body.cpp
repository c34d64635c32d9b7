#include "fe-prep/import/imported_body.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "fe-prep/import/matrix_files.h"
#include "fe-prep/mass_lumping.h"

namespace fc::feprep {
namespace {

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  throw InputError(file, line, 0, "", what);
}

// Rigid motions of the nodes (6 n x 6): u = t + omega x X, theta = omega.
Eigen::MatrixXd rigidModes(const Eigen::MatrixXd& X) {
  const long n = X.rows();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(6 * n, 6);
  for (long k = 0; k < n; ++k) {
    R.block<3, 3>(6 * k, 0).setIdentity();
    R.block<3, 3>(6 * k, 3) = -skew(X.row(k).transpose());
    R.block<3, 3>(6 * k + 3, 3).setIdentity();
  }
  return R;
}

// The mass matrix must be positive semi-definite: a negative diagonal, a zero
// diagonal with couplings (a negative 2x2 minor), or a negative LDL^T pivot of
// the DOF that carry mass is refused.
void checkMassDefinite(const Eigen::SparseMatrix<double>& M, const DofList& dofs, const std::string& file) {
  const long n = M.rows();
  auto name = [&](long i) {
    return "node " + std::to_string(dofs.dofs[static_cast<std::size_t>(i)].node) + " DOF " +
           std::to_string(dofs.dofs[static_cast<std::size_t>(i)].dof);
  };
  const Eigen::VectorXd d = M.diagonal();
  const double dmax = d.cwiseAbs().maxCoeff();
  std::vector<long> keep(static_cast<std::size_t>(n), -1);
  long m = 0;
  for (long i = 0; i < n; ++i) {
    if (d(i) < -1e-14 * dmax) {
      std::ostringstream os;
      os << "the mass matrix is indefinite: negative diagonal " << d(i) << " at " << name(i);
      fail(file, 0, os.str());
    }
    if (d(i) > 1e-14 * dmax) keep[static_cast<std::size_t>(i)] = m++;
  }
  std::vector<Eigen::Triplet<double>> t;
  for (long c = 0; c < n; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, c); it; ++it) {
      const long r = it.row();
      if (keep[static_cast<std::size_t>(r)] < 0 || keep[static_cast<std::size_t>(c)] < 0) {
        if (it.value() != 0.0 && r != c)
          fail(file, 0, "the mass matrix is indefinite: " + name(keep[static_cast<std::size_t>(r)] < 0 ? r : c) +
                            " has no mass on its diagonal but couples to " + name(keep[static_cast<std::size_t>(r)] < 0 ? c : r));
        continue;
      }
      t.emplace_back(keep[static_cast<std::size_t>(r)], keep[static_cast<std::size_t>(c)], it.value());
    }
  // Semi-definite is fine (a reduced-integration mass, C3D20R's, is singular):
  // by Sylvester's law of inertia, M + delta I has as many negative LDL^T pivots
  // as M has eigenvalues below -delta; delta = 1e-10 of the largest diagonal.
  const double delta = 1e-10 * dmax;
  for (long i = 0; i < m; ++i) t.emplace_back(i, i, delta);
  Eigen::SparseMatrix<double> A(m, m);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  if (ldlt.info() != Eigen::Success) fail(file, 0, "the mass matrix could not be factorised (indefinite)");
  const Eigen::VectorXd D = ldlt.vectorD();
  long negative = 0;
  for (long i = 0; i < m; ++i) negative += D(i) < 0.0 ? 1 : 0;
  if (negative > 0) {
    std::ostringstream os;
    os << "the mass matrix is indefinite: " << negative << " of its eigenvalues lie below -" << delta
       << " (1e-10 of its largest diagonal entry; LDL^T pivots of M + delta I)";
    fail(file, 0, os.str());
  }
}

// The lower triangle of P^T A P / (s s^T) * scale for the lower triangle A of
// a source matrix: source row i goes to body row to[i] (6 per node,
// node-major), its values divided by s_i (the unit of its DOF). A relabelling
// may carry an entry across the diagonal: it is stored at (max, min). Filled
// in place, 12 bytes per entry, no triplet list.
Eigen::SparseMatrix<double> spreadLowerTriangle(const Eigen::SparseMatrix<double>& A, const std::vector<long>& to,
                                                const Eigen::VectorXd& s, double scale, long N) {
  Eigen::SparseMatrix<double> B(N, N);
  B.resizeNonZeros(A.nonZeros());
  int* outer = B.outerIndexPtr();
  int* inner = B.innerIndexPtr();
  double* val = B.valuePtr();
  auto target = [&](long r, long c) {
    const long R = to[static_cast<std::size_t>(r)], C = to[static_cast<std::size_t>(c)];
    return std::make_pair(std::min(R, C), std::max(R, C));  // (column, row)
  };
  for (long c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) ++outer[target(it.row(), c).first + 1];
  for (long j = 0; j < N; ++j) outer[j + 1] += outer[j];
  {
    std::vector<int> next(outer, outer + N);
    for (long c = 0; c < A.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
        const auto [col, row] = target(it.row(), c);
        const int p = next[static_cast<std::size_t>(col)]++;
        inner[p] = static_cast<int>(row);
        val[p] = scale * it.value() / (s(it.row()) * s(c));
      }
  }
  std::vector<std::pair<int, double>> work;
  for (long j = 0; j < N; ++j) {
    const int a = outer[j], b = outer[j + 1];
    if (std::is_sorted(inner + a, inner + b)) continue;
    work.clear();
    for (int p = a; p < b; ++p) work.emplace_back(inner[p], val[p]);
    std::sort(work.begin(), work.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (int p = a; p < b; ++p) inner[p] = work[static_cast<std::size_t>(p - a)].first, val[p] = work[static_cast<std::size_t>(p - a)].second;
  }
  return B;
}

}  // namespace

ImportedModel importMatrices(const MatricesSpec& spec) {
  ImportedModel out;
  DofList dofs;
  if (!spec.dofs.empty()) dofs = readDofList(spec.dofs);
  const long nd = static_cast<long>(dofs.dofs.size());
  // Each matrix is read, checked and kept as its lower triangle before the
  // next is read: a file's entries (16 bytes each) live only while their own
  // matrix is built (docs/benchmarks.md, "Imported matrices at scale").
  Eigen::SparseMatrix<double> K, M;
  if (spec.format == "calculix" || spec.format == "matrix_market") {
    const bool ccx = spec.format == "calculix";
    {
      const StoredMatrix Ks = ccx ? readTripletMatrix(spec.stiffness, nd) : readMatrixMarket(spec.stiffness);
      out.indexing = Ks.indexing;
      K = symmetricLowerTriangle(Ks, nd, "stiffness", dofs, &out.storage_K);
    }
    const StoredMatrix Ms = ccx ? readTripletMatrix(spec.mass, nd) : readMatrixMarket(spec.mass);
    M = symmetricLowerTriangle(Ms, nd, "mass", dofs, &out.storage_M);
  } else {  // abaqus
    bool labelled = false;  // the stiffness names its DOF itself
    {
      const AbaqusMatrix k = readAbaqusMatrix(spec.stiffness, nd);
      labelled = !k.dofs.dofs.empty();
      if (labelled && !dofs.dofs.empty())
        fail(spec.dofs, 0, "the stiffness file " + spec.stiffness + " names its DOF itself (node, dof, node, dof, value); drop dofs:");
      if (labelled) dofs = k.dofs;
      else if (dofs.dofs.empty())
        fail(spec.stiffness, 0, "a 'row, column, value' matrix needs dofs: naming each row's node and DOF");
      out.indexing = k.matrix.indexing;
      K = symmetricLowerTriangle(k.matrix, static_cast<long>(dofs.dofs.size()), "stiffness", dofs, &out.storage_K);
    }
    AbaqusMatrix m = readAbaqusMatrix(spec.mass, nd);
    if (labelled) {
      if (m.dofs.dofs.empty()) fail(spec.mass, 0, "expected the same 'node, dof, node, dof, value' form as the stiffness");
      // The mass may omit DOF (massless rotations): its entries go to the
      // stiffness's rows (both lists ascend by node and DOF: a binary search).
      std::vector<long> to(m.dofs.dofs.size());
      auto key = [](const NodeDof& d) { return std::make_pair(d.node, d.dof); };
      for (std::size_t i = 0; i < m.dofs.dofs.size(); ++i) {
        const NodeDof& d = m.dofs.dofs[i];
        auto it = std::lower_bound(dofs.dofs.begin(), dofs.dofs.end(), d,
                                   [&](const NodeDof& a, const NodeDof& b) { return key(a) < key(b); });
        if (it == dofs.dofs.end() || key(*it) != key(d))
          fail(spec.mass, d.line, "node " + std::to_string(d.node) + " DOF " + std::to_string(d.dof) +
                                      " has mass but no stiffness (not in " + spec.stiffness + ")");
        to[i] = it - dofs.dofs.begin();
      }
      for (auto& e : m.matrix.entries)
        e.row = static_cast<int>(to[static_cast<std::size_t>(e.row)]), e.col = static_cast<int>(to[static_cast<std::size_t>(e.col)]);
      m.matrix.size = static_cast<long>(dofs.dofs.size());
    }
    M = symmetricLowerTriangle(m.matrix, static_cast<long>(dofs.dofs.size()), "mass", dofs, &out.storage_M);
  }
  const long n_src = static_cast<long>(dofs.dofs.size());
  out.source_dofs = n_src;
  checkMassDefinite(M, dofs, spec.mass);

  // Nodes: those the DOF list names, in its order; each must be in the model.
  const NodeTable table = readNodeTable(spec.model);
  const std::set<long> solid_elements(table.solid_nodes.begin(), table.solid_nodes.end());
  const std::set<long> structural_elements(table.structural_nodes.begin(), table.structural_nodes.end());
  std::map<long, long> index;
  std::vector<char> has_rotation;
  for (const NodeDof& d : dofs.dofs) {
    auto it = table.coordinates.find(d.node);
    if (it == table.coordinates.end())
      fail(dofs.file, d.line, "node " + std::to_string(d.node) + " is not in the model's node table " + table.file);
    if (d.dof > 3 && solid_elements.count(d.node) && !structural_elements.count(d.node))
      fail(dofs.file, d.line, "node " + std::to_string(d.node) + " carries rotation DOF " + std::to_string(d.dof) +
                                  " but belongs only to solid elements in " + table.file + " (solid nodes have 3 DOF)");
    if (index.emplace(d.node, static_cast<long>(index.size())).second) {
      out.labels.push_back(d.node);
      has_rotation.push_back(0);
    }
    if (d.dof > 3) has_rotation[static_cast<std::size_t>(index[d.node])] = 1;
  }
  const long n = static_cast<long>(out.labels.size());
  // Every node needs its three translations; rotations come all three or none.
  {
    std::vector<int> bits(static_cast<std::size_t>(n), 0), first_line(static_cast<std::size_t>(n), 0);
    for (const NodeDof& d : dofs.dofs) {
      const auto k = static_cast<std::size_t>(index[d.node]);
      bits[k] |= 1 << (d.dof - 1);
      if (!first_line[k]) first_line[k] = d.line;
    }
    for (long k = 0; k < n; ++k) {
      const int b = bits[static_cast<std::size_t>(k)];
      if ((b & 7) != 7 || ((b & 56) != 0 && (b & 56) != 56))
        fail(dofs.file, first_line[static_cast<std::size_t>(k)],
             "node " + std::to_string(out.labels[static_cast<std::size_t>(k)]) +
                 " lists DOF " + [&] {
                   std::string t;
                   for (int d = 0; d < 6; ++d)
                     if (b & (1 << d)) t += (t.empty() ? "" : ", ") + std::to_string(d + 1);
                   return t;
                 }() + ": every node needs translations 1, 2, 3, and rotations 4, 5, 6 all or none "
                       "(plane or axisymmetric models are not imported)");
    }
  }
  const double L = spec.units.length;
  out.mesh.nodes.resize(n, 3);
  for (long k = 0; k < n; ++k) out.mesh.nodes.row(k) = L * table.coordinates.at(out.labels[static_cast<std::size_t>(k)]).transpose();
  out.solid.resize(static_cast<std::size_t>(n));
  for (long k = 0; k < n; ++k) out.solid[static_cast<std::size_t>(k)] = has_rotation[static_cast<std::size_t>(k)] ? 0 : 1;
  for (const auto& [name, labels] : table.sets) {
    std::vector<long> members;
    for (long l : labels) {
      auto it = index.find(l);
      if (it != index.end()) members.push_back(it->second);
    }
    if (!members.empty()) out.mesh.sets[name] = members;
  }

  {
    std::vector<long> sorted_labels, sorted_index;
    for (const auto& [label, k] : index) sorted_labels.push_back(label), sorted_index.push_back(k);
    out.faces = boundaryFaces(table.solid_elements, sorted_labels, sorted_index);
  }

  // To SI on 6 DOF per node: a DOF's SI value is s times the file's (s = L for
  // translations, 1 for rotations), energies scale by E and kinetic energies by
  // m L^2: K_ij (SI) = E K_ij / (s_i s_j), M_ij (SI) = m L^2 M_ij / (s_i s_j).
  std::vector<long> to(static_cast<std::size_t>(n_src));
  Eigen::VectorXd s(n_src);
  for (long i = 0; i < n_src; ++i) {
    const NodeDof& d = dofs.dofs[static_cast<std::size_t>(i)];
    to[static_cast<std::size_t>(i)] = 6 * index[d.node] + d.dof - 1;
    s(i) = d.dof <= 3 ? L : 1.0;
  }
  const double e_scale = spec.units.energy(), m_scale = spec.units.mass * L * L;
  out.K = spreadLowerTriangle(K, to, s, e_scale, 6 * n);
  K = Eigen::SparseMatrix<double>();
  out.M = spreadLowerTriangle(M, to, s, m_scale, 6 * n);
  M = Eigen::SparseMatrix<double>();

  if (!(rigidMassProjection(out.mesh.nodes, out.M).mass > 0.0))
    fail(spec.mass, 0, "the mass matrix carries no mass in rigid translation (all zero?)");
  // A free model: its rigid motions must not strain it.
  const Eigen::MatrixXd R = rigidModes(out.mesh.nodes);
  const Eigen::MatrixXd KR = out.K.selfadjointView<Eigen::Lower>() * R;
  double knorm = 0.0;
  for (long c = 0; c < out.K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(out.K, c); it; ++it) knorm = std::max(knorm, std::abs(it.value()));
  double worst = 0.0;
  Eigen::Index worst_row = 0;
  for (int j = 0; j < 6; ++j) {
    // Rotations weigh by the body size so that the measure is one of forces.
    const double scale = knorm * R.col(j).cwiseAbs().maxCoeff();
    Eigen::Index row;
    const double v = KR.col(j).cwiseAbs().maxCoeff(&row) / scale;
    if (v > worst) worst = v, worst_row = row;
  }
  out.rigid_strain = worst;
  if (worst > 1e-8) {
    // Where the rigid motion is resisted most: the row's node and DOF, and its line in the DOF list.
    const long node = out.labels[static_cast<std::size_t>(worst_row / 6)];
    const int dof = static_cast<int>(worst_row % 6) + 1;
    int line = 0;
    for (const NodeDof& d : dofs.dofs)
      if (d.node == node && d.dof == dof) line = d.line;
    std::ostringstream os;
    os << "the stiffness strains rigid motions (|K r| / (|K| |r|) = " << worst << ", most at node " << node << " DOF "
       << dof << ", " << dofs.file << ":" << line << "): the source model holds the body (boundary conditions, "
       << "springs to ground), or its matrix and the node coordinates of " << spec.model << " disagree; export the "
       << "free model and give the conditions in reference:";
    fail(spec.stiffness, 0, os.str());
  }

  // Node pairs the matrices couple, for the assembly.
  std::vector<std::vector<long>> partners(static_cast<std::size_t>(n));
  for (const auto* A : {&out.K, &out.M})
    for (long c = 0; c < A->outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(*A, c); it; ++it) {
        const long i = c / 6, j = it.row() / 6;  // the lower triangle: i <= j
        partners[static_cast<std::size_t>(i)].push_back(j);
      }
  out.pairs.nodes = out.mesh.nodes;
  for (long i = 0; i < n; ++i) {
    auto& p = partners[static_cast<std::size_t>(i)];
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    for (long j : p) out.pairs.beams.push_back({i, j});
  }
  return out;
}

void ImportedModel::pairMatrices(long e, ElementResult& out) const {
  const long i = pairs.beams[static_cast<std::size_t>(e)][0], j = pairs.beams[static_cast<std::size_t>(e)][1];
  // Rows of node a in the columns of node b (a >= b: in the lower triangle);
  // a column's rows are sorted, so node a's are found by a search.
  auto block = [&](const Eigen::SparseMatrix<double>& A, long a, long b) {
    Eigen::Matrix<double, 6, 6> B = Eigen::Matrix<double, 6, 6>::Zero();
    const int* inner = A.innerIndexPtr();
    for (int c = 0; c < 6; ++c) {
      const long col = 6 * b + c;
      const int* first = inner + A.outerIndexPtr()[col];
      const int* last = inner + A.outerIndexPtr()[col + 1];
      for (const int* p = std::lower_bound(first, last, static_cast<int>(6 * a)); p != last && *p < 6 * a + 6; ++p)
        B(*p - 6 * a, c) = A.valuePtr()[p - inner];
    }
    return B;
  };
  if (i == j) {
    out.nodes = {i};
    // The diagonal block from its lower half.
    auto full = [&](const Eigen::SparseMatrix<double>& A) {
      const Eigen::Matrix<double, 6, 6> L = block(A, i, i);
      return Eigen::MatrixXd(Eigen::Matrix<double, 6, 6>(L.selfadjointView<Eigen::Lower>()));
    };
    out.K = full(K);
    out.M = full(M);
    out.lumped = Eigen::VectorXd::Zero(6);
    return;
  }
  out.nodes = {i, j};
  out.K = Eigen::MatrixXd::Zero(12, 12);
  out.M = Eigen::MatrixXd::Zero(12, 12);
  out.K.block<6, 6>(6, 0) = block(K, j, i);
  out.K.block<6, 6>(0, 6) = out.K.block<6, 6>(6, 0).transpose();
  out.M.block<6, 6>(6, 0) = block(M, j, i);
  out.M.block<6, 6>(0, 6) = out.M.block<6, 6>(6, 0).transpose();
  out.lumped = Eigen::VectorXd::Zero(12);
}

MassProjection rigidMassProjection(const Eigen::MatrixXd& nodes, const Eigen::SparseMatrix<double>& M) {
  const Eigen::MatrixXd R = rigidModes(nodes);
  const Eigen::MatrixXd MR = M.selfadjointView<Eigen::Lower>() * R;
  const Eigen::Matrix<double, 6, 6> P = R.transpose() * MR;
  MassProjection p;
  p.mass = P.topLeftCorner<3, 3>().trace() / 3.0;
  p.misfit = (P.topLeftCorner<3, 3>() - p.mass * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() / p.mass;
  // Rotation-translation block R_w^T M R_t = skew(S) for S = sum m_k X_k.
  const Eigen::Matrix3d B = 0.5 * (P.block<3, 3>(3, 0) - P.block<3, 3>(3, 0).transpose());
  p.first_moment = Eigen::Vector3d(B(2, 1), B(0, 2), B(1, 0));
  p.inertia_about_origin = 0.5 * (P.bottomRightCorner<3, 3>() + P.bottomRightCorner<3, 3>().transpose());
  return p;
}

ImportedLumping importedNodalMasses(const Eigen::MatrixXd& nodes, const Eigen::SparseMatrix<double>& M,
                                   const MassProjection& p) {
  const long n = nodes.rows();
  const Eigen::VectorXd d = M.diagonal();
  Eigen::VectorXd t(n);
  for (long k = 0; k < n; ++k) t(k) = d.segment<3>(6 * k).mean();
  const double c = p.mass / t.sum();
  ImportedLumping out;
  out.nodal.resize(n, 4);
  Eigen::Matrix3d rotary = Eigen::Matrix3d::Zero();
  for (long k = 0; k < n; ++k) {
    out.nodal(k, 0) = c * t(k);
    out.nodal.block<1, 3>(k, 1) = c * d.segment<3>(6 * k + 3).transpose();
    rotary.diagonal() += out.nodal.block<1, 3>(k, 1).transpose();
  }
  // The translational masses' second moment E from J = tr(E) I - E + rotary.
  const Eigen::Matrix3d Jt = p.inertia_about_origin - rotary;
  const Eigen::Matrix3d E = 0.5 * Jt.trace() * Eigen::Matrix3d::Identity() - Jt;
  const MomentLumping ml = momentConsistentMasses(nodes, out.nodal.col(0), p.mass, p.first_moment, E);
  out.applied = ml.applied;
  out.min_ratio = ml.min_ratio;
  if (ml.applied) {
    out.nodal.col(0) = ml.masses;
    return out;
  }
  // Nodes on a line or a plane cannot carry every second moment in their
  // translational masses; with 6-DOF nodes the rotary inertias can take the
  // rest. Translations: the mass and first moment made exact, the second
  // moment kept at the scaled diagonal's; rotations: what the projection's
  // inertia still lacks, J - (tr(E) I - E), if it is diagonal and non-negative,
  // shared among the 6-DOF nodes in proportion to their diagonal rotary terms.
  if (rotary.trace() <= 0.0) return out;
  // The translational masses closest (relative change) to the scaled diagonal
  // whose moments are the least-squares fit of the targets: what the nodes'
  // geometry can carry (the same correction as mass_lumping.h, kept when the
  // targets are only partly reachable).
  const Eigen::VectorXd m0 = out.nodal.col(0);
  const double Lc = std::max((nodes.colwise().maxCoeff() - nodes.colwise().minCoeff()).norm(), 1e-300);
  const Eigen::MatrixXd Y = nodes / Lc;
  Eigen::MatrixXd C(10, n);
  for (long k = 0; k < n; ++k) {
    const double x = Y(k, 0), y = Y(k, 1), z = Y(k, 2);
    C.col(k) << 1, x, y, z, x * x, y * y, z * z, x * y, x * z, y * z;
  }
  const Eigen::Vector3d f = p.first_moment / Lc;
  const Eigen::Matrix3d Es = E / (Lc * Lc);
  Eigen::VectorXd b(10);
  b << p.mass, f.x(), f.y(), f.z(), Es(0, 0), Es(1, 1), Es(2, 2), Es(0, 1), Es(0, 2), Es(1, 2);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(C * m0.asDiagonal() * C.transpose());
  Eigen::VectorXd inv = Eigen::VectorXd::Zero(10);
  for (int i = 0; i < 10; ++i)
    if (es.eigenvalues()(i) > 1e-12 * es.eigenvalues().cwiseAbs().maxCoeff()) inv(i) = 1.0 / es.eigenvalues()(i);
  const Eigen::VectorXd lambda = es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose() * (b - C * m0);
  const Eigen::VectorXd mt = m0 + m0.asDiagonal() * (C.transpose() * lambda);
  const double ratio = (mt.array() / m0.array()).minCoeff();
  if (!(ratio >= 0.1)) return out;
  // Mass and first moment must be met exactly.
  const Eigen::VectorXd got = C * mt;
  if ((got.head<4>() - b.head<4>()).norm() > 1e-12 * b.head<4>().norm()) return out;
  Eigen::Matrix3d Et = Eigen::Matrix3d::Zero();
  for (long k = 0; k < n; ++k) Et += mt(k) * nodes.row(k).transpose() * nodes.row(k);
  const Eigen::Matrix3d need = p.inertia_about_origin - (Et.trace() * Eigen::Matrix3d::Identity() - Et);
  const double scale = p.inertia_about_origin.cwiseAbs().maxCoeff();
  const Eigen::Matrix3d off = need - Eigen::Matrix3d(need.diagonal().asDiagonal());
  if (off.cwiseAbs().maxCoeff() > 1e-12 * scale || need.diagonal().minCoeff() < -1e-12 * scale) return out;
  for (int a = 0; a < 3; ++a) {
    const double have = rotary(a, a);
    if (have <= 0.0) {
      if (need(a, a) > 1e-12 * scale) return out;  // no node can carry it
      continue;
    }
    out.nodal.col(1 + a) *= std::max(need(a, a), 0.0) / have;
  }
  out.nodal.col(0) = mt;
  out.applied = true;
  out.min_ratio = ratio;
  return out;
}

void holdSolidRotations(DofMap& map, const std::vector<char>& solid) {
  const long n = static_cast<long>(map.T.size());
  std::vector<char> used(static_cast<std::size_t>(map.reduced), 0), needed(static_cast<std::size_t>(map.reduced), 0);
  for (long i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    for (std::size_t c = 0; c < map.idx[ui].size(); ++c) {
      const long g = map.idx[ui][c];
      const Eigen::VectorXd col = map.T[ui].col(static_cast<long>(c));
      if (col.cwiseAbs().maxCoeff() == 0.0) continue;
      used[static_cast<std::size_t>(g)] = 1;
      if (col.head<3>().cwiseAbs().maxCoeff() > 0.0 || (!solid[ui] && col.tail<3>().cwiseAbs().maxCoeff() > 0.0))
        needed[static_cast<std::size_t>(g)] = 1;
    }
  }
  std::vector<long> renumber(static_cast<std::size_t>(map.reduced), -1);
  long next = 0;
  for (long g = 0; g < map.reduced; ++g)
    if (needed[static_cast<std::size_t>(g)] || !used[static_cast<std::size_t>(g)]) renumber[static_cast<std::size_t>(g)] = next++;
  if (next == map.reduced) return;
  for (long i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    std::vector<long> cols;
    for (std::size_t c = 0; c < map.idx[ui].size(); ++c)
      if (renumber[static_cast<std::size_t>(map.idx[ui][c])] >= 0) cols.push_back(static_cast<long>(c));
    const bool changed = cols.size() != map.idx[ui].size();
    if (changed) {
      Eigen::MatrixXd T(6, static_cast<long>(cols.size()));
      std::vector<long> idx;
      for (std::size_t k = 0; k < cols.size(); ++k) {
        T.col(static_cast<long>(k)) = map.T[ui].col(cols[k]);
        idx.push_back(map.idx[ui][static_cast<std::size_t>(cols[k])]);
      }
      map.T[ui] = T;
      map.idx[ui] = idx;
    }
    for (long& g : map.idx[ui]) g = renumber[static_cast<std::size_t>(g)];
    // Own rows: the node's own reduced DOF offset .. offset + count - 1.
    const Eigen::MatrixXd own = map.own[ui];
    std::vector<long> rows;
    for (long r = 0; r < own.rows(); ++r)
      if (renumber[static_cast<std::size_t>(map.offset[ui] + r)] >= 0) rows.push_back(r);
    if (static_cast<long>(rows.size()) != own.rows()) {
      map.own[ui].resize(static_cast<long>(rows.size()), 6);
      for (std::size_t k = 0; k < rows.size(); ++k) map.own[ui].row(static_cast<long>(k)) = own.row(rows[k]);
      map.unconstrained[ui] = 0;
    }
    if (changed) map.unconstrained[ui] = 0;
  }
  long off = 0;
  for (long i = 0; i < n; ++i) {
    map.offset[static_cast<std::size_t>(i)] = off;
    off += map.own[static_cast<std::size_t>(i)].rows();
  }
  map.reduced = next;
}

Eigen::VectorXd readCalculixEigenvalues(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, 0, "cannot open the file");
  std::string raw;
  int line = 0;
  bool table = false;
  std::vector<double> values;
  while (std::getline(in, raw)) {
    ++line;
    if (!table) {
      table = raw.find("E I G E N V A L U E   O U T P U T") != std::string::npos;
      continue;
    }
    std::istringstream ss(raw);
    long mode;
    double lambda;
    if (ss >> mode >> lambda) {
      if (mode != static_cast<long>(values.size()) + 1)
        fail(path, line, "expected mode " + std::to_string(values.size() + 1) + " in the eigenvalue table");
      values.push_back(lambda);
    } else if (!values.empty()) {
      break;  // the table ends at the first non-numeric line after its rows
    }
  }
  if (values.empty()) fail(path, line, "no CalculiX eigenvalue table (E I G E N V A L U E   O U T P U T) found");
  return Eigen::Map<Eigen::VectorXd>(values.data(), static_cast<long>(values.size()));
}

}  // namespace fc::feprep
