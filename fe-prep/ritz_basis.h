#pragma once
// The reduced eigenproblem of a Ritz basis B (Craig-Bampton's [Psi Phi], a
// free-interface basis augmented with attachment modes):
//   K_r x = lambda M_r x,  K_r = B^T K B,  M_r = B^T M B  (dense, small).
// Two things make M_r singular in practice, and Eigen's Cholesky-based
// generalized solver then returns rounding for an "infinite" eigenvalue and
// loses the others' accuracy:
// - directions of the basis that carry no mass but have stiffness (a shell's
//   drilling rotation: a fictitious penalty stiffness, no mass): they are
//   condensed statically, x_z = -(Z^T K_r Z)^-1 Z^T K_r Y x_y (Guyan: no load
//   acts on them), which keeps the static response to loads on the others;
// - directions that carry neither (numerically dependent vectors): dropped.
// Columns are first scaled to unit weight in mass and stiffness (relative to
// the largest), so the rank decisions compare like with like.
#include <Eigen/Dense>

namespace fc::feprep {

struct RitzSolution {
  Eigen::VectorXd eigenvalues;  // ascending
  Eigen::MatrixXd X;            // (m, k): X^T M_r X = I, X^T K_r X = diag(eigenvalues)
  long massless = 0;            // directions condensed (stiffness, no mass)
  long dependent = 0;           // directions dropped (neither)
};

// tol: relative threshold of the scaled M_r (and K_r) eigenvalues.
RitzSolution ritzEigen(const Eigen::MatrixXd& Kr, const Eigen::MatrixXd& Mr, double tol = 1e-10);

}  // namespace fc::feprep
