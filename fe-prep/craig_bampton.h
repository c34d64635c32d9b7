#pragma once
// Hurty-Craig-Bampton reduction (Craig & Bampton, AIAA J. 6 (1968) 1313-1319;
// Craig & Kurdila, Fundamentals of Structural Dynamics, 2nd ed., ch. 18):
// the basis is one static constraint mode per boundary DOF plus the
// fixed-interface normal modes,
//   psi_j = l_j + T r_j,  (T^T K T) r_j = -T^T K l_j,
// l_j any motion that gives boundary DOF j a unit value and the others zero (a
// "lift"), T the reference-condition map (fixed interfaces), so psi_j is the
// static response to that unit boundary motion. With B = [Psi Phi] the reduced
// K_r = B^T K B, M_r = B^T M B (of the free body) are diagonalised,
// K_r x = lambda M_r x (ritzEigen: massless directions condensed); the eigenvectors that are rigid motions (their share of
// the rigid-motion space above one half) are removed, the others give the
// file's shapes B x (M-orthonormal) and eigenvalues, so /modes/ keeps its
// meaning (contracts.md, fe-prep, reduction: craig_bampton).
#include <mpi.h>
#include <petscmat.h>

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "fe-prep/reference_conditions.h"

namespace fc::feprep {

struct CraigBamptonInput {
  Mat K_fixed = nullptr;           // reduced with the reference conditions (T)
  const DofMap* fixed = nullptr;   // T
  Mat K_free = nullptr, M_free = nullptr;  // the free body (couplings only)
  const DofMap* free = nullptr;
  Eigen::MatrixXd lifts;           // (6 n, n_boundary) full nodal vectors
  Eigen::MatrixXd K_lifts;         // (6 n, n_boundary) K l_j, full (from the elements)
  Eigen::MatrixXd normal;          // (6 n, n_normal) fixed-interface modes, full
  Eigen::MatrixXd rigid;           // (6 n, 6) rigid motions, full
};

struct CraigBamptonResult {
  Eigen::VectorXd eigenvalues;     // ascending
  Eigen::MatrixXd shapes;          // (6 n, n_shapes), M-orthonormal
  Eigen::MatrixXd constraint_modes;// (6 n, n_boundary), the static constraint modes
  // (n_shapes, n_normal): row i holds the fixed-interface modal amplitudes of
  // unit shape i (the last n_normal rows of the Ritz eigenvector), so a state q
  // has eta = F^T q and each fixed-interface mode's strain energy is
  // lambda_j eta_j^2 / 2 exactly (the reduced K is block diagonal: the
  // constraint modes' Guyan block and diag(lambda)).
  Eigen::MatrixXd fixed_interface_coordinates;
  Eigen::VectorXd rigid_eigenvalues;
  double rigid_share_removed_min = 1.0, rigid_share_kept_max = 0.0;
  long massless_condensed = 0;     // basis directions without mass, condensed (ritz_basis.h)
};

CraigBamptonResult craigBampton(MPI_Comm comm, const CraigBamptonInput& in);

// Boundary DOF of one reference condition: C (c x 6 p) on the full DOF of
// `nodes`; appends one lift per independent row (C^+ e_j on those nodes).
void appendLifts(long n_nodes, const std::vector<long>& nodes, const Eigen::MatrixXd& C, std::vector<Eigen::VectorXd>& lifts);

}  // namespace fc::feprep
