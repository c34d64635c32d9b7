#include "section-prep/dense_kernels.h"

#include <Eigen/Dense>
#include <cctype>

namespace {

using Stride = Eigen::OuterStride<>;
using ConstMap = Eigen::Map<const Eigen::MatrixXd, 0, Stride>;
using Map = Eigen::Map<Eigen::MatrixXd, 0, Stride>;

bool transposed(const char* t) { return std::toupper(*t) != 'N'; }
bool lower(const char* u) { return std::toupper(*u) == 'L'; }
bool unitDiagonal(const char* d) { return std::toupper(*d) == 'U'; }

// Mode of the transposed triangle: lower <-> upper, unit diagonal kept.
constexpr int transposedMode(int mode) {
  return mode == Eigen::Lower       ? Eigen::Upper
         : mode == Eigen::Upper     ? Eigen::Lower
         : mode == Eigen::UnitLower ? Eigen::UnitUpper
                                    : Eigen::UnitLower;
}

// B := op(A)^-1 B (left) or B op(A)^-1 (right), A triangular of kind Mode.
template <int Mode>
void triangularSolve(bool left, bool trans, const ConstMap& A, Map& B) {
  constexpr int TMode = transposedMode(Mode);
  const auto At = A.transpose();
  if (left) {
    if (trans) At.template triangularView<TMode>().solveInPlace(B);
    else A.template triangularView<Mode>().solveInPlace(B);
  } else {
    if (trans) At.template triangularView<TMode>().template solveInPlace<Eigen::OnTheRight>(B);
    else A.template triangularView<Mode>().template solveInPlace<Eigen::OnTheRight>(B);
  }
}

}  // namespace

namespace fc::section {
bool eigenDenseKernelsLinked() { return true; }
}  // namespace fc::section

extern "C" {

void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc) {
  if (*m <= 0 || *n <= 0) return;
  Map C(c, *m, *n, Stride(*ldc));
  if (*beta == 0.0)
    C.setZero();  // BLAS: C is not read when beta = 0 (it may hold NaN)
  else if (*beta != 1.0)
    C *= *beta;
  if (*alpha == 0.0 || *k <= 0) return;
  const bool ta = transposed(transa), tb = transposed(transb);
  const ConstMap A(a, ta ? *k : *m, ta ? *m : *k, Stride(*lda));
  const ConstMap B(b, tb ? *n : *k, tb ? *k : *n, Stride(*ldb));
  if (!ta && !tb) C.noalias() += *alpha * A * B;
  else if (ta && !tb) C.noalias() += *alpha * A.transpose() * B;
  else if (!ta && tb) C.noalias() += *alpha * A * B.transpose();
  else C.noalias() += *alpha * A.transpose() * B.transpose();
}

void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* beta, double* c, const int* ldc) {
  if (*n <= 0) return;
  Map C(c, *n, *n, Stride(*ldc));
  const bool lo = lower(uplo);
  // Only the `uplo` triangle of C is referenced and updated.
  if (*beta != 1.0) {
    for (int j = 0; j < *n; ++j) {
      const int i0 = lo ? j : 0, i1 = lo ? *n : j + 1;
      for (int i = i0; i < i1; ++i) C(i, j) = (*beta == 0.0) ? 0.0 : *beta * C(i, j);
    }
  }
  if (*alpha == 0.0 || *k <= 0) return;
  const bool t = transposed(trans);
  const ConstMap A(a, t ? *k : *n, t ? *n : *k, Stride(*lda));
  if (lo) {
    if (t) C.selfadjointView<Eigen::Lower>().rankUpdate(A.transpose(), *alpha);
    else C.selfadjointView<Eigen::Lower>().rankUpdate(A, *alpha);
  } else {
    if (t) C.selfadjointView<Eigen::Upper>().rankUpdate(A.transpose(), *alpha);
    else C.selfadjointView<Eigen::Upper>().rankUpdate(A, *alpha);
  }
}

void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
            const int* n, const double* alpha, const double* a, const int* lda, double* b,
            const int* ldb) {
  if (*m <= 0 || *n <= 0) return;
  Map B(b, *m, *n, Stride(*ldb));
  if (*alpha == 0.0) {
    B.setZero();
    return;
  }
  if (*alpha != 1.0) B *= *alpha;
  const bool left = std::toupper(*side) == 'L';
  const int na = left ? *m : *n;
  const ConstMap A(a, na, na, Stride(*lda));
  const bool t = transposed(transa), lo = lower(uplo), unit = unitDiagonal(diag);
  if (lo && !unit) triangularSolve<Eigen::Lower>(left, t, A, B);
  else if (lo && unit) triangularSolve<Eigen::UnitLower>(left, t, A, B);
  else if (!lo && !unit) triangularSolve<Eigen::Upper>(left, t, A, B);
  else triangularSolve<Eigen::UnitUpper>(left, t, A, B);
}

}  // extern "C"
