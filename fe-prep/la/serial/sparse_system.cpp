// The serial backend's matrices: the reduced K and M assembled as upper
// triangles on the exact pattern of the connectivity (the PETSc assembly's
// pattern, fe-prep/assembly.cpp, in one process), their products and checks.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "fe-prep/assembly.h"
#include "fe-prep/modal_solver.h"
#include "fe-prep/reference_conditions.h"
#include "la_backend.h"

// The backend's own names (la_backend.h) are in the inline namespace serial;
// the shared headers' functions (assembly.h, modal_solver.h) in fc::feprep,
// their serial types in their signatures.
namespace fc::feprep {
inline namespace serial {

const char* backendName() { return "serial (Eigen, CHOLMOD or MUMPS, ARPACK; program fe-prep)"; }

Eigen::VectorXd multiply(SystemMatrix A, const Eigen::VectorXd& v) {
  Eigen::VectorXd y(v.size());
  y.noalias() = A->selfadjointView<Eigen::Upper>() * v;
  return y;
}

}  // namespace serial

namespace {

using Adjacency = std::vector<std::vector<long>>;

// Links every node of `src` with every other (a clique in the node graph).
void link(Adjacency& adj, const std::vector<long>& src) {
  for (long a : src) adj[static_cast<std::size_t>(a)].insert(adj[static_cast<std::size_t>(a)].end(), src.begin(), src.end());
}

// The upper triangle's compressed pattern: column c of node a holds the DOF
// (<= c) of a's neighbours; a held patch's multiplier columns hold the patch
// DOF they constrain and an explicit (zero) diagonal. Values zero.
SparseMatrix upperPattern(const DofMap& map, Adjacency& adj, const std::vector<MultiplierRows>& held) {
  const long n = static_cast<long>(adj.size()), N = map.reduced;
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(N));
  std::vector<int> dofs;
  for (long a = 0; a < n; ++a) {
    auto& nb = adj[static_cast<std::size_t>(a)];
    nb.push_back(a);
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    if (map.count(a) == 0) {
      std::vector<long>().swap(nb);
      continue;
    }
    dofs.clear();
    for (long b : nb)
      for (int k = 0; k < map.count(b); ++k) dofs.push_back(static_cast<int>(map.offset[static_cast<std::size_t>(b)] + k));
    std::sort(dofs.begin(), dofs.end());
    for (int k = 0; k < map.count(a); ++k) {
      const int c = static_cast<int>(map.offset[static_cast<std::size_t>(a)] + k);
      rows[static_cast<std::size_t>(c)].assign(dofs.begin(), std::upper_bound(dofs.begin(), dofs.end(), c));
    }
    std::vector<long>().swap(nb);
  }
  for (const auto& h : held)
    for (long i = 0; i < h.values.rows(); ++i) {
      auto& r = rows[static_cast<std::size_t>(h.first_row + i)];
      for (long g : h.indices) r.push_back(static_cast<int>(g));
      r.push_back(static_cast<int>(h.first_row + i));
    }
  SparseMatrix A(N, N);
  long nnz = 0;
  for (const auto& r : rows) nnz += static_cast<long>(r.size());
  A.resizeNonZeros(nnz);
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  long at = 0;
  for (long c = 0; c < N; ++c) {
    outer[c] = static_cast<int>(at);
    auto& r = rows[static_cast<std::size_t>(c)];
    std::copy(r.begin(), r.end(), inner + at);
    at += static_cast<long>(r.size());
    std::vector<int>().swap(r);
  }
  outer[N] = static_cast<int>(at);
  std::fill(A.valuePtr(), A.valuePtr() + nnz, 0.0);
  return A;
}

// Adds the reduced element matrix (rows and columns idx) into the upper triangle.
void addUpper(SparseMatrix& A, const Eigen::MatrixXd& Ar, const std::vector<long>& idx) {
  const long m = static_cast<long>(idx.size());
  for (long q = 0; q < m; ++q)
    for (long p = 0; p < m; ++p)
      if (idx[static_cast<std::size_t>(p)] <= idx[static_cast<std::size_t>(q)] && Ar(p, q) != 0.0)
        A.coeffRef(idx[static_cast<std::size_t>(p)], idx[static_cast<std::size_t>(q)]) += Ar(p, q);
}

}  // namespace

void assemble(Comm, const Mesh& mesh, const DofMap& map, long elements, const ElementKernel& kernel,
              AssembledSystem& out, const std::function<void(double)>& progress, bool nodal_mass) {
  const long n = mesh.nodeCount();
  std::vector<MultiplierRows> held;
  for (std::size_t k = 0; k < map.held.size(); ++k) held.push_back(multiplierRows(map, k));
  {
    const Adjacency sources = nodeSources(map, n);
    Adjacency adj(static_cast<std::size_t>(n)), adj_m(nodal_mass ? static_cast<std::size_t>(n) : 0);
    std::vector<long> src;
    auto element = [&](const long* nodes, int count) {
      elementSources(sources, nodes, count, src);
      link(adj, src);
    };
    for (const auto& t : mesh.triangles) element(t.data(), 3);
    for (const auto& b : mesh.beams) element(b.data(), 2);
    // A node's own sources with each other: its mass (and a point mass) lands there.
    for (long i = 0; i < n; ++i) {
      link(adj, sources[static_cast<std::size_t>(i)]);
      if (nodal_mass) link(adj_m, sources[static_cast<std::size_t>(i)]);
    }
    out.K = upperPattern(map, adj, held);
    out.M = nodal_mass ? upperPattern(map, adj_m, held) : out.K;
  }
  out.lumped = Eigen::VectorXd::Zero(6 * n);
  ElementResult er;
  Eigen::MatrixXd Kr, Mr;
  std::vector<long> idx;
  double kdiag = 0.0;
  for (long e = 0; e < elements; ++e) {
    kernel(e, er);
    for (std::size_t a = 0; a < er.nodes.size(); ++a)
      out.lumped.segment<6>(6 * er.nodes[a]) += er.lumped.segment<6>(6 * static_cast<long>(a));
    reduceElement(map, er.nodes, er.K, Kr, idx);
    if (idx.empty()) continue;
    if (Kr.size()) kdiag = std::max(kdiag, Kr.diagonal().cwiseAbs().maxCoeff());
    addUpper(out.K, Kr, idx);
    if (nodal_mass) {
      const long a = static_cast<long>(er.nodes.size());
      for (long i = 0; i < a; ++i) {
        const Eigen::MatrixXd D = nodalMassBlock(er, e, i);
        if (D.cwiseAbs().maxCoeff() == 0.0) continue;
        std::vector<long> one_idx;
        reduceElement(map, {er.nodes[static_cast<std::size_t>(i)]}, D, Mr, one_idx);
        addUpper(out.M, Mr, one_idx);
      }
    } else {
      reduceElement(map, er.nodes, er.M, Mr, idx);
      addUpper(out.M, Mr, idx);
    }
    if (progress && (e % 1024 == 0)) progress(static_cast<double>(e) / static_cast<double>(std::max(elements, 1L)));
  }
  // The held patches' multiplier rows scaled to K's largest diagonal, as the
  // PETSc assembly's (the saddle point's pivots stay of one size).
  const double alpha = kdiag > 0.0 ? kdiag : 1.0;
  for (const auto& h : held)
    for (long i = 0; i < h.values.rows(); ++i)
      for (std::size_t j = 0; j < h.indices.size(); ++j)
        out.K.coeffRef(h.indices[j], h.first_row + i) += alpha * h.values(i, static_cast<long>(j));
  out.first_row = 0;
  out.local_rows = map.reduced;
  if (progress) progress(1.0);
}

bool freeBlockOf(const AssembledSystem& held, const DofMap& held_map, const DofMap& free_map, AssembledSystem& out) {
  if (!sameNodalDofs(held_map, free_map)) return false;
  // Upper triangles: the first n columns hold rows < n only, multiplier
  // columns come after; the nodal block is K's and M's leading corner.
  const long n = free_map.reduced;
  out.K = held.K.topLeftCorner(n, n);
  out.M = held.M.topLeftCorner(n, n);
  out.lumped = held.lumped;
  out.first_row = 0;
  out.local_rows = n;
  return true;
}

void addNodalTranslationalMass(Comm, const Mesh& mesh, const DofMap& map, const Eigen::VectorXd& dm, SystemMatrix M) {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(6, 6), Dr;
  std::vector<long> idx;
  for (long k = 0; k < mesh.nodeCount(); ++k) {
    if (dm(k) == 0.0 || map.idx[static_cast<std::size_t>(k)].empty()) continue;
    D.topLeftCorner<3, 3>() = dm(k) * Eigen::Matrix3d::Identity();
    reduceElement(map, {k}, D, Dr, idx);
    addUpper(*M, Dr, idx);
  }
}

long masslessDofs(SystemMatrix M) {
  const Eigen::VectorXd diag = M->diagonal();
  const double scale = diag.cwiseAbs().maxCoeff();
  return static_cast<long>((diag.array().abs() <= 1e-14 * scale).count());
}

double rigidNullResidual(SystemMatrix K, const Eigen::MatrixXd& rigid) {
  if (rigid.cols() == 0) return 0.0;
  // ||K||_inf of the symmetric K from its upper triangle.
  Eigen::VectorXd rows = Eigen::VectorXd::Zero(K->rows());
  for (int j = 0; j < K->outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(*K, j); it; ++it) {
      rows(it.row()) += std::abs(it.value());
      if (it.row() != j) rows(j) += std::abs(it.value());
    }
  const double knorm = rows.maxCoeff();
  double worst = 0.0;
  for (long j = 0; j < rigid.cols(); ++j)
    worst = std::max(worst, multiply(K, rigid.col(j)).cwiseAbs().maxCoeff() / (knorm * rigid.col(j).cwiseAbs().maxCoeff()));
  return worst;
}

}  // namespace fc::feprep
