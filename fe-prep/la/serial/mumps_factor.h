#pragma once
// Sequential MUMPS (Debian's libmumps-seq) on the serial backend's matrices:
// the LDL^T factorisation of a symmetric A = K - sigma M (SYM = 2, general
// symmetric with pivoting, as PETSc's MUMPS Cholesky: the held patches'
// saddle point factorises), its solves, and its own account of memory and
// failures (MUMPS user's guide 5.5, sections 5 and 8).
#include <memory>
#include <string>

#include "factorisation.h"

namespace fc::feprep {
inline namespace serial {

class MumpsFactor : public Factorisation {
 public:
  // Analyses and factorises A = K - sigma M (upper triangles; M null: A = K).
  // `what` names A in errors ("the stiffness"); `singular` is the message of
  // the std::runtime_error thrown when MUMPS finds A singular (INFOG(1) = -10).
  // A memory failure (INFOG(1) = -8, -9, -13 ...) throws fc::OutOfMemory with
  // MUMPS's figures. analysis_only: the ordering and MUMPS's estimates only.
  MumpsFactor(const SparseMatrix& K, const SparseMatrix* M, double sigma, const std::string& what,
              const std::string& singular, bool analysis_only = false);
  ~MumpsFactor() override;
  MumpsFactor(const MumpsFactor&) = delete;
  MumpsFactor& operator=(const MumpsFactor&) = delete;

  long size() const override { return n_; }
  void solve(double* b, long nrhs) const override;
  MumpsMemory memory() const override;
  // INFOG(i), 1-based as in MUMPS's guide.
  long infog(int i) const;

 private:
  void run(int job) const;
  struct Instance;  // MUMPS's DMUMPS_STRUC_C
  std::unique_ptr<Instance> m_;
  long n_ = 0;
  std::string what_, singular_;
};

}  // namespace serial
}  // namespace fc::feprep
