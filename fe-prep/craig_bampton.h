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
// Two stages, so that the free body's matrices are assembled only after the
// constraint modes' factorisation is freed: constraintModes, then craigBampton.
#include <Eigen/Dense>
#include <functional>
#include <map>
#include <vector>

#include "fe-prep/reference_conditions.h"
#include "la_backend.h"

namespace fc::feprep {

// The boundary DOF's lifts and their products K l_j live on a patch and its
// neighbours: stored per node, node -> (6, n_boundary) rows, never as
// n_boundary full vectors of zeros.
using NodeRows = std::map<long, Eigen::MatrixXd>;

// One lift while the boundary DOF are gathered: node -> its six values.
using Lift = std::map<long, Eigen::Matrix<double, 6, 1>>;

// Boundary DOF of one reference condition: C (c x 6 p) on the full DOF of
// `nodes`; appends one lift per independent row (C^+ e_j on those nodes).
void appendLifts(const std::vector<long>& nodes, const Eigen::MatrixXd& C, std::vector<Lift>& lifts);

// The lifts as node rows (6, n_lifts), in ascending node order.
NodeRows liftRows(const std::vector<Lift>& lifts);

struct ConstraintModeInput {
  SystemMatrix K_fixed = nullptr;            // reduced with the reference conditions (T)
  const DofMap* fixed = nullptr;    // T
  long n_nodes = 0;
  long n_boundary = 0;
  NodeRows lifts;                   // l_j on the nodes they touch
  NodeRows K_lifts;                 // K l_j (from the elements), on the nodes it touches
  const Eigen::MatrixXd* normal = nullptr;  // (T's reduced DOF, n_normal) fixed-interface modes
  // K_fixed's factor from the fixed-interface eigen-solve (shift 0,
  // `ModalResult::factor_of_K`), or null: factorise here.
  FactorRef factored = nullptr;
};

// The basis B = [Psi Phi] (6 n, n_boundary + n_normal), full nodal vectors:
// the constraint modes solved one right-hand side at a time on one MUMPS
// factorisation of the fixed-interface K (its own, freed before returning, or
// the fixed-interface eigen-solve's, `factored`), the
// fixed-interface modes expanded beside them. B is the only dense block of
// this size the reduction holds while the factor is alive.
struct CraigBamptonBasis {
  Eigen::MatrixXd B;
  long n_boundary = 0;
  MumpsMemory factorisation;
};
CraigBamptonBasis constraintModes(Comm comm, const ConstraintModeInput& in);

struct CraigBamptonResult {
  Eigen::VectorXd eigenvalues;     // ascending
  Eigen::MatrixXd shapes;          // (6 n, n_shapes), M-orthonormal
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

// K_r = B^T K B, M_r = B^T M B on the free body (K_free, M_free on `free`'s
// reduced DOF, couplings only), diagonalised, rigid motions removed. Works in
// one dense (free DOF, n_basis) block beside B (none when `free` keeps every
// DOF as it is: B itself is used) and the shapes it returns; B is released.
CraigBamptonResult craigBampton(Comm comm, CraigBamptonBasis basis, SystemMatrix K_free, SystemMatrix M_free, const DofMap& free,
                                const Eigen::MatrixXd& rigid);

}  // namespace fc::feprep
