#pragma once
// A direct factorisation of the serial backend's symmetric A = K - sigma M
// (upper triangles): CHOLMOD's supernodal Cholesky where A is positive
// definite, sequential MUMPS's LDL^T with pivoting otherwise (the held
// patches' multipliers: a zero diagonal, a saddle point). Chosen by
// factorise(); docs/architecture.md says why each library is here.
#include <memory>
#include <string>

#include "la_backend.h"

namespace fc::feprep {
inline namespace serial {

class Factorisation {
 public:
  virtual ~Factorisation() = default;
  virtual long size() const = 0;
  // x = A^-1 b in place for the nrhs columns of b (n x nrhs, column-major).
  virtual void solve(double* b, long nrhs) const = 0;
  virtual MumpsMemory memory() const = 0;
};

// A = K - sigma M (M null: K) factorised: CHOLMOD when every diagonal of A is
// positive (no multiplier rows) and CHOLMOD finds it positive definite, else
// MUMPS. `what` names A in errors; `singular` is the std::runtime_error's
// message when A is singular (MUMPS INFOG(1) = -10; CHOLMOD not positive
// definite where A must be: sigma < 0, or sigma = 0 with every rigid motion
// held). Out of memory in either throws fc::OutOfMemory.
std::shared_ptr<Factorisation> factorise(const SparseMatrix& K, const SparseMatrix* M, double sigma,
                                         const std::string& what, const std::string& singular);

}  // namespace serial
}  // namespace fc::feprep
