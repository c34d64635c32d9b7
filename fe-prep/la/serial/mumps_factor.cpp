#include "mumps_factor.h"

#include <dmumps_c.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/memory.h"

namespace fc::feprep {
inline namespace serial {

namespace {

// Fortran communicator value that sequential MUMPS takes for "no MPI".
constexpr int kUseCommWorld = -987654;

// MUMPS factorises only the held patches' saddle point here (CHOLMOD the
// rest). Measured on the benchmark panel's Craig-Bampton K (8 pinned patches;
// docs/fe-prep.md, "Two programs"): QAMD (ICNTL(7) = 6) the fastest at 3e4
// and 1e5 DOF (2.42 / 8.55 s against SCOTCH's 2.87 / 10.78 s, PORD's 2.60 /
// 9.78 s), within noise of AMD and PORD at 1e4; above kPordDofs, unmeasured
// here, PORD, the PETSc path's ordering at 1e6.
constexpr long kPordDofs = 200000;

// MUMPS's INFOG(1) values that mean memory (its guide, "Error diagnostics"):
// -7 the analysis's integer work space could not be allocated (met under
// ulimit -v), -8, -9, -14, -15 work arrays too small, -13 an allocation
// failed, -17, -20 buffers too small, -19 ICNTL(23) too small.
bool memoryError(int infog1) {
  for (int c : {-7, -8, -9, -13, -14, -15, -17, -19, -20})
    if (infog1 == c) return true;
  return false;
}

// MUMPS sizes (INFO(2)): entries, or millions of entries when negative.
double entries(int v) { return v < 0 ? -1e6 * static_cast<double>(v) : static_cast<double>(v); }

}  // namespace

struct MumpsFactor::Instance {
  DMUMPS_STRUC_C id{};
};

MumpsFactor::MumpsFactor(const SparseMatrix& K, const SparseMatrix* M, double sigma, const std::string& what,
                         const std::string& singular, bool analysis_only)
    : m_(std::make_unique<Instance>()), n_(K.rows()), what_(what), singular_(singular) {
  m_->id.job = -1;
  m_->id.par = 1;
  m_->id.sym = 2;
  m_->id.comm_fortran = kUseCommWorld;
  dmumps_c(&m_->id);
  // No output of MUMPS's own: fe-prep says what failed, once.
  m_->id.icntl[0] = -1;
  m_->id.icntl[1] = -1;
  m_->id.icntl[2] = -1;
  m_->id.icntl[3] = 0;
  // ICNTL(7): the fill-reducing ordering (the Debian seq build has AMD, AMF,
  // QAMD, PORD and SCOTCH, no METIS): QAMD below kPordDofs, PORD above.
  // FLEXCOMP_MUMPS_ORDERING=<ICNTL(7)> overrides it (measurements).
  m_->id.icntl[6] = n_ < kPordDofs ? 6 : 4;
  if (const char* o = std::getenv("FLEXCOMP_MUMPS_ORDERING")) m_->id.icntl[6] = std::atoi(o);
  // A = K - sigma M in coordinates (1-based), K's and M's upper triangles
  // merged column by column. Released as soon as MUMPS holds its own copy:
  // not alive at the factorisation's peak beyond the factorisation itself.
  std::vector<int> irn, jcn;
  std::vector<double> a;
  irn.reserve(static_cast<std::size_t>(K.nonZeros()));
  jcn.reserve(static_cast<std::size_t>(K.nonZeros()));
  a.reserve(static_cast<std::size_t>(K.nonZeros()));
  for (int j = 0; j < K.outerSize(); ++j) {
    SparseMatrix::InnerIterator k(K, j);
    if (M && sigma != 0.0) {
      SparseMatrix::InnerIterator m(*M, j);
      while (k || m) {
        const int rk = k ? static_cast<int>(k.row()) : INT32_MAX, rm = m ? static_cast<int>(m.row()) : INT32_MAX;
        const int r = std::min(rk, rm);
        double v = 0.0;
        if (rk == r) v += k.value(), ++k;
        if (rm == r) v -= sigma * m.value(), ++m;
        irn.push_back(r + 1), jcn.push_back(j + 1), a.push_back(v);
      }
    } else {
      for (; k; ++k) irn.push_back(static_cast<int>(k.row()) + 1), jcn.push_back(j + 1), a.push_back(k.value());
    }
  }
  m_->id.n = static_cast<int>(n_);
  m_->id.nnz = static_cast<MUMPS_INT8>(a.size());
  m_->id.irn = irn.data();
  m_->id.jcn = jcn.data();
  m_->id.a = a.data();
  run(1);
  if (!analysis_only) run(2);
  m_->id.irn = m_->id.jcn = nullptr;
  m_->id.a = nullptr;
}

MumpsFactor::~MumpsFactor() {
  m_->id.job = -2;
  dmumps_c(&m_->id);
}

void MumpsFactor::run(int job) const {
  m_->id.job = job;
  dmumps_c(&m_->id);
  const int e = m_->id.infog[0];
  if (e >= 0) return;
  std::string s = "MUMPS INFOG(1) = " + std::to_string(e);
  const double bytes = 8.0 * entries(m_->id.info[1]);
  if (e == -9) s += ", its work array is " + formatMegabytes(bytes / 1048576.0) + " short";
  else if (e == -13) s += ", an allocation of " + formatMegabytes(bytes / 1048576.0) + " failed";
  const char* step = job == 1 ? "the analysis of " : "the factorisation of ";
  if (memoryError(e)) throw OutOfMemory(std::string(step) + what_ + " ran out of memory (" + s + ")");
  if (e == -10) throw std::runtime_error(singular_);
  throw std::runtime_error(std::string("MUMPS failed in ") + (job == 3 ? "a solve with " : step) + what_ + " (" + s +
                           ", INFOG(2) = " + std::to_string(m_->id.infog[1]) + ")");
}

void MumpsFactor::solve(double* b, long nrhs) const {
  if (nrhs <= 0) return;
  m_->id.icntl[19] = 0;  // dense right-hand sides
  m_->id.rhs = b;
  m_->id.nrhs = static_cast<int>(nrhs);
  m_->id.lrhs = static_cast<int>(n_);
  run(3);
  m_->id.rhs = nullptr;
}

MumpsMemory MumpsFactor::memory() const {
  // MUMPS reports millions of bytes: in MiB as the PETSc path's mumpsMemory.
  const double mib = 1e6 / (1024.0 * 1024.0);
  return {static_cast<double>(m_->id.infog[16]) * mib, static_cast<double>(m_->id.infog[21]) * mib,
          static_cast<double>(m_->id.infog[20]) * mib, "MUMPS"};
}

long MumpsFactor::infog(int i) const { return m_->id.infog[i - 1]; }

MumpsMemory largerMumpsMemory(const MumpsMemory& a, const MumpsMemory& b) {
  return {std::max(a.estimated_mib, b.estimated_mib), std::max(a.used_mib, b.used_mib),
          std::max(a.used_max_rank_mib, b.used_max_rank_mib), a.used_mib >= b.used_mib ? a.library : b.library};
}

}  // namespace serial
}  // namespace fc::feprep
