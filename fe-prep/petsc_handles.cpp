#include "fe-prep/petsc_handles.h"

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

}  // namespace fc::feprep
