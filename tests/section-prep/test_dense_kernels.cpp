// The Eigen level-3 BLAS kernels (section-prep/dense_kernels.h) against the
// definitions in the reference BLAS documentation, written as plain loops,
// for every flag combination, leading dimensions larger than the matrices,
// and beta = 0 with NaN in C (BLAS must not read C then).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "section-prep/dense_kernels.h"

namespace {

using Eigen::MatrixXd;

// A column-major buffer with leading dimension ld >= rows, padding = 777.
struct Buf {
  int rows, cols, ld;
  std::vector<double> v;
  Buf(const MatrixXd& m, int pad) : rows(int(m.rows())), cols(int(m.cols())), ld(int(m.rows()) + pad) {
    v.assign(std::size_t(ld) * cols, 777.0);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) v[std::size_t(j) * ld + i] = m(i, j);
  }
  MatrixXd mat() const {
    MatrixXd m(rows, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) m(i, j) = v[std::size_t(j) * ld + i];
    return m;
  }
  bool paddingIntact() const {
    for (int j = 0; j < cols; ++j)
      for (int i = rows; i < ld; ++i)
        if (v[std::size_t(j) * ld + i] != 777.0) return false;
    return true;
  }
};

MatrixXd op(const MatrixXd& a, char t) { return t == 'N' ? a : MatrixXd(a.transpose()); }

TEST(DenseKernels, Dgemm) {
  const int m = 7, n = 5, k = 6;
  for (char ta : {'N', 'T'})
    for (char tb : {'N', 'T'})
      for (double beta : {0.0, 1.0, -0.5}) {
        const MatrixXd A = MatrixXd::Random(ta == 'N' ? m : k, ta == 'N' ? k : m);
        const MatrixXd B = MatrixXd::Random(tb == 'N' ? k : n, tb == 'N' ? n : k);
        MatrixXd C0 = MatrixXd::Random(m, n);
        if (beta == 0.0) C0.setConstant(std::numeric_limits<double>::quiet_NaN());
        Buf a(A, 2), b(B, 3), c(C0, 1);
        const double alpha = 1.7;
        dgemm_(&ta, &tb, &m, &n, &k, &alpha, a.v.data(), &a.ld, b.v.data(), &b.ld, &beta,
               c.v.data(), &c.ld);
        MatrixXd ref = alpha * op(A, ta) * op(B, tb);
        if (beta != 0.0) ref += beta * C0;
        EXPECT_LT((c.mat() - ref).cwiseAbs().maxCoeff(), 1e-13) << ta << tb << beta;
        EXPECT_TRUE(c.paddingIntact());
      }
}

TEST(DenseKernels, Dsyrk) {
  const int n = 6, k = 4;
  for (char uplo : {'L', 'U'})
    for (char t : {'N', 'T'})
      for (double beta : {0.0, 2.0}) {
        const MatrixXd A = MatrixXd::Random(t == 'N' ? n : k, t == 'N' ? k : n);
        MatrixXd C0 = MatrixXd::Random(n, n);
        Buf a(A, 2), c(C0, 2);
        if (beta == 0.0)  // NaN in the referenced triangle must not leak out
          for (int j = 0; j < n; ++j) c.v[std::size_t(j) * c.ld + j] = std::nan("");
        const double alpha = -0.8;
        dsyrk_(&uplo, &t, &n, &k, &alpha, a.v.data(), &a.ld, &beta, c.v.data(), &c.ld);
        const MatrixXd full = alpha * (t == 'N' ? MatrixXd(A * A.transpose()) : MatrixXd(A.transpose() * A)) +
                              (beta != 0.0 ? MatrixXd(beta * C0) : MatrixXd::Zero(n, n));
        const MatrixXd got = c.mat();
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const bool in = uplo == 'L' ? i >= j : i <= j;
            if (in) {
              EXPECT_NEAR(got(i, j), full(i, j), 1e-13) << uplo << t << beta;
            }
            else EXPECT_EQ(got(i, j), C0(i, j)) << "the other triangle is untouched";
          }
        EXPECT_TRUE(c.paddingIntact());
      }
}

TEST(DenseKernels, Dtrsm) {
  const int m = 5, n = 4;
  for (char side : {'L', 'R'})
    for (char uplo : {'L', 'U'})
      for (char t : {'N', 'T'})
        for (char diag : {'N', 'U'}) {
          const int na = side == 'L' ? m : n;
          MatrixXd A = MatrixXd::Random(na, na);
          A.diagonal().array() += 4.0;  // well conditioned
          MatrixXd T = uplo == 'L' ? MatrixXd(A.triangularView<Eigen::Lower>())
                                   : MatrixXd(A.triangularView<Eigen::Upper>());
          if (diag == 'U') T.diagonal().setOnes();
          const MatrixXd B0 = MatrixXd::Random(m, n);
          Buf a(A, 1), b(B0, 2);
          const double alpha = 0.6;
          dtrsm_(&side, &uplo, &t, &diag, &m, &n, &alpha, a.v.data(), &a.ld, b.v.data(), &b.ld);
          const MatrixXd opT = op(T, t);
          const MatrixXd X = b.mat();
          const MatrixXd lhs = side == 'L' ? MatrixXd(opT * X) : MatrixXd(X * opT);
          EXPECT_LT((lhs - alpha * B0).cwiseAbs().maxCoeff(), 1e-12) << side << uplo << t << diag;
          EXPECT_TRUE(b.paddingIntact());
        }
}

}  // namespace
