#include "mbs-run/constrained/augmented_lagrangian.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace fc::mbs {

using Eigen::VectorXd;

ConstantBlock::ConstantBlock(const Eigen::MatrixXd& D_) : D(D_), llt(D_) {}

Eigen::MatrixXd BlockDiagonal::dense(std::size_t b) const {
  if (!arrow(b)) return block[b];
  const int n = dim(b), r = int(block[b].rows());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  D.topRows(r) = block[b];
  D.bottomLeftCorner(n - r, r) = block[b].rightCols(n - r).transpose();
  if (const ConstantBlock* cb = constantBlock(b)) D.bottomRightCorner(n - r, n - r) = cb->D;
  else D.bottomRightCorner(n - r, n - r).diagonal() = diagonal[b];
  return D;
}

void BlockDiagonal::multiply(const VectorXd& x, VectorXd& y) const {
  y.resize(size);
  for (std::size_t b = 0; b < block.size(); ++b) {
    const int n = dim(b);
    if (!arrow(b)) {
      y.segment(offset[b], n).noalias() = block[b] * x.segment(offset[b], n);
      continue;
    }
    const int r = int(block[b].rows());
    const auto xr = x.segment(offset[b], r);
    const auto xf = x.segment(offset[b] + r, n - r);
    const auto C = block[b].rightCols(n - r);
    y.segment(offset[b], r).noalias() = block[b] * x.segment(offset[b], n);
    if (const ConstantBlock* cb = constantBlock(b)) y.segment(offset[b] + r, n - r).noalias() = cb->D * xf;
    else y.segment(offset[b] + r, n - r) = diagonal[b].cwiseProduct(xf);
    y.segment(offset[b] + r, n - r).noalias() += C.transpose() * xr;
  }
}

SparseMatrixd BlockDiagonal::toSparse() const {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t b = 0; b < block.size(); ++b) {
    const int o = offset[b], r = int(block[b].rows());
    for (Eigen::Index c = 0; c < block[b].cols(); ++c)
      for (Eigen::Index i = 0; i < r; ++i) {
        t.emplace_back(o + int(i), o + int(c), block[b](i, c));
        if (arrow(b) && c >= r) t.emplace_back(o + int(c), o + int(i), block[b](i, c));
      }
    for (Eigen::Index k = 0; k < diagonal[b].size(); ++k) t.emplace_back(o + r + int(k), o + r + int(k), diagonal[b][k]);
    if (const ConstantBlock* cb = constantBlock(b))
      for (Eigen::Index c = 0; c < cb->D.cols(); ++c)
        for (Eigen::Index i = 0; i < cb->D.rows(); ++i) t.emplace_back(o + r + int(i), o + r + int(c), cb->D(i, c));
  }
  SparseMatrixd M(size, size);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

bool BlockFactor::compute(const BlockDiagonal& M, std::size_t b) {
  const Eigen::MatrixXd& B = M.block[b];
  if (!M.arrow(b)) {
    r_ = 0;
    llt_.compute(B);
    return llt_.info() == Eigen::Success;
  }
  r_ = int(B.rows());
  const int nf = M.dim(b) - r_;
  constant_.reset();
  if (b < M.constant.size() && M.constant[b]) {
    constant_ = M.constant[b];
    if (!constant_->ok()) return false;
    // E = C L_D^-T, i.e. E^T = L_D^-1 C^T.
    E_ = constant_->llt.matrixL().solve(B.rightCols(nf).transpose()).transpose();
    Eigen::MatrixXd S = B.leftCols(r_);
    S.noalias() -= E_ * E_.transpose();
    llt_.compute(S);
    return llt_.info() == Eigen::Success;
  }
  const Eigen::VectorXd& d = M.diagonal[b];
  if (!(d.minCoeff() > 0.0)) return false;
  dh_ = d.cwiseSqrt();
  E_ = B.rightCols(nf) * dh_.cwiseInverse().asDiagonal();
  Eigen::MatrixXd S = B.leftCols(r_);
  S.noalias() -= E_ * E_.transpose();
  llt_.compute(S);
  return llt_.info() == Eigen::Success;
}

void BlockFactor::solveF(Eigen::Ref<Eigen::MatrixXd> X) const {
  if (r_ == 0) {
    llt_.matrixL().solveInPlace(X);
    return;
  }
  const Eigen::Index nf = X.rows() - r_;
  if (constant_) constant_->llt.matrixL().solveInPlace(X.bottomRows(nf));
  else X.bottomRows(nf) = dh_.cwiseInverse().asDiagonal() * X.bottomRows(nf);
  X.topRows(r_).noalias() -= E_ * X.bottomRows(nf);
  llt_.matrixL().solveInPlace(X.topRows(r_));
}

void BlockFactor::solveFT(Eigen::Ref<Eigen::VectorXd> x) const {
  if (r_ == 0) {
    llt_.matrixU().solveInPlace(x);
    return;
  }
  const Eigen::Index nf = x.size() - r_;
  auto xr = x.head(r_);
  llt_.matrixU().solveInPlace(xr);
  x.tail(nf).noalias() -= E_.transpose() * xr;
  if (constant_) {
    auto xf = x.tail(nf);
    constant_->llt.matrixU().solveInPlace(xf);
  } else {
    x.tail(nf) = x.tail(nf).cwiseQuotient(dh_);
  }
}

BlockDiagonal BlockDiagonal::fromSparse(const SparseMatrixd& M) {
  // A column range [start, end) closes a block when no entry of its columns
  // lies outside it: track the farthest row reached (and, the pattern being
  // symmetric, the farthest column) while sweeping the columns.
  BlockDiagonal D;
  D.size = int(M.rows());
  int start = 0, reach = 0;
  for (int c = 0; c < M.cols(); ++c) {
    for (SparseMatrixd::InnerIterator it(M, c); it; ++it) {
      reach = std::max(reach, int(it.row()));
    }
    reach = std::max(reach, c);
    if (reach == c) {
      D.offset.push_back(start);
      D.block.push_back(Eigen::MatrixXd(M.block(start, start, c + 1 - start, c + 1 - start)));
      D.diagonal.emplace_back();
      start = c + 1;
      reach = start;
    }
  }
  return D;
}

bool AlSolver::SparsityPattern::update(const SparseMatrixd& A) {
  // A is compressed (setFromTriplets, sparse products, makeCompressed).
  const bool same = outer.size() == std::size_t(A.cols() + 1) &&
                    std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
                    inner.size() == std::size_t(A.nonZeros()) &&
                    std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
  if (same) return false;
  outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
  inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  return true;
}

bool AlSolver::wantsSchur(const SparseMatrixd&) const { return method_ != AlMethod::SparseLdlt; }

bool AlSolver::wantsSparseS(int rows) const {
  return method_ == AlMethod::SparseSchur || (method_ == AlMethod::Automatic && rows > kMaxDenseSchurRows);
}

void AlSolver::factorize(const BlockDiagonal& M, const SparseMatrixd& Phi_v, double alpha) {
  alpha_ = alpha;
  M_ = M;
  Phi_ = Phi_v;
  M_sparse_.resize(0, 0);
  if (wantsSchur(Phi_v) && factorizeSchur()) return;
  M_sparse_ = M_.toSparse();
  factorizeSparse();
}

void AlSolver::factorize(const SparseMatrixd& M, const SparseMatrixd& Phi_v, double alpha) {
  alpha_ = alpha;
  Phi_ = Phi_v;
  if (wantsSchur(Phi_v)) {
    M_ = BlockDiagonal::fromSparse(M);
    M_sparse_.resize(0, 0);
    if (factorizeSchur()) return;
  }
  M_ = BlockDiagonal{};
  M_sparse_ = M;
  factorizeSparse();
}

namespace {
// Left-looking Cholesky of the lower triangle, in place: column j loses
// L(j:n, 0:j) L(j, 0:j)^T (one matrix-vector product Eigen vectorises), then
// is scaled by its pivot. For the joint-space matrices here (m ~ 60) it runs
// in 2/3 the time of Eigen's blocked LLT, whose panel updates do not pay at
// this size. False at a pivot that is not positive.
bool choleskyInPlace(Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows();
  for (Eigen::Index j = 0; j < n; ++j) {
    if (j > 0) A.col(j).tail(n - j).noalias() -= A.block(j, 0, n - j, j) * A.row(j).head(j).transpose();
    const double d = A(j, j);
    if (!(d > 0.0)) return false;
    A.col(j).tail(n - j) /= std::sqrt(d);
  }
  return true;
}
}  // namespace

bool AlSolver::factorizeSchur() {
  const int m = int(Phi_.rows());
  const std::size_t nb = M_.block.size();
  const bool new_pattern = phi_pattern_.update(Phi_);
  if (new_pattern || blocks_.size() != nb) {
    blocks_.assign(nb, BlockData{});
    std::vector<int> local(m, -1);
    for (std::size_t b = 0; b < nb; ++b) {
      BlockData& B = blocks_[b];
      const int c0 = M_.offset[b], n = M_.dim(b);
      for (int c = c0; c < c0 + n; ++c)
        for (SparseMatrixd::InnerIterator it(Phi_, c); it; ++it)
          if (local[it.row()] != int(b)) {
            local[it.row()] = int(b);
            B.rows.push_back(int(it.row()));
          }
      std::sort(B.rows.begin(), B.rows.end());
      std::vector<int> index(m, -1);
      for (std::size_t k = 0; k < B.rows.size(); ++k) index[B.rows[k]] = int(k);
      for (int c = c0; c < c0 + n; ++c)
        for (SparseMatrixd::InnerIterator it(Phi_, c); it; ++it) B.slot.push_back(index[it.row()]);
    }
  }
  s_sparse_ = m > 0 && wantsSparseS(m);
  if (s_sparse_ && (new_pattern || !s_sparse_analysed_ || s_block_slot_.size() != nb)) buildSparsePattern();
  if (s_sparse_) {
    std::fill(S_sparse_.valuePtr(), S_sparse_.valuePtr() + S_sparse_.nonZeros(), 0.0);
    for (int d : s_diag_slot_) S_sparse_.valuePtr()[d] = 1.0 / alpha_;
  } else {
    S_.setZero(m, m);
  }
  for (std::size_t b = 0; b < nb; ++b) {
    BlockData& B = blocks_[b];
    const int c0 = M_.offset[b];
    const int n = M_.dim(b), nr = int(B.rows.size());
    if (!B.factor.compute(M_, b)) {
      phi_pattern_.clear();  // the sparse path will run; rebuild the pattern next time
      return false;  // singular body block: K may still be definite
    }
    if (nr == 0) continue;
    B.V.setZero(n, nr);
    std::size_t k = 0;
    for (int c = c0; c < c0 + n; ++c)
      for (SparseMatrixd::InnerIterator it(Phi_, c); it; ++it) B.V(c - c0, B.slot[k++]) = it.value();
    B.factor.solveF(B.V);
    B.G.noalias() = B.V.transpose() * B.V;
    if (s_sparse_) {
      double* values = S_sparse_.valuePtr();
      const int* slot = s_block_slot_[b].data();
      for (int j = 0; j < nr; ++j)
        for (int i = j; i < nr; ++i) values[*slot++] += B.G(i, j);
      continue;
    }
    for (int j = 0; j < nr; ++j)
      for (int i = 0; i < nr; ++i) S_(B.rows[i], B.rows[j]) += B.G(i, j);
  }
  if (s_sparse_) {
    // LDL^T without pivoting: S is positive definite, and a rounding-negative
    // pivot of redundant rows (see below) only gives a negative D entry.
    s_sparse_ldlt_.factorize(S_sparse_);
    ok_ = s_sparse_ldlt_.info() == Eigen::Success;
    used_ = AlMethod::SparseSchur;
    return ok_;
  }
  used_ = AlMethod::BlockSchur;
  S_.diagonal().array() += 1.0 / alpha_;
  // I/a + Phi M^-1 Phi^T is positive definite, but with redundant rows its
  // condition number is of order a / (smallest inertia): Cholesky can meet a
  // rounding-negative pivot, and LDL^T with pivoting cannot.
  s_L_ = S_;
  s_use_ldlt_ = !choleskyInPlace(s_L_);
  if (s_use_ldlt_) s_ldlt_.compute(S_);
  ok_ = !s_use_ldlt_ || s_ldlt_.info() == Eigen::Success;
  return ok_;
}

// S's pattern: the diagonal, and for every block the pairs of rows it
// touches (B.rows is sorted, so i >= j in B.rows is the lower triangle),
// permuted by the AMD ordering of that pattern and stored as the upper
// triangle. Each value has its slot; the LDL^T's symbolic analysis
// (elimination tree, column counts) is redone for the new pattern.
void AlSolver::buildSparsePattern() {
  const int m = int(Phi_.rows());
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < m; ++i) t.emplace_back(i, i, 1.0);
  for (const BlockData& B : blocks_)
    for (std::size_t j = 0; j < B.rows.size(); ++j)
      for (std::size_t i = j; i < B.rows.size(); ++i) t.emplace_back(B.rows[i], B.rows[j], 1.0);
  SparseMatrixd lower(m, m);
  lower.setFromTriplets(t.begin(), t.end());
  const SparseMatrixd full = SparseMatrixd(lower.selfadjointView<Eigen::Lower>());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;  // new position -> row
  Eigen::AMDOrdering<int>()(full, order);
  s_perm_.resize(m);
  for (int k = 0; k < m; ++k) s_perm_[order.indices()[k]] = k;
  auto upper = [&](int r, int c) {
    const int a = s_perm_[r], b = s_perm_[c];
    return std::pair<int, int>(std::min(a, b), std::max(a, b));
  };
  for (auto& e : t) {
    const auto [r, c] = upper(e.row(), e.col());
    e = Eigen::Triplet<double>(r, c, 1.0);
  }
  S_sparse_.resize(m, m);
  S_sparse_.setFromTriplets(t.begin(), t.end());
  S_sparse_.makeCompressed();
  auto slot = [&](int r, int c) {
    const auto [a, b] = upper(r, c);
    return int(&S_sparse_.coeffRef(a, b) - S_sparse_.valuePtr());
  };
  s_diag_slot_.resize(m);
  for (int i = 0; i < m; ++i) s_diag_slot_[i] = slot(i, i);
  s_block_slot_.assign(blocks_.size(), {});
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const BlockData& B = blocks_[b];
    for (std::size_t j = 0; j < B.rows.size(); ++j)
      for (std::size_t i = j; i < B.rows.size(); ++i) s_block_slot_[b].push_back(slot(B.rows[i], B.rows[j]));
  }
  s_sparse_ldlt_.analyzePattern(S_sparse_);
  s_sparse_analysed_ = true;
}

void AlSolver::factorizeSparse() {
  used_ = AlMethod::SparseLdlt;
  SparseMatrixd K = M_sparse_;
  if (Phi_.rows() > 0) K += alpha_ * SparseMatrixd(Phi_.transpose() * Phi_);
  K.makeCompressed();
  if (k_pattern_.update(K)) ldlt_.analyzePattern(K);
  ldlt_.factorize(K);
  ok_ = ldlt_.info() == Eigen::Success;
}

VectorXd AlSolver::multiplyM(const VectorXd& x) const {
  if (used_ == AlMethod::SparseLdlt && M_sparse_.rows() > 0) return M_sparse_ * x;
  VectorXd y;
  M_.multiply(x, y);
  return y;
}

// x = S^-1 r (x must not alias r). The sparse path permutes through a kept
// workspace and solves in place: nothing is allocated once the sizes are set
// (it runs once per multiplier pass, several times per evaluation).
void AlSolver::solveS(const VectorXd& r, VectorXd& x) const {
  const Eigen::Index n = r.size();
  if (s_sparse_) {
    s_work_.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) s_work_[s_perm_[i]] = r[i];
    s_work_ = s_sparse_ldlt_.solve(s_work_);
    x.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) x[i] = s_work_[s_perm_[i]];
    return;
  }
  if (s_use_ldlt_) {
    x = s_ldlt_.solve(r);
    return;
  }
  x = r;
  s_L_.triangularView<Eigen::Lower>().solveInPlace(x);
  s_L_.triangularView<Eigen::Lower>().transpose().solveInPlace(x);
}

// The two halves of M^-1 Phi^T-type products on the blocks: y <- L^-1 y per
// block while u gathers Phi M^-1-side terms V^T y, and x <- L^-T (x - V z)
// per block.
void AlSolver::forwardBlocks(VectorXd& y, VectorXd& u) const {
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const BlockData& B = blocks_[b];
    auto yb = y.segment(M_.offset[b], M_.dim(b));
    B.factor.solveF(yb);
    if (B.rows.empty()) continue;
    const VectorXd ub = B.V.transpose() * yb;
    for (std::size_t k = 0; k < B.rows.size(); ++k) u[B.rows[k]] += ub[k];
  }
}

void AlSolver::backwardBlocks(VectorXd& x, const VectorXd& z) const {
  VectorXd zb;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const BlockData& B = blocks_[b];
    auto xb = x.segment(M_.offset[b], M_.dim(b));
    if (!B.rows.empty()) {
      zb.resize(B.rows.size());
      for (std::size_t k = 0; k < B.rows.size(); ++k) zb[k] = z[B.rows[k]];
      xb.noalias() -= B.V * zb;
    }
    B.factor.solveFT(xb);
  }
}

VectorXd AlSolver::solve(const VectorXd& r) const {
  if (used_ == AlMethod::SparseLdlt) return ldlt_.solve(r);
  // x = L^-T (y - V z), y = L^-1 r, z = S^-1 Phi M^-1 r = S^-1 sum V^T y.
  VectorXd x = r, u = VectorXd::Zero(Phi_.rows()), z;
  forwardBlocks(x, u);
  if (u.size()) solveS(u, z);
  backwardBlocks(x, u.size() ? z : u);
  return x;
}

// Multiplier iteration for  K x = b - Phi^T (mu + a g),  mu += a (Phi x + g),
// K = M + a Phi^T Phi, converging to M x = b - Phi^T mu with Phi x + g = 0 (in
// the least-squares sense if the equations are inconsistent). Written in
// correction form, x += K^-1 (b - M x - Phi^T (mu + a (Phi x + g))), so each
// pass also refines away the rounding of the solve: K is ill-conditioned by
// design (a large, light bodies' small inertias), and solving for x afresh
// would leave errors of eps cond(K) |x| in every acceleration.
VectorXd AlSolver::iterate(const VectorXd& b, const VectorXd& g, double tol, int max_it, bool stop_on_stall,
                           VectorXd* mu_out, int* its, double* res) const {
  if (used_ != AlMethod::SparseLdlt) return iterateSchur(b, g, tol, max_it, stop_on_stall, mu_out, its, res);
  const double a = alpha_;
  const SparseMatrixd& Phi = Phi_;
  VectorXd mu = VectorXd::Zero(Phi.rows());
  VectorXd x = solve(b - a * (Phi.transpose() * g));
  VectorXd e = Phi * x + g;
  double r = e.size() ? e.cwiseAbs().maxCoeff() : 0.0;
  int k = 0;
  double r_prev = std::numeric_limits<double>::infinity();
  while (k < max_it) {
    mu += a * e;
    const VectorXd rhs = b - multiplyM(x) - Phi.transpose() * (mu + a * e);
    const VectorXd dx = solve(rhs);
    x += dx;
    e = Phi * x + g;
    ++k;
    r = e.size() ? e.cwiseAbs().maxCoeff() : 0.0;
    const double d = dx.lpNorm<Eigen::Infinity>();
    const double xn = x.lpNorm<Eigen::Infinity>();
    if (r <= tol && d <= 1e-13 * xn) break;
    // Converged x with a residual that cannot vanish: inconsistent equations
    // at a singular configuration, where the least-squares accelerations are
    // the answer. Otherwise keep iterating up to max_it even when progress is
    // slow (near-singular): stopping at a variable, state-dependent point
    // would make f(y) rough at the tolerance level and stall the step control
    // (we measured 2500 rejected steps at the SAR toggle with such a rule).
    if (d <= 1e-13 * xn) break;
    // Projections stop when the residual stops improving fast: near a
    // singular configuration the nearly dependent rows are then enforced only
    // as a penalty, which lets a mechanism pass a toggle position instead of
    // having its velocity projected onto the tangent of whichever branch the
    // step happened to land nearest (that captured the SAR knee, losing all
    // its kinetic energy).
    if (stop_on_stall && r > 0.5 * r_prev) break;
    r_prev = r;
  }
  if (mu_out) *mu_out = mu + a * e;
  if (its) *its = k;
  if (res) *res = r;
  return x;
}

// The same iteration in multiplier space, for the block Schur path. With
// S = I/a + Phi M^-1 Phi^T and c = Phi M^-1 b + g, pass k solves
//   S lambda_k = c + mu_k / a,   mu_{k+1} = lambda_k,
// which is the iteration above written for lambda_k = mu_k + a (Phi x_k + g),
// the multipliers with M x_k = b - Phi^T lambda_k (Bayo & Ledesma's update).
// A pass costs one m x m triangular pair and the bodies' small blocks, not
// a solve with K; x is formed from lambda as M^-1 (b - Phi^T lambda), whose
// rounding is eps |M^-1 b|, not eps cond(K) |x|, so it needs no refinement.
VectorXd AlSolver::iterateSchur(const VectorXd& b, const VectorXd& g, double tol, int max_it, bool stop_on_stall,
                                VectorXd* mu_out, int* its, double* res) const {
  const double a = alpha_;
  const int m = int(Phi_.rows());
  VectorXd yl = b, c = g;  // yl = L^-1 b per block, c = Phi M^-1 b + g
  forwardBlocks(yl, c);
  VectorXd x(b.size());
  auto accelerationsFor = [&](const VectorXd& lam) {
    x = yl;
    backwardBlocks(x, lam);
  };
  VectorXd lam, s_rhs(m);
  if (m) solveS(c, lam);
  accelerationsFor(lam);
  VectorXd e = Phi_ * x + g;
  double r = m ? e.cwiseAbs().maxCoeff() : 0.0;
  int k = 0;
  double r_prev = std::numeric_limits<double>::infinity();
  VectorXd x_prev;
  while (k < max_it && m > 0) {
    x_prev = x;
    s_rhs = c + lam / a;
    solveS(s_rhs, lam);
    accelerationsFor(lam);
    e = Phi_ * x + g;
    ++k;
    r = e.cwiseAbs().maxCoeff();
    const double d = (x - x_prev).lpNorm<Eigen::Infinity>();
    const double xn = x.lpNorm<Eigen::Infinity>();
    // Stopping rules as in iterate() (and for the same reasons).
    if (r <= tol && d <= 1e-13 * xn) break;
    if (d <= 1e-13 * xn) {
      // Converged multipliers, residual above tol: either inconsistent rows
      // (nothing to gain) or the rounding of x = M^-1 (b - Phi^T lambda),
      // eps |M^-1 b|, large where a body is light in some direction. One
      // pass of the correction form (iterative refinement of the dynamic
      // equation's residual) removes the latter and is harmless for the former.
      const VectorXd dx = solve(b - multiplyM(x) - Phi_.transpose() * (lam + a * e));
      x += dx;
      const VectorXd e_new = Phi_ * x + g;
      lam += a * e_new;
      e = e_new;
      r = e.cwiseAbs().maxCoeff();
      break;
    }
    if (stop_on_stall && r > 0.5 * r_prev) break;
    r_prev = r;
  }
  if (mu_out) *mu_out = lam;
  if (its) *its = k;
  if (res) *res = r;
  return x;
}

AlResult AlSolver::accelerations(const VectorXd& Q, const VectorXd& s, double tol, int max_iterations) const {
  AlResult r;
  r.vdot = iterate(Q, s, tol, max_iterations, false, &r.lambda, &r.iterations, &r.residual);
  return r;
}

VectorXd AlSolver::projectVelocities(const VectorXd& v0, const VectorXd& phit, double tol,
                                     int max_iterations) const {
  return iterate(multiplyM(v0), phit, tol, max_iterations, true, nullptr, nullptr, nullptr);
}

VectorXd AlSolver::positionCorrection(const VectorXd& phi, const VectorXd& accumulated, double tol,
                                      int max_iterations) const {
  // Unknown dq; constraint Phi_v dq + phi = 0; objective (d + dq)^T M (d + dq).
  return iterate(-multiplyM(accumulated), phi, tol, max_iterations, true, nullptr, nullptr, nullptr);
}

}  // namespace fc::mbs
