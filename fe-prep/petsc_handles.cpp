#include "fe-prep/petsc_handles.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace fc::feprep {

void check(PetscErrorCode ierr, const char* what) {
  if (ierr) throw std::runtime_error(std::string("PETSc error in ") + what + " (code " + std::to_string(ierr) + ")");
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
          std::max(a.used_max_rank_mib, b.used_max_rank_mib)};
}

}  // namespace fc::feprep
