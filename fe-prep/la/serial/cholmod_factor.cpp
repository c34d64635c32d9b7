#include <Eigen/CholmodSupport>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "common/memory.h"
#include "factorisation.h"
#include "mumps_factor.h"

namespace fc::feprep {
inline namespace serial {

namespace {

// CHOLMOD's supernodal LL^T (SuiteSparse, through Eigen's CholmodSupport) of
// a positive definite A, METIS-ordered: at 1e4 DOF its factor was 6.4 MB and
// a solve 5 ms against MUMPS's 11 MB and 8 ms (docs/fe-prep.md, "Two programs").
class CholmodFactor : public Factorisation {
 public:
  CholmodFactor(const SparseMatrix& A, const std::string& what) : n_(A.rows()) {
    cholmod_common& c = llt_.cholmod();
    c.print = 0;  // fe-prep says what failed, once
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_METIS;
    llt_.compute(A);
    if (c.status == CHOLMOD_OUT_OF_MEMORY || c.status == CHOLMOD_TOO_LARGE)
      throw OutOfMemory("the factorisation of " + what + " ran out of memory (CHOLMOD status " +
                        std::to_string(c.status) + ", peak " + formatMegabytes(static_cast<double>(c.memory_usage) / 1048576.0) + ")");
    positive_ = llt_.info() == Eigen::Success;
    peak_mib_ = static_cast<double>(c.memory_usage) / 1048576.0;
  }
  bool positiveDefinite() const { return positive_; }
  long size() const override { return n_; }
  void solve(double* b, long nrhs) const override {
    Eigen::Map<Eigen::MatrixXd> B(b, n_, nrhs);
    B = llt_.solve(B);
  }
  MumpsMemory memory() const override { return {peak_mib_, peak_mib_, peak_mib_, "CHOLMOD"}; }

 private:
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt_;
  long n_ = 0;
  bool positive_ = false;
  double peak_mib_ = 0.0;
};

}  // namespace

std::shared_ptr<Factorisation> factorise(const SparseMatrix& K, const SparseMatrix* M, double sigma,
                                         const std::string& what, const std::string& singular) {
  const bool shifted = M && sigma != 0.0;
  SparseMatrix A;
  if (shifted) A = K - sigma * *M;
  const SparseMatrix& a = shifted ? A : K;
  // Positive definite only if every diagonal is: a multiplier's zero diagonal
  // goes to MUMPS. FLEXCOMP_SERIAL_FACTOR=mumps takes MUMPS for every matrix
  // (the comparison in docs/fe-prep.md).
  const char* choice = std::getenv("FLEXCOMP_SERIAL_FACTOR");
  const bool mumps_only = choice && std::string(choice) == "mumps";
  if (!mumps_only && (a.diagonal().array() > 0.0).all()) {
    auto f = std::make_shared<CholmodFactor>(a, what);
    if (f->positiveDefinite()) return f;
    // K - sigma M with sigma < 0 and K held of every rigid motion are
    // positive definite: not so means singular (a mechanism, a free rigid motion).
    if (sigma < 0.0 || !M) throw std::runtime_error(singular);
  }
  A = SparseMatrix();
  return std::make_shared<MumpsFactor>(K, M, sigma, what, singular);
}

}  // namespace serial
}  // namespace fc::feprep
