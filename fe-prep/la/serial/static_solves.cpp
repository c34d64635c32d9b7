// The serial backend's direct solves: static responses and Craig-Bampton
// constraint modes on one sequential MUMPS factorisation, the right-hand
// sides in blocks (MUMPS's dense multi-column solve), and MUMPS's estimate
// of a factorisation's memory before it starts.
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/memory.h"
#include "fe-prep/craig_bampton.h"
#include "fe-prep/static_response.h"
#include "factorisation.h"
#include "mumps_factor.h"

namespace fc::feprep {

namespace {

// Right-hand sides solved together: MUMPS's block solve is ~2.5x faster a
// column than one at a time (the factor is read once a block), and a block
// of 32 columns is small against the factor.
constexpr long kBlock = 32;

}  // namespace

Eigen::MatrixXd solveReduced(Comm, SystemMatrix K, const Eigen::MatrixXd& rhs, const char* singular,
                             const std::vector<long>& held, double* kmax_out) {
  std::shared_ptr<Factorisation> F;
  if (held.empty()) {
    F = factorise(*K, nullptr, 0.0, "the stiffness", singular);
  } else {
    // The held DOF's rows and columns replaced by K's largest diagonal.
    const double kmax = K->diagonal().cwiseAbs().maxCoeff();
    if (kmax_out) *kmax_out = kmax;
    std::vector<char> is_held(static_cast<std::size_t>(K->rows()), 0);
    for (long i : held) is_held[static_cast<std::size_t>(i)] = 1;
    SparseMatrix Ks = *K;
    for (int j = 0; j < Ks.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Ks, j); it; ++it)
        if (is_held[static_cast<std::size_t>(it.row())] || is_held[static_cast<std::size_t>(j)])
          it.valueRef() = it.row() == j ? kmax : 0.0;
    F = factorise(Ks, nullptr, 0.0, "the stiffness", singular);
  }
  Eigen::MatrixXd x = rhs;
  for (long j = 0; j < x.cols(); j += kBlock) F->solve(x.col(j).data(), std::min(kBlock, x.cols() - j));
  return x;
}

CraigBamptonBasis constraintModes(Comm, const ConstraintModeInput& in) {
  const long nb = in.n_boundary, nk = in.normal ? in.normal->cols() : 0, N = 6 * in.n_nodes;
  CraigBamptonBasis out;
  out.n_boundary = nb;
  out.B.resize(N, nb + nk);
  // One factorisation of the fixed-interface K (the eigen-solve's when
  // given), nb solves in blocks of kBlock right-hand sides.
  std::shared_ptr<Factorisation> own;
  const Factorisation* F = in.factored;
  if (!F) {
    own = factorise(*in.K_fixed, nullptr, 0.0, "the fixed-interface stiffness",
                                        "craig_bampton: the fixed-interface stiffness is singular (the reference leaves "
                                        "rigid motions free: clamp the boundary interfaces, or pin at least three)");
    F = own.get();
    out.factorisation = own->memory();
  }
  const long n = in.fixed->reduced;
  Eigen::VectorXd f(N);
  for (long j0 = 0; j0 < nb; j0 += kBlock) {
    const long m = std::min(kBlock, nb - j0);
    Eigen::MatrixXd b(n, m);
    for (long j = 0; j < m; ++j) {
      f.setZero();
      for (const auto& [node, rows] : in.K_lifts) f.segment<6>(6 * node) = rows.col(j0 + j);
      b.col(j) = -reduceForce(*in.fixed, f);
    }
    F->solve(b.data(), m);
    for (long j = 0; j < m; ++j) {
      out.B.col(j0 + j) = in.fixed->expand(b.col(j));
      for (const auto& [node, rows] : in.lifts) out.B.col(j0 + j).segment<6>(6 * node) += rows.col(j0 + j);
    }
  }
  for (long j = 0; j < nk; ++j) out.B.col(nb + j) = in.fixed->expand(in.normal->col(j));
  return out;
}

inline namespace serial {

std::string checkFactorisationMemory(SystemMatrix A, const std::string& what) {
  // The analysis alone (ordering, symbolic factorisation): MUMPS's estimates
  // come out of it (INFOG(16), INFOG(17), millions of bytes).
  double need = -1.0;
  try {
    const MumpsFactor analysis(*A, nullptr, 0.0, what, "", true);
    need = static_cast<double>(analysis.infog(16));  // as the PETSc path reads it
  } catch (const OutOfMemory&) {
    throw;
  } catch (const std::exception&) {
    return "";  // any other failure of the analysis is the factorisation's to report
  }
  if (need <= 0) return "";
  const MemoryState mem = memoryState();
  const double left = mem.headroom_mb();
  const bool over_limit = mem.limit_mb >= 0 && mem.size_mb >= 0 && need > mem.limit_mb - mem.size_mb;
  const bool over_ram = mem.available_mb >= 0 && need > mem.available_mb;
  if (over_limit || over_ram) {
    std::string s = "the factorisation of " + what + " (" + std::to_string(A->rows()) + " DOF) needs about " +
                    formatMegabytes(need) + " by MUMPS's estimate, more than ";
    s += over_limit ? formatMegabytes(mem.limit_mb - mem.size_mb) + " left under the address-space limit (ulimit -v " +
                          formatMegabytes(mem.limit_mb) + ")"
                    : formatMegabytes(mem.available_mb) + " of available RAM (MemAvailable)";
    throw OutOfMemory(s + "; refused before starting it");
  }
  return "factorisation ~" + formatMegabytes(need) + " (MUMPS estimate" +
         (left >= 0 ? ", " + formatMegabytes(left) + " available" : "") + ")";
}

}  // namespace serial
}  // namespace fc::feprep
