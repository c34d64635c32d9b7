#include "fe-prep/petsc_handles.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/memory.h"

namespace fc::feprep {

namespace {

bool g_petsc_oom = false;
std::string g_petsc_oom_size, g_petsc_oom_where;

// The allocation failure PETSc reported since the last call, as text ("" if none); clears it.
std::string takePetscOutOfMemory() {
  if (!g_petsc_oom) return "";
  g_petsc_oom = false;
  std::string s = "PETSc could not allocate " + (g_petsc_oom_size.empty() ? std::string("memory") : g_petsc_oom_size);
  if (!g_petsc_oom_where.empty()) s += " in " + g_petsc_oom_where;
  return s;
}

}  // namespace

PetscErrorCode recordingErrorHandler(MPI_Comm, int, const char* fun, const char*, PetscErrorCode n, PetscErrorType p,
                                     const char* mess, void*) {
  // PETSc 3.18 (Debian) does not always pass PETSC_ERR_MEM on: under ulimit -v
  // the code came up as aij.c's line number. A frame of the allocator itself in
  // the error's chain means an allocation failed.
  const bool allocator = fun && (std::strncmp(fun, "PetscMalloc", 11) == 0 || std::strncmp(fun, "PetscCalloc", 11) == 0 ||
                                 std::strncmp(fun, "PetscTrMalloc", 13) == 0);
  if ((n == PETSC_ERR_MEM || allocator) && !g_petsc_oom) {
    g_petsc_oom = true;
    g_petsc_oom_size.clear();
    g_petsc_oom_where.clear();
    // PetscMallocAlign's message: "Memory requested N" (bytes).
    const char* at = mess ? std::strstr(mess, "requested") : nullptr;
    if (at) g_petsc_oom_size = formatMegabytes(std::atof(at + 9) / 1048576.0);
  } else if (g_petsc_oom && g_petsc_oom_size.empty() && allocator && mess && std::strstr(mess, "requested")) {
    g_petsc_oom_size = formatMegabytes(std::atof(std::strstr(mess, "requested") + 9) / 1048576.0);
  } else if (g_petsc_oom && g_petsc_oom_where.empty() && fun && !allocator) {
    g_petsc_oom_where = fun;  // the first caller that is not the allocator itself
  }
  return n;
}

void check(PetscErrorCode ierr, const char* what) {
  if (ierr) {
    const std::string oom = takePetscOutOfMemory();
    if (!oom.empty() || ierr == PETSC_ERR_MEM)
      throw OutOfMemory((oom.empty() ? std::string("PETSc could not allocate memory") : oom) + " (" + what + ")");
  }
  if (ierr) {
    const char* text = nullptr;
    PetscErrorMessage(ierr, &text, nullptr);
    throw std::runtime_error(std::string("PETSc error in ") + what + " (" + (text ? text : "error") + ", code " +
                             std::to_string(ierr) + ")");
  }
}

namespace {

// MUMPS sizes (INFO(2) and the like): entries, or millions of entries when negative.
double mumpsEntries(PetscInt v) { return v < 0 ? -1e6 * static_cast<double>(v) : static_cast<double>(v); }

// MUMPS's INFOG(1) values that mean memory (its user guide, section "Error
// diagnostics"): -8, -9, -14, -15 work arrays too small, -13 an allocation
// failed, -17, -20 communication buffers too small, -19 ICNTL(23) too small.
bool mumpsMemoryError(PetscInt infog1) {
  for (PetscInt c : {-8, -9, -13, -14, -15, -17, -19, -20})
    if (infog1 == c) return true;
  return false;
}

std::string mumpsMemoryText(Mat F) {
  PetscInt infog1 = 0, info2 = 0;
  if (MatMumpsGetInfog(F, 1, &infog1) || MatMumpsGetInfo(F, 2, &info2)) return "";
  std::string s = "MUMPS INFOG(1) = " + std::to_string(infog1);
  const double bytes = 8.0 * mumpsEntries(info2);  // real entries of 8 bytes
  if (infog1 == -9) s += ", its work array is " + formatMegabytes(bytes / 1048576.0) + " short";
  else if (infog1 == -13) s += ", an allocation of " + formatMegabytes(bytes / 1048576.0) + " failed";
  return s;
}

}  // namespace

std::string checkFactorisationMemory(Mat A, const std::string& what) {
  // The analysis alone (ordering, symbolic factorisation): cheap against the
  // numerical factorisation, and MUMPS's estimates come out of it.
  check(PetscPushErrorHandler(recordingErrorHandler, nullptr), "PetscPushErrorHandler");
  Mat F = nullptr;
  PetscErrorCode ierr = MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F);
  MatFactorInfo info;
  if (!ierr) ierr = MatFactorInfoInitialize(&info);
  if (!ierr) ierr = MatCholeskyFactorSymbolic(F, A, nullptr, &info);
  PetscInt infog1 = 0, per_rank = -1, total = -1;
  MatFactorError ferr = MAT_FACTOR_NOERROR;
  if (!ierr) ierr = MatFactorGetError(F, &ferr);
  if (!ierr) ierr = MatMumpsGetInfog(F, 1, &infog1);
  if (!ierr) ierr = MatMumpsGetInfog(F, 16, &per_rank);
  if (!ierr) ierr = MatMumpsGetInfog(F, 17, &total);
  const std::string mumps = F ? mumpsMemoryText(F) : "";
  if (F) MatDestroy(&F);
  PetscPopErrorHandler();
  const std::string petsc = takePetscOutOfMemory();
  if (!petsc.empty()) throw OutOfMemory(petsc + " (the analysis of " + what + ")");
  if (ierr == PETSC_ERR_MEM || ferr == MAT_FACTOR_OUTMEMORY || mumpsMemoryError(infog1))
    throw OutOfMemory("the analysis of " + what + " (MUMPS) ran out of memory" + (mumps.empty() ? "" : " (" + mumps + ")"));
  // Any other failure of the analysis is the factorisation's to report.
  if (ierr || infog1 < 0 || per_rank <= 0) return "";
  PetscInt N = 0;
  MatGetSize(A, &N, nullptr);
  int ranks = 1;
  MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(A)), &ranks);
  const MemoryState mem = memoryState();
  const double need = static_cast<double>(per_rank), need_all = static_cast<double>(total);
  const double left = mem.headroom_mb();
  // Per process against the address-space limit, all ranks together against
  // the machine's free memory (ranks on one node share it).
  const bool over_limit = mem.limit_mb >= 0 && mem.size_mb >= 0 && need > mem.limit_mb - mem.size_mb;
  const bool over_ram = mem.available_mb >= 0 && need_all > mem.available_mb;
  if (over_limit || over_ram) {
    std::string s = "the factorisation of " + what + " (" + std::to_string(static_cast<long>(N)) +
                    " DOF) needs about " + formatMegabytes(ranks > 1 ? need_all : need) + " by MUMPS's estimate" +
                    (ranks > 1 ? " (" + formatMegabytes(need) + " on its largest rank)" : "") + ", more than ";
    s += over_limit ? formatMegabytes(mem.limit_mb - mem.size_mb) + " left under the address-space limit (ulimit -v " +
                          formatMegabytes(mem.limit_mb) + ")"
                    : formatMegabytes(mem.available_mb) + " of available RAM (MemAvailable)";
    throw OutOfMemory(s + "; refused before starting it");
  }
  return "factorisation ~" + formatMegabytes(ranks > 1 ? need_all : need) + " (MUMPS estimate" +
         (left >= 0 ? ", " + formatMegabytes(left) + " available" : "") + ")";
}

void throwIfOutOfMemory(PC pc, PetscErrorCode ierr, const std::string& what) {
  Mat F = nullptr;
  MatFactorError ferr = MAT_FACTOR_NOERROR;
  PetscInt infog1 = 0;
  check(PetscPushErrorHandler(recordingErrorHandler, nullptr), "PetscPushErrorHandler");
  if (pc && !PCFactorGetMatrix(pc, &F) && F) {
    if (MatFactorGetError(F, &ferr)) ferr = MAT_FACTOR_NOERROR;
    if (MatMumpsGetInfog(F, 1, &infog1)) infog1 = 0;
  }
  const std::string mumps = F ? mumpsMemoryText(F) : "";
  PetscPopErrorHandler();
  const std::string petsc = takePetscOutOfMemory();
  if (!petsc.empty()) throw OutOfMemory(petsc + " (the factorisation of " + what + ")");
  if (ierr == PETSC_ERR_MEM || ferr == MAT_FACTOR_OUTMEMORY || mumpsMemoryError(infog1))
    throw OutOfMemory("the factorisation of " + what + " ran out of memory" + (mumps.empty() ? "" : " (" + mumps + ")"));
}

void setLocal(Vec x, const Eigen::VectorXd& v) {
  PetscInt lo, hi;
  check(VecGetOwnershipRange(x, &lo, &hi), "VecGetOwnershipRange");
  PetscScalar* a;
  check(VecGetArray(x, &a), "VecGetArray");
  for (PetscInt i = lo; i < hi; ++i) a[i - lo] = v(i);
  check(VecRestoreArray(x, &a), "VecRestoreArray");
}

Eigen::VectorXd gatherAll(Vec x) {
  OwnedScatter sc;
  OwnedVec all;
  check(VecScatterCreateToAll(x, &sc, &all), "VecScatterCreateToAll");
  check(VecScatterBegin(sc, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(sc, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  PetscInt n;
  check(VecGetSize(all, &n), "VecGetSize");
  const PetscScalar* a;
  check(VecGetArrayRead(all, &a), "VecGetArrayRead");
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(a, n);
  check(VecRestoreArrayRead(all, &a), "VecRestoreArrayRead");
  return out;
}

Eigen::VectorXd multiply(Mat A, const Eigen::VectorXd& v) {
  OwnedVec x, y;
  check(MatCreateVecs(A, &x, &y), "MatCreateVecs");
  setLocal(x, v);
  check(MatMult(A, x, y), "MatMult");
  return gatherAll(y);
}

OwnedKsp choleskySolver(MPI_Comm comm, Mat A) {
  OwnedKsp ksp;
  check(KSPCreate(comm, &ksp), "KSPCreate");
  check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  return ksp;
}

MumpsMemory mumpsMemory(PC pc) {
  MumpsMemory m;
  Mat F = nullptr;
  // A PC not yet set up has no factor: PETSc would raise an error; none is wanted here.
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode ierr = PCFactorGetMatrix(pc, &F);
  PetscPopErrorHandler();
  if (ierr || !F) return m;
  MatSolverType type = nullptr;
  if (MatFactorGetSolverType(F, &type) || !type || std::strcmp(type, MATSOLVERMUMPS) != 0) return m;
  PetscInt v17 = 0, v21 = 0, v22 = 0;
  check(MatMumpsGetInfog(F, 17, &v17), "MatMumpsGetInfog");
  check(MatMumpsGetInfog(F, 21, &v21), "MatMumpsGetInfog");
  check(MatMumpsGetInfog(F, 22, &v22), "MatMumpsGetInfog");
  const double mib = 1e6 / (1024.0 * 1024.0);
  m.estimated_mib = static_cast<double>(v17) * mib;
  m.used_mib = static_cast<double>(v22) * mib;
  m.used_max_rank_mib = static_cast<double>(v21) * mib;
  return m;
}

MumpsMemory largerMumpsMemory(const MumpsMemory& a, const MumpsMemory& b) {
  return {std::max(a.estimated_mib, b.estimated_mib), std::max(a.used_mib, b.used_mib),
          std::max(a.used_max_rank_mib, b.used_max_rank_mib), "MUMPS"};
}

}  // namespace fc::feprep
