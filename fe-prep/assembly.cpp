#include "fe-prep/assembly.h"

#include "fe-prep/petsc_handles.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fc::feprep {

AssembledSystem::~AssembledSystem() {
  if (K) MatDestroy(&K);
  if (M) MatDestroy(&M);
}

std::vector<long> nodeOwnership(long n_nodes, int ranks) {
  std::vector<long> first(static_cast<std::size_t>(ranks) + 1);
  for (int r = 0; r <= ranks; ++r) first[static_cast<std::size_t>(r)] = n_nodes * r / ranks;
  return first;
}

void assemble(MPI_Comm comm, const Mesh& mesh, const DofMap& map, long elements, const ElementKernel& kernel,
              AssembledSystem& out, const std::function<void(double)>& progress, bool nodal_mass) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const long n = mesh.nodeCount();
  const auto first = nodeOwnership(n, size);
  const long n0 = first[static_cast<std::size_t>(rank)], n1 = first[static_cast<std::size_t>(rank) + 1];
  auto owner = [&](long node) {
    return static_cast<int>(std::upper_bound(first.begin(), first.end(), node) - first.begin()) - 1;
  };

  // Node adjacency from the connectivity: the sparsity pattern, exactly. A node
  // whose DOF are expressed through other nodes' reduced DOF (a rigid slave
  // through its master, a held distributing patch through the patch) links
  // those nodes instead of itself.
  std::vector<long> owner_node(static_cast<std::size_t>(map.reduced));
  for (long i = 0; i < n; ++i)
    for (int k = 0; k < map.count(i); ++k) owner_node[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] + k)] = i;
  std::vector<std::vector<long>> sources(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) {
    auto& s = sources[static_cast<std::size_t>(i)];
    for (long g : map.idx[static_cast<std::size_t>(i)]) s.push_back(owner_node[static_cast<std::size_t>(g)]);
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
  }
  std::vector<std::vector<long>> adj(static_cast<std::size_t>(n));
  std::vector<long> src;
  auto link = [&](const long* nodes, int count) {
    src.clear();
    for (int i = 0; i < count; ++i) {
      const auto& s = sources[static_cast<std::size_t>(nodes[i])];
      src.insert(src.end(), s.begin(), s.end());
    }
    for (long a : src)
      if (a >= n0 && a < n1) adj[static_cast<std::size_t>(a)].insert(adj[static_cast<std::size_t>(a)].end(), src.begin(), src.end());
  };
  for (const auto& t : mesh.triangles) link(t.data(), 3);
  for (const auto& b : mesh.beams) link(b.data(), 2);

  const long row0 = n0 < n ? map.offset[static_cast<std::size_t>(n0)] : map.reduced;
  const long row1 = n1 < n ? map.offset[static_cast<std::size_t>(n1)] : map.reduced;
  const long local = row1 - row0;
  // Node i's rows from its neighbours a (i included, sorted, unique): the
  // entries in this rank's diagonal block and off it; a is released.
  auto countRows = [&](long i, std::vector<long>& a, std::vector<PetscInt>& d_rows, std::vector<PetscInt>& o_rows) {
    a.push_back(i);
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    PetscInt d = 0, o = 0;
    for (long j : a) (j >= n0 && j < n1 ? d : o) += map.count(j);
    for (int k = 0; k < map.count(i); ++k) {
      d_rows[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] - row0 + k)] = d;
      o_rows[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] - row0 + k)] = o;
    }
    std::vector<long>().swap(a);
  };
  std::vector<PetscInt> d_nnz(static_cast<std::size_t>(local), 0), o_nnz(static_cast<std::size_t>(local), 0);
  for (long i = n0; i < n1; ++i) countRows(i, adj[static_cast<std::size_t>(i)], d_nnz, o_nnz);

  // The node-local mass pattern: node i's mass reaches the nodes it is
  // expressed through (sources[i]), all of them with each other. Every node i
  // counts, not only this rank's: a rigid slave or a patch node owned by
  // another rank puts its mass into rows this rank owns.
  std::vector<PetscInt> dm_nnz, om_nnz;
  if (nodal_mass) {
    std::vector<std::vector<long>> adj_m(static_cast<std::size_t>(n1 - n0));
    for (long i = 0; i < n; ++i) {
      const auto& s = sources[static_cast<std::size_t>(i)];
      for (long a : s)
        if (a >= n0 && a < n1) adj_m[static_cast<std::size_t>(a - n0)].insert(adj_m[static_cast<std::size_t>(a - n0)].end(), s.begin(), s.end());
    }
    dm_nnz.assign(static_cast<std::size_t>(local), 0);
    om_nnz.assign(static_cast<std::size_t>(local), 0);
    for (long i = n0; i < n1; ++i) countRows(i, adj_m[static_cast<std::size_t>(i - n0)], dm_nnz, om_nnz);
  }

  // Held patches' multipliers (reference_conditions.h): the rows alpha C T on
  // the patch DOF, their transposes in the patch DOF's rows, and an explicit
  // zero diagonal; the multiplier rows are the last ones (the last rank's).
  auto isLocal = [&](long g) { return g >= row0 && g < row1; };
  std::vector<MultiplierRows> held;
  for (std::size_t k = 0; k < map.held.size(); ++k) held.push_back(multiplierRows(map, k));
  for (const auto& h : held) {
    const long c = h.values.rows();
    const bool mine_rows = isLocal(h.first_row);
    for (long g : h.indices)
      if (isLocal(g)) (mine_rows ? d_nnz : o_nnz)[static_cast<std::size_t>(g - row0)] += static_cast<PetscInt>(c);
    if (!mine_rows) continue;
    PetscInt d = 1, o = 0;
    for (long g : h.indices) (isLocal(g) ? d : o) += 1;
    for (long i = 0; i < c; ++i) {
      d_nnz[static_cast<std::size_t>(h.first_row + i - row0)] = d;
      o_nnz[static_cast<std::size_t>(h.first_row + i - row0)] = o;
      if (nodal_mass) dm_nnz[static_cast<std::size_t>(h.first_row + i - row0)] = 1;  // the zero diagonal
    }
  }

  for (Mat* A : {&out.K, &out.M}) {
    const bool own_pattern = nodal_mass && A == &out.M;
    check(MatCreateAIJ(comm, local, local, map.reduced, map.reduced, 0, (own_pattern ? dm_nnz : d_nnz).data(), 0,
                       (own_pattern ? om_nnz : o_nnz).data(), A),
          "MatCreateAIJ");
    check(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  }
  std::vector<PetscInt>().swap(dm_nnz);
  std::vector<PetscInt>().swap(om_nnz);
  out.first_row = row0;
  out.local_rows = local;

  ElementResult er;
  Eigen::MatrixXd Kr, Mr;
  std::vector<long> idx;
  std::vector<PetscInt> pidx;
  Eigen::Matrix<PetscScalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> buf;
  out.lumped = Eigen::VectorXd::Zero(6 * n);
  long mine = 0, done = 0;
  double kdiag = 0.0;  // the largest diagonal of K, the multiplier rows' scale
  // Elements are the triangles, then the beams, then the point masses (one node each):
  // the point masses' index must not run on into the beams (it read past them).
  const long n_tri = static_cast<long>(mesh.triangles.size()), n_beam = static_cast<long>(mesh.beams.size());
  auto firstNode = [&](long e) {
    if (e < n_tri) return mesh.triangles[static_cast<std::size_t>(e)][0];
    if (e < n_tri + n_beam) return mesh.beams[static_cast<std::size_t>(e - n_tri)][0];
    return mesh.point_masses[static_cast<std::size_t>(e - n_tri - n_beam)].node;
  };
  for (long e = 0; e < elements; ++e)
    if (owner(firstNode(e)) == rank) ++mine;
  for (long e = 0; e < elements; ++e) {
    if (owner(firstNode(e)) != rank) continue;
    kernel(e, er);
    for (std::size_t a = 0; a < er.nodes.size(); ++a)
      out.lumped.segment<6>(6 * er.nodes[a]) += er.lumped.segment<6>(6 * static_cast<long>(a));
    reduceElement(map, er.nodes, er.K, Kr, idx);
    if (idx.empty()) continue;
    if (Kr.size()) kdiag = std::max(kdiag, Kr.diagonal().cwiseAbs().maxCoeff());
    pidx.assign(idx.begin(), idx.end());
    const PetscInt m = static_cast<PetscInt>(pidx.size());
    buf = Kr;
    check(MatSetValues(out.K, m, pidx.data(), m, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
    if (nodal_mass) {
      // Node by node, within the node-local pattern.
      const long a = static_cast<long>(er.nodes.size());
      for (long i = 0; i < a; ++i) {
        for (long j = 0; j < a; ++j)
          if (j != i && er.M.block(6 * i, 6 * j, 6, 6).cwiseAbs().maxCoeff() > 0.0)
            throw std::logic_error("assembly: a nodal mass pattern was asked but element " + std::to_string(e) +
                                   "'s mass couples two nodes");
        const Eigen::MatrixXd D = er.M.block(6 * i, 6 * i, 6, 6);
        if (D.cwiseAbs().maxCoeff() == 0.0) continue;
        reduceElement(map, {er.nodes[static_cast<std::size_t>(i)]}, D, Mr, idx);
        if (idx.empty()) continue;
        pidx.assign(idx.begin(), idx.end());
        const PetscInt mi = static_cast<PetscInt>(pidx.size());
        buf = Mr;
        check(MatSetValues(out.M, mi, pidx.data(), mi, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
      }
    } else {
      reduceElement(map, er.nodes, er.M, Mr, idx);
      buf = Mr;
      check(MatSetValues(out.M, m, pidx.data(), m, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
    }
    ++done;
    if (progress && rank == 0 && (done % 1024 == 0)) progress(static_cast<double>(done) / static_cast<double>(mine));
  }
  if (!held.empty()) {
    // Scaled to K's largest diagonal: the saddle point's pivots stay of one size
    // (the multipliers, forces / alpha, are never read).
    MPI_Allreduce(MPI_IN_PLACE, &kdiag, 1, MPI_DOUBLE, MPI_MAX, comm);
    const double alpha = kdiag > 0.0 ? kdiag : 1.0;
    for (const auto& h : held) {
      if (!isLocal(h.first_row)) continue;
      const PetscInt c = static_cast<PetscInt>(h.values.rows()), m = static_cast<PetscInt>(h.indices.size());
      std::vector<PetscInt> rows(static_cast<std::size_t>(c));
      for (PetscInt i = 0; i < c; ++i) rows[static_cast<std::size_t>(i)] = static_cast<PetscInt>(h.first_row + i);
      pidx.assign(h.indices.begin(), h.indices.end());
      buf = alpha * h.values;
      check(MatSetValues(out.K, c, rows.data(), m, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
      buf = alpha * h.values.transpose();
      check(MatSetValues(out.K, m, pidx.data(), c, rows.data(), buf.data(), ADD_VALUES), "MatSetValues");
      for (PetscInt r : rows)
        for (Mat A : {out.K, out.M}) check(MatSetValue(A, r, r, 0.0, ADD_VALUES), "MatSetValue");
    }
  }
  for (Mat A : {out.K, out.M}) {
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    check(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  }
  MPI_Allreduce(MPI_IN_PLACE, out.lumped.data(), static_cast<int>(out.lumped.size()), MPI_DOUBLE, MPI_SUM, comm);
  if (progress && rank == 0) progress(1.0);
}

void addNodalTranslationalMass(MPI_Comm comm, const Mesh& mesh, const DofMap& map, const Eigen::VectorXd& dm, Mat M) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const auto first = nodeOwnership(mesh.nodeCount(), size);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(6, 6), Dr;
  std::vector<long> idx;
  std::vector<PetscInt> pidx;
  Eigen::Matrix<PetscScalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> buf;
  for (long k = first[static_cast<std::size_t>(rank)]; k < first[static_cast<std::size_t>(rank) + 1]; ++k) {
    if (dm(k) == 0.0 || map.idx[static_cast<std::size_t>(k)].empty()) continue;
    D.topLeftCorner<3, 3>() = dm(k) * Eigen::Matrix3d::Identity();
    reduceElement(map, {k}, D, Dr, idx);
    pidx.assign(idx.begin(), idx.end());
    buf = Dr;
    const PetscInt m = static_cast<PetscInt>(pidx.size());
    check(MatSetValues(M, m, pidx.data(), m, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
  }
  check(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

}  // namespace fc::feprep
