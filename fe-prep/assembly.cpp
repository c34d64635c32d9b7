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
              AssembledSystem& out, const std::function<void(double)>& progress) {
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
  std::vector<PetscInt> d_nnz(static_cast<std::size_t>(local), 0), o_nnz(static_cast<std::size_t>(local), 0);
  for (long i = n0; i < n1; ++i) {
    auto& a = adj[static_cast<std::size_t>(i)];
    a.push_back(i);
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    PetscInt d = 0, o = 0;
    for (long j : a) (j >= n0 && j < n1 ? d : o) += map.count(j);
    for (int k = 0; k < map.count(i); ++k) {
      d_nnz[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] - row0 + k)] = d;
      o_nnz[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] - row0 + k)] = o;
    }
    std::vector<long>().swap(a);
  }

  for (Mat* A : {&out.K, &out.M}) {
    check(MatCreateAIJ(comm, local, local, map.reduced, map.reduced, 0, d_nnz.data(), 0, o_nnz.data(), A),
          "MatCreateAIJ");
    check(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  }
  out.first_row = row0;
  out.local_rows = local;

  ElementResult er;
  Eigen::MatrixXd Kr, Mr;
  std::vector<long> idx;
  std::vector<PetscInt> pidx;
  Eigen::Matrix<PetscScalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> buf;
  out.lumped = Eigen::VectorXd::Zero(6 * n);
  long mine = 0, done = 0;
  for (long e = 0; e < elements; ++e) {
    const long first_node = !mesh.triangles.empty() && e < static_cast<long>(mesh.triangles.size())
                                ? mesh.triangles[static_cast<std::size_t>(e)][0]
                                : mesh.beams[static_cast<std::size_t>(e - static_cast<long>(mesh.triangles.size()))][0];
    if (owner(first_node) == rank) ++mine;
  }
  for (long e = 0; e < elements; ++e) {
    const long first_node = e < static_cast<long>(mesh.triangles.size())
                                ? mesh.triangles[static_cast<std::size_t>(e)][0]
                                : mesh.beams[static_cast<std::size_t>(e - static_cast<long>(mesh.triangles.size()))][0];
    if (owner(first_node) != rank) continue;
    kernel(e, er);
    for (std::size_t a = 0; a < er.nodes.size(); ++a)
      out.lumped.segment<6>(6 * er.nodes[a]) += er.lumped.segment<6>(6 * static_cast<long>(a));
    reduceElement(map, er.nodes, er.K, Kr, idx);
    if (idx.empty()) continue;
    reduceElement(map, er.nodes, er.M, Mr, idx);
    pidx.assign(idx.begin(), idx.end());
    const PetscInt m = static_cast<PetscInt>(pidx.size());
    buf = Kr;
    check(MatSetValues(out.K, m, pidx.data(), m, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
    buf = Mr;
    check(MatSetValues(out.M, m, pidx.data(), m, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
    ++done;
    if (progress && rank == 0 && (done % 1024 == 0)) progress(static_cast<double>(done) / static_cast<double>(mine));
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
