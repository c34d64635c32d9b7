#pragma once
// The augmented Lagrangian index-3-free formulation of Bayo, Garcia de Jalon &
// Serna (1988) and Bayo & Ledesma (1996, Nonlinear Dynamics 9:113-130):
//   (M + Phi_v^T a Phi_v) vdot_{k+1} = Q - Phi_v^T (lambda_k + a s),
//   lambda_{k+1} = lambda_k + a (Phi_v vdot_{k+1} + s),
//   s = c + 2 xi omega Phi_dot + omega^2 Phi          (stabilisation)
// starting from lambda_0 = 0. The leading matrix is positive definite whenever M
// is, whatever the rank of Phi_v, so redundant constraints and singular
// configurations never make the solve fail: the iteration converges to the
// least-squares-consistent accelerations, and lambda to one set of multipliers.
// After a step the state is projected mass-orthogonally onto the constraint
// manifold (positions) and its tangent (velocities) with the same matrix.
//
// Three ways to apply K^-1, K = M + a Phi_v^T Phi_v, same iteration, same
// answers to rounding:
// - block Schur: M is block diagonal, one dense block per body, so
//     K^-1 = M^-1 - M^-1 Phi^T (I/a + Phi M^-1 Phi^T)^-1 Phi M^-1
//   (Sherman-Morrison-Woodbury) needs only the bodies' small blocks and one
//   factorisation of the joint-space matrix S = I/a + Phi M^-1 Phi^T. On the
//   SAR antenna (112 coordinates, 64 rows) it is several times cheaper than a
//   general sparse LDL^T of K, whose scalar elimination and index handling
//   cost more than the arithmetic at this size. S is factorised
//   - dense (BlockSchur; the default up to kMaxDenseSchurRows rows), or
//   - sparse (SparseSchur, the default above): S couples two rows only
//     where they touch a common body, so for a chain or a tree it is
//     block-sparse (block tridiagonal for a chain) and its LDL^T (Eigen's
//     SimplicialLDLT, AMD ordering: leaves first, no fill for a tree) costs
//     O(m). With the bodies' blocks that makes an evaluation O(N) in the
//     number of bodies (docs/benchmarks.md, rigid chains).
// - sparse LDL^T of K (Eigen's SimplicialLDLT, AMD ordering): whenever a
//   body's own mass block is singular (K may still be definite); forming
//   Phi^T Phi and K each time costs several times the Schur forms.
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <memory>
#include <vector>

#include "mbs-run/model/al_method.h"

namespace fc::mbs {

using SparseMatrixd = Eigen::SparseMatrix<double>;

// A symmetric block-diagonal matrix: blocks on the diagonal at the given
// offsets (the bodies' mass matrices in the velocity coordinates). A block is
// either dense (block[b] the whole n x n block, diagonal[b] empty) or an arrow
// block: block[b] holds only its first r rows (r x n) and the rest of the
// block is diag(diagonal[b]) (n - r entries), zero off the diagonal. A
// floating-frame flexible body with mass-normalised modes has that structure
// (r = 6, modal mass diagonal): stored, multiplied and factorised in O(n)
// instead of O(n^2) and O(n^3) (BlockFactor). When the modal mass is constant
// but not diagonal to rounding (modes orthonormal only to the eigensolver's
// precision), the trailing block is that constant dense matrix, factorised
// once when the body is loaded (ConstantBlock): an evaluation then costs the
// r x (n - r) coupling's triangular solve, O(r n^2), not an O(n^3) Cholesky
// of the whole block.
struct ConstantBlock {
  explicit ConstantBlock(const Eigen::MatrixXd& D);
  Eigen::MatrixXd D;
  Eigen::LLT<Eigen::MatrixXd> llt;  // D = L L^T
  bool ok() const { return llt.info() == Eigen::Success; }
};

struct BlockDiagonal {
  int size = 0;
  std::vector<int> offset;
  std::vector<Eigen::MatrixXd> block;
  std::vector<Eigen::VectorXd> diagonal;  // one per block; empty for a dense block
  // Optional, one per block (may be shorter than block): a constant dense
  // trailing block of an arrow block whose diagonal[b] is empty.
  std::vector<std::shared_ptr<const ConstantBlock>> constant;

  int dim(std::size_t b) const { return int(block[b].cols()); }
  const ConstantBlock* constantBlock(std::size_t b) const { return b < constant.size() ? constant[b].get() : nullptr; }
  bool arrow(std::size_t b) const { return diagonal[b].size() > 0 || constantBlock(b) != nullptr; }
  // The whole block b, dense.
  Eigen::MatrixXd dense(std::size_t b) const;
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  SparseMatrixd toSparse() const;
  // Blocks = the contiguous diagonal ranges no entry of M couples (each a
  // dense block, zeros included); M symmetric in pattern. Body-ordered
  // coordinates give one block per body; a general matrix gives one block.
  static BlockDiagonal fromSparse(const SparseMatrixd& M);
};

// A factor F of one block, M_b = F F^T, with F^-1 and F^-T applied in place.
// Dense block: F = L, its Cholesky factor. Arrow block [A C; C^T D]:
//   F = [Ls  C D^-1/2; 0  D^1/2],  Ls Ls^T = A - C D^-1 C^T
// (the Schur complement on the small r x r block), so F^-1 and F^-T cost
// O(n r) and the factorisation O(n r^2). With a constant dense D = L_D L_D^T
// (ConstantBlock), F = [Ls  C L_D^-T; 0  L_D]: F^-1 and F^-T cost O(n^2) per
// column (triangular solves with the constant L_D) and the factorisation
// O(r n^2).
class BlockFactor {
 public:
  bool compute(const BlockDiagonal& M, std::size_t b);  // false: not positive definite
  void solveF(Eigen::Ref<Eigen::MatrixXd> X) const;     // X <- F^-1 X
  void solveFT(Eigen::Ref<Eigen::VectorXd> x) const;    // x <- F^-T x

 private:
  int r_ = 0;  // leading rows of an arrow block; 0 for a dense block
  Eigen::LLT<Eigen::MatrixXd> llt_;  // of the block, or of the arrow's Schur complement
  Eigen::MatrixXd E_;                // C D^-1/2 (r x (n - r)), or C L_D^-T
  Eigen::VectorXd dh_;               // D^1/2 (diagonal D)
  std::shared_ptr<const ConstantBlock> constant_;  // dense constant D, else null
};

struct AlResult {
  Eigen::VectorXd vdot;
  Eigen::VectorXd lambda;
  int iterations = 0;
  double residual = 0.0;  // ||Phi_v vdot + s||_inf at the end
};

// Holds the factorised K for one configuration, with copies of M and Phi_v,
// and runs the multiplier iterations against it.
class AlSolver {
 public:
  // Automatic: block Schur with a dense S while the rows are at most this
  // many, with a sparse S above (and the sparse LDL^T of K when a body's
  // block is singular). Measured: see kMaxDenseSchurRows's note in
  // docs/mbs-run.md ("Cost").
  static constexpr int kMaxDenseSchurRows = 120;

  void setMethod(AlMethod method) { method_ = method; }
  // Factorises M + alpha Phi_v^T Phi_v.
  void factorize(const BlockDiagonal& M, const SparseMatrixd& Phi_v, double alpha);
  void factorize(const SparseMatrixd& M, const SparseMatrixd& Phi_v, double alpha);

  // The iteration above; stops when the constraint residual is below tol and
  // the correction has reached rounding, or after max_iterations.
  AlResult accelerations(const Eigen::VectorXd& Q, const Eigen::VectorXd& s, double tol,
                         int max_iterations) const;
  // Mass-orthogonal velocity projection: min 1/2 (v - v0)^T M (v - v0)
  // subject to Phi_v v + Phi_t = 0, by the same multiplier iteration.
  Eigen::VectorXd projectVelocities(const Eigen::VectorXd& v0, const Eigen::VectorXd& phit, double tol,
                                    int max_iterations) const;
  // One linearised position correction: dq minimising 1/2 (d + dq)^T M (d + dq)
  // with Phi + Phi_v dq = 0, d the correction accumulated so far.
  Eigen::VectorXd positionCorrection(const Eigen::VectorXd& phi, const Eigen::VectorXd& accumulated,
                                     double tol, int max_iterations) const;

  double alpha() const { return alpha_; }
  bool ok() const { return ok_; }
  // The method of the last factorisation (never Automatic).
  AlMethod methodUsed() const { return used_; }

 private:
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const;  // K^-1 r
  void forwardBlocks(Eigen::VectorXd& y, Eigen::VectorXd& u) const;
  void backwardBlocks(Eigen::VectorXd& x, const Eigen::VectorXd& z) const;
  Eigen::VectorXd multiplyM(const Eigen::VectorXd& x) const;
  bool factorizeSchur();
  void factorizeSparse();
  Eigen::VectorXd iterate(const Eigen::VectorXd& b, const Eigen::VectorXd& g, double tol, int max_it,
                          bool stop_on_stall, Eigen::VectorXd* mu_out, int* its, double* res) const;

  AlMethod method_ = AlMethod::Automatic;
  AlMethod used_ = AlMethod::BlockSchur;
  double alpha_ = 1.0;
  bool ok_ = false;
  BlockDiagonal M_;
  SparseMatrixd Phi_;

  // Block Schur: per block, the rows of Phi that touch it, the Cholesky
  // factor L of the block and V = L^-1 Phi_b^T, so that the block adds V^T V
  // to Phi M^-1 Phi^T. The row lists and the position of each of the block's
  // nonzeros of Phi in V^T are kept while Phi's pattern is unchanged.
  struct BlockData {
    std::vector<int> rows;
    std::vector<int> slot;  // per nonzero of the block's columns: its row's index in `rows`
    Eigen::MatrixXd V, G;
    BlockFactor factor;
  };
  // The index arrays of a compressed sparse matrix, to tell when its
  // pattern changes (and cached symbolic work must be redone).
  struct SparsityPattern {
    std::vector<int> outer, inner;
    bool update(const SparseMatrixd& A);  // true (and stored) if A's pattern differs
    void clear() { outer.clear(); }
  };
  bool wantsSchur(const SparseMatrixd& Phi_v) const;
  bool wantsSparseS(int rows) const;

  std::vector<BlockData> blocks_;
  SparsityPattern phi_pattern_;
  Eigen::MatrixXd S_;  // I/a + Phi M^-1 Phi^T
  Eigen::MatrixXd s_L_;  // Cholesky factor of S (lower triangle)
  Eigen::LDLT<Eigen::MatrixXd> s_ldlt_;
  bool s_use_ldlt_ = false;
  // Sparse S, stored already permuted by its fill-reducing (AMD) ordering,
  // upper triangle: the LDL^T then factorises it in place, without the copy
  // and permutation it would make on every factorisation. s_perm_[i] is the
  // position of row i; the value slot of each diagonal entry and, per block,
  // of each (i >= j) entry of its G are kept while Phi's pattern is
  // unchanged, and the symbolic analysis likewise.
  bool s_sparse_ = false;
  SparseMatrixd S_sparse_;
  std::vector<int> s_perm_;
  std::vector<int> s_diag_slot_;
  std::vector<std::vector<int>> s_block_slot_;
  Eigen::SimplicialLDLT<SparseMatrixd, Eigen::Upper, Eigen::NaturalOrdering<int>> s_sparse_ldlt_;
  bool s_sparse_analysed_ = false;
  void buildSparsePattern();
  mutable Eigen::VectorXd s_work_;  // solveS's permuted right-hand side
  void solveS(const Eigen::VectorXd& r, Eigen::VectorXd& x) const;
  Eigen::VectorXd iterateSchur(const Eigen::VectorXd& b, const Eigen::VectorXd& g, double tol, int max_it,
                               bool stop_on_stall, Eigen::VectorXd* mu_out, int* its, double* res) const;

  // Sparse LDL^T; the symbolic analysis is kept while K's pattern is unchanged.
  SparseMatrixd M_sparse_;
  Eigen::SimplicialLDLT<SparseMatrixd> ldlt_;
  SparsityPattern k_pattern_;
};

}  // namespace fc::mbs
