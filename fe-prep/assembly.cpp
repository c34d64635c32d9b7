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

namespace {

// This rank's share: its nodes [n0, n1) and their reduced rows [row0, row1).
struct Partition {
  int rank = 0, size = 1;
  std::vector<long> first;  // nodeOwnership
  long n = 0, n0 = 0, n1 = 0, row0 = 0, row1 = 0, local = 0;
  int owner(long node) const {
    return static_cast<int>(std::upper_bound(first.begin(), first.end(), node) - first.begin()) - 1;
  }
  bool ownsNode(long node) const { return node >= n0 && node < n1; }
  bool ownsRow(long g) const { return g >= row0 && g < row1; }
};

Partition partition(MPI_Comm comm, const Mesh& mesh, const DofMap& map) {
  Partition p;
  MPI_Comm_rank(comm, &p.rank);
  MPI_Comm_size(comm, &p.size);
  p.n = mesh.nodeCount();
  p.first = nodeOwnership(p.n, p.size);
  p.n0 = p.first[static_cast<std::size_t>(p.rank)];
  p.n1 = p.first[static_cast<std::size_t>(p.rank) + 1];
  p.row0 = p.n0 < p.n ? map.offset[static_cast<std::size_t>(p.n0)] : map.reduced;
  p.row1 = p.n1 < p.n ? map.offset[static_cast<std::size_t>(p.n1)] : map.reduced;
  p.local = p.row1 - p.row0;
  return p;
}


// Entries per local row in this rank's diagonal block (d) and off it (o): PETSc's preallocation.
struct RowCounts {
  std::vector<PetscInt> d, o;
};

// Node i's rows from its neighbours a (i included, sorted, unique): the
// entries in this rank's diagonal block and off it; a is released.
void countRows(const Partition& p, const DofMap& map, long i, std::vector<long>& a, RowCounts& rows) {
  a.push_back(i);
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  PetscInt d = 0, o = 0;
  for (long j : a) (p.ownsNode(j) ? d : o) += map.count(j);
  for (int k = 0; k < map.count(i); ++k) {
    rows.d[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] - p.row0 + k)] = d;
    rows.o[static_cast<std::size_t>(map.offset[static_cast<std::size_t>(i)] - p.row0 + k)] = o;
  }
  std::vector<long>().swap(a);
}

// K's pattern: node adjacency from the connectivity, exactly, through each
// node's sources.
RowCounts stiffnessPattern(const Partition& p, const Mesh& mesh, const DofMap& map,
                           const std::vector<std::vector<long>>& sources) {
  std::vector<std::vector<long>> adj(static_cast<std::size_t>(p.n));
  std::vector<long> src;
  auto link = [&](const long* nodes, int count) {
    elementSources(sources, nodes, count, src);
    for (long a : src)
      if (p.ownsNode(a)) adj[static_cast<std::size_t>(a)].insert(adj[static_cast<std::size_t>(a)].end(), src.begin(), src.end());
  };
  for (const auto& t : mesh.triangles) link(t.data(), 3);
  for (const auto& b : mesh.beams) link(b.data(), 2);
  RowCounts rows{std::vector<PetscInt>(static_cast<std::size_t>(p.local), 0),
                 std::vector<PetscInt>(static_cast<std::size_t>(p.local), 0)};
  for (long i = p.n0; i < p.n1; ++i) countRows(p, map, i, adj[static_cast<std::size_t>(i)], rows);
  return rows;
}

// The node-local mass pattern: node i's mass reaches the nodes it is
// expressed through (sources[i]), all of them with each other. Every node i
// counts, not only this rank's: a rigid slave or a patch node owned by
// another rank puts its mass into rows this rank owns.
RowCounts nodalMassPattern(const Partition& p, const DofMap& map, const std::vector<std::vector<long>>& sources) {
  std::vector<std::vector<long>> adj_m(static_cast<std::size_t>(p.n1 - p.n0));
  for (long i = 0; i < p.n; ++i) {
    const auto& s = sources[static_cast<std::size_t>(i)];
    for (long a : s)
      if (p.ownsNode(a)) adj_m[static_cast<std::size_t>(a - p.n0)].insert(adj_m[static_cast<std::size_t>(a - p.n0)].end(), s.begin(), s.end());
  }
  RowCounts rows{std::vector<PetscInt>(static_cast<std::size_t>(p.local), 0),
                 std::vector<PetscInt>(static_cast<std::size_t>(p.local), 0)};
  for (long i = p.n0; i < p.n1; ++i) countRows(p, map, i, adj_m[static_cast<std::size_t>(i - p.n0)], rows);
  return rows;
}

// Held patches' multipliers (reference_conditions.h): the rows alpha C T on
// the patch DOF, their transposes in the patch DOF's rows, and an explicit
// zero diagonal; the multiplier rows are the last ones (the last rank's).
// mass: the nodal mass pattern, null without one.
void addMultiplierPattern(const Partition& p, const std::vector<MultiplierRows>& held, RowCounts& stiffness,
                          RowCounts* mass) {
  for (const auto& h : held) {
    const long c = h.values.rows();
    const bool mine_rows = p.ownsRow(h.first_row);
    for (long g : h.indices)
      if (p.ownsRow(g)) (mine_rows ? stiffness.d : stiffness.o)[static_cast<std::size_t>(g - p.row0)] += static_cast<PetscInt>(c);
    if (!mine_rows) continue;
    PetscInt d = 1, o = 0;
    for (long g : h.indices) (p.ownsRow(g) ? d : o) += 1;
    for (long i = 0; i < c; ++i) {
      stiffness.d[static_cast<std::size_t>(h.first_row + i - p.row0)] = d;
      stiffness.o[static_cast<std::size_t>(h.first_row + i - p.row0)] = o;
      if (mass) mass->d[static_cast<std::size_t>(h.first_row + i - p.row0)] = 1;  // the zero diagonal
    }
  }
}

// K and M preallocated, M on its own pattern when there is one (mass not null).
void createMatrices(MPI_Comm comm, const Partition& p, const DofMap& map, RowCounts& stiffness, RowCounts* mass,
                    AssembledSystem& out) {
  for (Mat* A : {&out.K, &out.M}) {
    RowCounts& rows = mass && A == &out.M ? *mass : stiffness;
    check(MatCreateAIJ(comm, p.local, p.local, map.reduced, map.reduced, 0, rows.d.data(), 0, rows.o.data(), A),
          "MatCreateAIJ");
    check(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  }
  out.first_row = p.row0;
  out.local_rows = p.local;
}

using RowMajor = Eigen::Matrix<PetscScalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Element e's mass node by node, within the node-local pattern.
void addNodalMassBlocks(const DofMap& map, long e, const ElementResult& er, Mat M) {
  Eigen::MatrixXd Mr;
  std::vector<long> idx;
  std::vector<PetscInt> pidx;
  RowMajor buf;
  const long a = static_cast<long>(er.nodes.size());
  for (long i = 0; i < a; ++i) {
    const Eigen::MatrixXd D = nodalMassBlock(er, e, i);
    if (D.cwiseAbs().maxCoeff() == 0.0) continue;
    reduceElement(map, {er.nodes[static_cast<std::size_t>(i)]}, D, Mr, idx);
    if (idx.empty()) continue;
    pidx.assign(idx.begin(), idx.end());
    const PetscInt mi = static_cast<PetscInt>(pidx.size());
    buf = Mr;
    check(MatSetValues(M, mi, pidx.data(), mi, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
  }
}

// The elements whose first node this rank owns, into K, M and the lumped
// masses; returns the largest diagonal of K seen, the multiplier rows' scale.
double assembleElements(const Partition& p, const Mesh& mesh, const DofMap& map, long elements,
                        const ElementKernel& kernel, AssembledSystem& out, const std::function<void(double)>& progress,
                        bool nodal_mass) {
  ElementResult er;
  Eigen::MatrixXd Kr, Mr;
  std::vector<long> idx;
  std::vector<PetscInt> pidx;
  RowMajor buf;
  out.lumped = Eigen::VectorXd::Zero(6 * p.n);
  long mine = 0, done = 0;
  double kdiag = 0.0;
  // Elements are the triangles, then the beams, then the point masses (one node each):
  // the point masses' index must not run on into the beams (it read past them).
  const long n_tri = static_cast<long>(mesh.triangles.size()), n_beam = static_cast<long>(mesh.beams.size());
  auto firstNode = [&](long e) {
    if (e < n_tri) return mesh.triangles[static_cast<std::size_t>(e)][0];
    if (e < n_tri + n_beam) return mesh.beams[static_cast<std::size_t>(e - n_tri)][0];
    return mesh.point_masses[static_cast<std::size_t>(e - n_tri - n_beam)].node;
  };
  for (long e = 0; e < elements; ++e)
    if (p.owner(firstNode(e)) == p.rank) ++mine;
  for (long e = 0; e < elements; ++e) {
    if (p.owner(firstNode(e)) != p.rank) continue;
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
      addNodalMassBlocks(map, e, er, out.M);
    } else {
      reduceElement(map, er.nodes, er.M, Mr, idx);
      buf = Mr;
      check(MatSetValues(out.M, m, pidx.data(), m, pidx.data(), buf.data(), ADD_VALUES), "MatSetValues");
    }
    ++done;
    if (progress && p.rank == 0 && (done % 1024 == 0)) progress(static_cast<double>(done) / static_cast<double>(mine));
  }
  return kdiag;
}

// The held patches' multiplier rows, scaled to K's largest diagonal: the
// saddle point's pivots stay of one size (the multipliers, forces / alpha,
// are never read).
void addMultiplierRows(MPI_Comm comm, const Partition& p, const std::vector<MultiplierRows>& held, double kdiag,
                       AssembledSystem& out) {
  MPI_Allreduce(MPI_IN_PLACE, &kdiag, 1, MPI_DOUBLE, MPI_MAX, comm);
  const double alpha = kdiag > 0.0 ? kdiag : 1.0;
  std::vector<PetscInt> pidx;
  RowMajor buf;
  for (const auto& h : held) {
    if (!p.ownsRow(h.first_row)) continue;
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

void finishMatrices(MPI_Comm comm, AssembledSystem& out) {
  for (Mat A : {out.K, out.M}) {
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    check(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  }
  MPI_Allreduce(MPI_IN_PLACE, out.lumped.data(), static_cast<int>(out.lumped.size()), MPI_DOUBLE, MPI_SUM, comm);
}

}  // namespace

// The stages: this rank's share, the sparsity patterns (K's from the
// connectivity, M's node-local one, the multiplier rows'), the matrices, the
// element loop, the multiplier rows, the final assembly.
void assemble(MPI_Comm comm, const Mesh& mesh, const DofMap& map, long elements, const ElementKernel& kernel,
              AssembledSystem& out, const std::function<void(double)>& progress, bool nodal_mass) {
  const Partition p = partition(comm, mesh, map);
  std::vector<MultiplierRows> held;
  for (std::size_t k = 0; k < map.held.size(); ++k) held.push_back(multiplierRows(map, k));
  {
    std::vector<std::vector<long>> sources = nodeSources(map, p.n);
    RowCounts stiffness = stiffnessPattern(p, mesh, map, sources);
    RowCounts mass = nodal_mass ? nodalMassPattern(p, map, sources) : RowCounts{};
    std::vector<std::vector<long>>().swap(sources);
    addMultiplierPattern(p, held, stiffness, nodal_mass ? &mass : nullptr);
    createMatrices(comm, p, map, stiffness, nodal_mass ? &mass : nullptr, out);
  }
  const double kdiag = assembleElements(p, mesh, map, elements, kernel, out, progress, nodal_mass);
  if (!held.empty()) addMultiplierRows(comm, p, held, kdiag, out);
  finishMatrices(comm, out);
  if (progress && p.rank == 0) progress(1.0);
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

// A distributed matrix keeps no leading block to hand over cheaply
// (MatCreateSubMatrix would redistribute it): the driver assembles again.
bool freeBlockOf(const AssembledSystem&, const DofMap&, const DofMap&, AssembledSystem&) { return false; }

}  // namespace fc::feprep
