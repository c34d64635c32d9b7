#pragma once
// Residual-flexibility (static) correction of a free-interface basis (issue
// 16; Craig & Kurdila, Fundamentals of Structural Dynamics, 2nd ed., sec.
// 19.3 on attachment modes and MacNeal's residual flexibility; Chrono's
// modal "static correction" modes do the same).
//
// The kept modes Phi (M-orthonormal, K Phi = M Phi Lambda) of the held body
// miss part of the static response A = K^-1 F to unit loads F at the
// interfaces. The residual (attachment) vectors
//   R = A - Phi (Phi^T M A)
// are A's M-orthogonal complement to the modes (also K-orthogonal:
// Phi^T K R = Lambda Phi^T M R = 0). The augmented basis B = [Phi R] contains
// every static response to the unit loads exactly, and so reproduces the
// static compliance at the interfaces; diagonalising it (K_B x = lambda M_B x,
// ritzEigen) keeps the file an ordinary modal basis. By Rayleigh-Ritz the new
// eigenvalues bound the full model's from above, and the first ones (the kept
// modes, exact eigenvectors) are unchanged.
#include <Eigen/Dense>

namespace fc::feprep {

// R = A - Phi (Phi^T M A); MA = M A.
Eigen::MatrixXd residualVectors(const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& A, const Eigen::MatrixXd& MA);

struct AugmentedBasis {
  Eigen::VectorXd eigenvalues;   // ascending
  Eigen::MatrixXd coefficients;  // (n + m, k): the new shapes are [Phi R] coefficients, M-orthonormal
  long in_span = 0;              // unit loads whose static response the modes already hold (dropped)
  long dependent = 0;            // residual directions dependent on the others (dropped)
  long massless = 0;             // residual directions without mass, condensed (ritz_basis.h)
};

// Phi (r, n) and lambda (n) the kept modes; R (r, m) the residual vectors and
// KR = K R, MR = M R; KA_diag(j) = A_j^T K A_j, the static energy of load j.
// A residual whose energy R_j^T K R_j is below 1e-12 of its load's is in the
// span already and dropped; the others are scaled to R^T K R = lambda_n before
// the reduced eigenproblem so that every column weighs alike.
AugmentedBasis augmentBasis(const Eigen::MatrixXd& Phi, const Eigen::VectorXd& lambda, const Eigen::MatrixXd& R,
                            const Eigen::MatrixXd& KR, const Eigen::MatrixXd& MR, const Eigen::VectorXd& KA_diag);

}  // namespace fc::feprep
