#pragma once
// How the constrained formulation applies (M + a Phi^T Phi)^-1 (scene
// `simulation: {linear_solver: ...}`): a plain choice the Model carries and the
// solver (constrained/augmented_lagrangian.h, AlSolver) acts on, kept here so
// that the constant Model includes nothing of the engine.
namespace fc::mbs {

// Automatic: block Schur complement with a dense joint-space matrix up to
// AlSolver::kMaxDenseSchurRows constraint rows, with a sparse one above;
// BlockSchur and SparseSchur force one of those; SparseLdlt factorises the
// whole matrix (augmented_lagrangian.h explains each).
enum class AlMethod { Automatic, BlockSchur, SparseSchur, SparseLdlt };

}  // namespace fc::mbs
