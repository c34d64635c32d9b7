#pragma once
// Assembly of the reduced stiffness and mass matrices, into the backend's
// matrices (la_backend.h). PETSc: MPIAIJ matrices; every rank holds the whole
// (small) mesh, rank r owns a contiguous block of nodes and the rows of their
// reduced DOF, and computes the elements whose first node it owns, so each
// element is computed once. Serial: Eigen's upper triangles on the exact
// pattern of the same connectivity.

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "fe-prep/reference_conditions.h"
#include "fe-prep/element_kernel.h"
#include "fe-prep/mesh.h"
#include "la_backend.h"

namespace fc::feprep {


// Contiguous node ranges per rank: nodes [first[r], first[r+1]).
std::vector<long> nodeOwnership(long n_nodes, int ranks);

// `elements`: number of elements; `kernel` fills one. progress(done) is called
// on rank 0 as elements are processed (fraction of its share).
// nodal_mass: every element mass matrix is block diagonal by node (lumped
// masses, point masses), so M gets its own node-local pattern (a node's
// reduced DOF and those it is expressed through) instead of K's: at 1e6 DOF
// K's pattern would hold ~4e7 explicit zeros in M. An element mass that
// couples two nodes is then a logic error.
void assemble(Comm comm, const Mesh& mesh, const DofMap& map, long elements, const ElementKernel& kernel,
              AssembledSystem& out, const std::function<void(double)>& progress = {}, bool nodal_mass = false);

// The free body's K and M (FREE_MAP: the couplings alone) taken from HELD,
// assembled over HELD_MAP, instead of assembled again, where HELD_MAP's nodal
// reduced DOF are FREE_MAP's (sameNodalDofs: a reference that holds
// distributing patches by multipliers and nothing else): HELD's leading nodal
// block, the same numbers in the same pattern as an assembly over FREE_MAP.
// Returns false, OUT untouched, where it cannot: a condition eliminated DOF,
// or the backend keeps no such block (the PETSc program assembles again).
bool freeBlockOf(const AssembledSystem& held, const DofMap& held_map, const DofMap& free_map, AssembledSystem& out);

// Adds dm_k to the three translational diagonal entries of every node this rank
// owns (in reduced DOF through the node's T) and re-assembles M.
void addNodalTranslationalMass(Comm comm, const Mesh& mesh, const DofMap& map, const Eigen::VectorXd& dm, SystemMatrix M);

}  // namespace fc::feprep
