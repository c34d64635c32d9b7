#pragma once
// Level-3 BLAS routines (dgemm, dsyrk, dtrsm) implemented with Eigen's
// blocked, vectorised kernels. Debian's default libblas is the unoptimised
// reference BLAS; CHOLMOD's supernodal Cholesky spends most of its time in
// these three routines, and Eigen's versions run them ~3x faster (10 against
// 3 GFlop/s on the development VM). Defined in the executable, they take
// precedence over libblas for every caller in the process (CHOLMOD, LAPACK's
// dpotrf), with the exact reference-BLAS semantics (column-major, leading
// dimensions, beta = 0 never reads C). With an optimised BLAS installed the
// CMake option FLEXCOMP_SECTION_EIGEN_BLAS=OFF leaves the system's in charge.
namespace fc::section {

// Called by the solver so that the linker keeps this translation unit.
bool eigenDenseKernelsLinked();

}  // namespace fc::section

extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
            const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
            const double* beta, double* c, const int* ldc);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
            const int* n, const double* alpha, const double* a, const int* lda, double* b,
            const int* ldb);
}
