#pragma once
// Static responses of the reduced (reference-held) body, and the static
// truncation error of a set of modes at the interfaces ("modes
// chosen by error").
//
// A unit load e_k (k: force x, y, z, moment x, y, z) at an interface reaches
// the nodes as f = L^T e_k, L (6 x 6n) the interface's map (the rigid offset
// from its node, or the distributing fit W). The exact static deflection in the
// loaded direction is delta_k = e_k^T L K^-1 L^T e_k (K with the reference
// conditions, T^T K T); the modes' is sum_j s_jk^2 / lambda_j, s_jk = (L phi_j)_k
// the interface's shape (mass-normalised phi_j). Per mode, its participation
// p_jk = s_jk^2 / (lambda_j delta_k); the truncation error of the first n modes
// e_k(n) = 1 - sum_{j<n} p_jk, the share of the static deflection they miss
// (0 <= e <= 1 as the modes are K-orthogonal and complete).
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "fe-prep/reference_conditions.h"
#include "la_backend.h"

namespace fc::feprep {

// T^T f: a full nodal force vector to the reduced DOF of `map`.
Eigen::VectorXd reduceForce(const DofMap& map, const Eigen::VectorXd& f);

// K^-1 rhs for reduced right-hand sides (reduced DOF, m), one factorisation
// (MUMPS, the backend's: fe-prep/la/*/); every rank gets the whole result.
// `held`: reduced DOF replaced by unit rows and columns scaled to K's largest
// diagonal (returned in *kmax), the support of an inertia-relief solve; the
// right-hand side must be zero there. Throws std::runtime_error(singular) if
// the factorisation finds K singular, fc::OutOfMemory if it runs out of memory.
Eigen::MatrixXd solveReduced(Comm comm, SystemMatrix K, const Eigen::MatrixXd& rhs, const char* singular,
                             const std::vector<long>& held = {}, double* kmax = nullptr);

// Full nodal displacements (6 n, m) of the reduced system K (map) under full
// nodal forces (6 n, m); MUMPS Cholesky, every rank gets the whole result.
// Throws std::runtime_error if K is singular (rigid motions left free).
Eigen::MatrixXd solveStatic(Comm comm, SystemMatrix K, const DofMap& map, const Eigen::MatrixXd& forces);

// Inertia relief (free or partly held bodies, r >= 1 rigid motions left by the
// reference; MSC Nastran's inertia relief, Craig & Kurdila sec. 19.3 on
// attachment modes of free structures): the loads are balanced by the inertia
// forces of the rigid-body accelerations they cause, f_e = P f with
// P = I - M R G^-1 R^T (R the admissible rigid modes, G = R^T M R), so that
// R^T f_e = 0; K u_s = f_e is solved on a statically determinate support (r
// reduced DOF where R's rows are best conditioned, a column-pivoted QR of R^T:
// its reactions vanish for an equilibrated load, so K u_s = f_e holds
// everywhere), and the rigid part is removed, u = P^T u_s = u_s - R G^-1 R^T M u_s
// (the elastic flexibility G_e = P^T K_s^-1 P, M-orthogonal to the rigid modes,
// equal to the sum over every elastic mode of phi phi^T / lambda). Returns the
// full nodal displacements (6 n, m); every rank gets the whole result. Throws
// std::runtime_error if K has a null space beyond R (a mechanism).
Eigen::MatrixXd solveInertiaRelief(Comm comm, SystemMatrix K, SystemMatrix M, const DofMap& map, const Eigen::MatrixXd& rigid,
                                   const Eigen::MatrixXd& forces);

struct StaticTruncation {
  Eigen::MatrixXd participation;  // (n_modes, 6) p_jk; zero in held directions
  Eigen::VectorXd error;          // (6) e_k of all the modes given; zero in held directions
  std::array<bool, 6> held{};     // direction k held by the reference
  Eigen::VectorXd compliance;     // (6) delta_k, the exact static deflection per unit load
};

// map_rows: L (6, 6 n) of the interface; shapes (n_modes, 6) its modal shapes.
// scale: the largest compliance of the body in each kind (forces, moments):
// directions below 1e-9 of it are held.
StaticTruncation staticTruncation(const Eigen::VectorXd& compliance, const Eigen::MatrixXd& shapes,
                                  const Eigen::VectorXd& eigenvalues, const Eigen::Vector2d& scale);

// Smallest number of leading modes whose error e_k is <= target for the unit
// forces (the deflections; moments are reported, not chosen on) at every
// interface (n_modes if none is); *worst: the error left with that number.
long modesForStaticError(const std::vector<StaticTruncation>& t, double target, double* worst = nullptr);

}  // namespace fc::feprep
