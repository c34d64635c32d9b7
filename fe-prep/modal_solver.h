#pragma once
// The generalized eigenproblem K x = lambda M x, shift-and-invert: in the
// PETSc program SLEPc's Krylov-Schur with the shifted matrix factorised by
// MUMPS (modal_solver.cpp), in the serial one ARPACK's Lanczos with CHOLMOD
// or MUMPS (fe-prep/la/serial/arpack_modes.cpp). The rigid-body motions the
// reference leaves free are found among the lowest modes and removed: they
// are identified by their projection on the geometric rigid-mode space, not
// by a threshold on lambda.
#include <Eigen/Dense>
#include <functional>
#include <stdexcept>

#include "la_backend.h"

namespace fc::feprep {

struct ModalRequest {
  long modes = 0;                 // lowest elastic modes wanted, or
  double max_frequency_hz = 0.0;  // all elastic modes below this frequency
  double tolerance = 1e-10;       // SLEPc relative residual tolerance
  // Shift sigma < 0 (rad/s)^2 when rigid modes exist (K singular); with all
  // lambda >= 0 > sigma the modes nearest sigma are exactly the lowest ones.
  double shift = -1.0;
  // The last `multipliers` rows of K are Lagrange multipliers of held patches
  // (reference_conditions.h): no mass, no part of a shape. Each removes one
  // DOF that carries mass from the constrained problem, and the sign
  // convention looks at the other rows only.
  long multipliers = 0;
  // Keep the shift-invert solver when the shift is 0, i.e. when it holds a
  // factorisation of K itself (a reference without rigid modes): the
  // Craig-Bampton constraint modes solve with that same K, so they need not
  // factorise it again.
  bool keep_factor = false;
  // Deflate the rigid motions (EPSSetDeflationSpace) when they are null
  // vectors of K to rounding (rigidNullResidual): Krylov-Schur then seeks only
  // the elastic pairs, in the M-orthogonal complement of the rigid space.
  // Off gives the undeflated solve, kept for the comparison test.
  bool deflate_rigid = true;
};

struct ModalResult {
  Eigen::VectorXd eigenvalues;        // elastic, ascending (omega^2)
  Eigen::MatrixXd vectors;            // reduced DOF x modes, M-orthonormal (every rank)
  Eigen::VectorXd rigid_eigenvalues;  // the removed ones (should be ~0)
  double rigid_projection_min = 1.0;  // smallest rigid-space share among the removed modes
  double rigid_projection_max = 0.0;  // largest rigid-space share among the kept modes
  long iterations = 0;
  bool deflated = false;              // the rigid motions were a deflation space
  double rigid_null_residual = 0.0;   // rigidNullResidual of the rigid basis (0 when not deflatable)
  MumpsMemory factorisation;          // the shift-invert factorisation's (the largest of the solves)
  // With keep_factor and shift 0: the eigen-solve's MUMPS factor of K, for
  // MatSolve (its memory stays held until this is released).
  FactorHandle factor_of_K;
};

// The request cannot be met: more modes than the body has with a finite
// frequency, or SLEPc failing for that reason. fe-prep locates it at `modes`.
class ModeCountError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reduced DOF that carry no mass: a zero diagonal of the positive semidefinite
// M (so a zero row and column), e.g. a shell node's drilling rotation, which
// has stiffness (the drilling penalty) but no inertia. Each is an infinite
// eigenvalue: at most N - masslessDofs(M) - r elastic modes exist.
long masslessDofs(SystemMatrix M);

// The largest ||K r_j||_inf / (||K||_inf ||r_j||_inf) over the rigid basis's
// columns: how far the geometric rigid motions are from null vectors of the
// assembled K (rounding, ~1e-16, for the shell and beam elements; more for an
// imported K written to a few digits).
double rigidNullResidual(SystemMatrix K, const Eigen::MatrixXd& rigid);

// rigid: reduced DOF x r basis of the admissible rigid motions (every rank).
// progress(converged, wanted) is called on rank 0 during the iteration.
ModalResult solveModes(Comm comm, SystemMatrix K, SystemMatrix M, const Eigen::MatrixXd& rigid, const ModalRequest& request,
                       const std::function<void(long, long)>& progress = {});

}  // namespace fc::feprep
