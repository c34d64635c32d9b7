#include "fe-prep/static_response.h"

#include <petscksp.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fc::feprep {
namespace {

void check(PetscErrorCode ierr, const char* what) {
  if (ierr) throw std::runtime_error(std::string("PETSc error in ") + what + " (code " + std::to_string(ierr) + ")");
}

// PETSc handles released on every path.
struct VecH {
  Vec v = nullptr;
  ~VecH() {
    if (v) VecDestroy(&v);
  }
};
struct KspH {
  KSP k = nullptr;
  ~KspH() {
    if (k) KSPDestroy(&k);
  }
};
struct ScatterH {
  VecScatter s = nullptr;
  ~ScatterH() {
    if (s) VecScatterDestroy(&s);
  }
};

void setLocal(Vec x, const Eigen::VectorXd& v) {
  PetscInt lo, hi;
  check(VecGetOwnershipRange(x, &lo, &hi), "VecGetOwnershipRange");
  PetscScalar* a;
  check(VecGetArray(x, &a), "VecGetArray");
  for (PetscInt i = lo; i < hi; ++i) a[i - lo] = v(i);
  check(VecRestoreArray(x, &a), "VecRestoreArray");
}

Eigen::VectorXd gatherAll(Vec x) {
  ScatterH sc;
  VecH all;
  check(VecScatterCreateToAll(x, &sc.s, &all.v), "VecScatterCreateToAll");
  check(VecScatterBegin(sc.s, x, all.v, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(sc.s, x, all.v, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  PetscInt n;
  check(VecGetSize(all.v, &n), "VecGetSize");
  const PetscScalar* a;
  check(VecGetArrayRead(all.v, &a), "VecGetArrayRead");
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(a, n);
  check(VecRestoreArrayRead(all.v, &a), "VecRestoreArrayRead");
  return out;
}

}  // namespace

Eigen::VectorXd reduceForce(const DofMap& map, const Eigen::VectorXd& f) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(map.reduced);
  for (std::size_t n = 0; n < map.T.size(); ++n) {
    const auto& ix = map.idx[n];
    if (ix.empty()) continue;
    const Eigen::VectorXd g = map.T[n].transpose() * f.segment<6>(6 * static_cast<long>(n));
    for (std::size_t j = 0; j < ix.size(); ++j) r(ix[j]) += g(static_cast<long>(j));
  }
  return r;
}

Eigen::MatrixXd solveStatic(MPI_Comm comm, Mat K, const DofMap& map, const Eigen::MatrixXd& forces) {
  KspH ksp;
  check(KSPCreate(comm, &ksp.k), "KSPCreate");
  check(KSPSetOperators(ksp.k, K, K), "KSPSetOperators");
  check(KSPSetType(ksp.k, KSPPREONLY), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp.k, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(KSPSetFromOptions(ksp.k), "KSPSetFromOptions");
  VecH b, x;
  check(MatCreateVecs(K, &x.v, &b.v), "MatCreateVecs");
  Eigen::MatrixXd out(forces.rows(), forces.cols());
  for (long j = 0; j < forces.cols(); ++j) {
    setLocal(b.v, reduceForce(map, forces.col(j)));
    check(KSPSolve(ksp.k, b.v, x.v), "KSPSolve");
    KSPConvergedReason why;
    check(KSPGetConvergedReason(ksp.k, &why), "KSPGetConvergedReason");
    if (why < 0) throw std::runtime_error("the stiffness with the reference conditions is singular (rigid motions left free)");
    out.col(j) = map.expand(gatherAll(x.v));
  }
  return out;
}

StaticTruncation staticTruncation(const Eigen::VectorXd& compliance, const Eigen::MatrixXd& shapes,
                                  const Eigen::VectorXd& eigenvalues, const Eigen::Vector2d& scale) {
  StaticTruncation t;
  t.compliance = compliance;
  t.participation = Eigen::MatrixXd::Zero(shapes.rows(), 6);
  t.error = Eigen::VectorXd::Zero(6);
  for (int k = 0; k < 6; ++k) {
    // Held directions (the point cannot move that way) have no deflection to miss.
    t.held[static_cast<std::size_t>(k)] = !(compliance(k) > 1e-9 * scale(k / 3));
    if (t.held[static_cast<std::size_t>(k)]) continue;
    for (long j = 0; j < shapes.rows(); ++j) t.participation(j, k) = shapes(j, k) * shapes(j, k) / (eigenvalues(j) * compliance(k));
    t.error(k) = 1.0 - t.participation.col(k).sum();
  }
  return t;
}

long modesForStaticError(const std::vector<StaticTruncation>& ts, double target, double* worst_out) {
  const long nm = ts.empty() ? 0 : ts.front().participation.rows();
  auto worst = [&](long n) {
    double w = 0.0;
    for (const auto& t : ts)
      for (int k = 0; k < 3; ++k)
        if (!t.held[static_cast<std::size_t>(k)]) w = std::max(w, 1.0 - t.participation.col(k).head(n).sum());
    return w;
  };
  long n = 1;
  while (n < nm && worst(n) > target) ++n;
  if (worst_out) *worst_out = worst(n);
  return n;
}

}  // namespace fc::feprep
