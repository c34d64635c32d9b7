#pragma once
// Parallel assembly of the reduced stiffness and mass matrices into PETSc
// MPIAIJ matrices. Every rank holds the whole (small) mesh; rank r owns a
// contiguous block of nodes and the rows of their reduced DOF, and computes
// the elements whose first node it owns, so each element is computed once.
#include <petscmat.h>

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "fe-prep/reference_conditions.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

// Element e: its nodes, stiffness and mass (6 DOF per node, body frame), and the
// lumped nodal mass vector (6 per node) reported in /mass/nodal.
struct ElementResult {
  std::vector<long> nodes;
  Eigen::MatrixXd K, M;
  Eigen::VectorXd lumped;
};
using ElementKernel = std::function<void(long element, ElementResult& out)>;

struct AssembledSystem {
  Mat K = nullptr, M = nullptr;
  Eigen::VectorXd lumped;  // n_nodes * 6, summed over all ranks (every rank has it)
  long first_row = 0, local_rows = 0;
  ~AssembledSystem();
  AssembledSystem() = default;
  AssembledSystem(const AssembledSystem&) = delete;
  AssembledSystem& operator=(const AssembledSystem&) = delete;
};

// Contiguous node ranges per rank: nodes [first[r], first[r+1]).
std::vector<long> nodeOwnership(long n_nodes, int ranks);

// `elements`: number of elements; `kernel` fills one. progress(done) is called
// on rank 0 as elements are processed (fraction of its share).
// nodal_mass: every element mass matrix is block diagonal by node (lumped
// masses, point masses), so M gets its own node-local pattern (a node's
// reduced DOF and those it is expressed through) instead of K's: at 1e6 DOF
// K's pattern would hold ~4e7 explicit zeros in M. An element mass that
// couples two nodes is then a logic error.
void assemble(MPI_Comm comm, const Mesh& mesh, const DofMap& map, long elements, const ElementKernel& kernel,
              AssembledSystem& out, const std::function<void(double)>& progress = {}, bool nodal_mass = false);

// Adds dm_k to the three translational diagonal entries of every node this rank
// owns (in reduced DOF through the node's T) and re-assembles M.
void addNodalTranslationalMass(MPI_Comm comm, const Mesh& mesh, const DofMap& map, const Eigen::VectorXd& dm, Mat M);

}  // namespace fc::feprep
