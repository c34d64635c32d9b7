#include "fe-prep/modal_solver.h"

#include <slepceps.h>

#include "fe-prep/mode_selection.h"
#include "fe-prep/petsc_handles.h"

#include <algorithm>
#include <memory>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace fc::feprep {
namespace {

using OwnedEps = Owned<EPS, EPSDestroy>;

// The largest rigidNullResidual at which the rigid motions are deflated, a
// guard rather than an accuracy bound: the DST panels and the beams measure
// 4e-18..2e-16 (rounding of K r for an exact null vector), a K that is not
// singular on the rigid motions (an imported one written to a few digits)
// far more. Whether the deflated body equals the undeflated one is not told
// by this residual (the beam that differs by 2e-9 measured 5e-17; the
// caller restricts deflation to shell meshes, build_body.cpp).
constexpr double kDeflationNullBound = 1e-12;

struct MonitorContext {
  const std::function<void(long, long)>* progress;
  long wanted;
};

PetscErrorCode monitor(EPS, PetscInt, PetscInt nconv, PetscScalar*, PetscScalar*, PetscReal*, PetscInt, void* ctx) {
  auto* c = static_cast<MonitorContext*>(ctx);
  if (c->progress && *c->progress) (*c->progress)(std::min<long>(nconv, c->wanted), c->wanted);
  return 0;
}

// A PETSc vector with the layout of M's rows holding this rank's part of v.
OwnedVec toPetsc(Mat M, const Eigen::VectorXd& v) {
  OwnedVec x;
  check(MatCreateVecs(M, &x, nullptr), "MatCreateVecs");
  setLocal(x, v);
  return x;
}

struct Pair {
  double lambda;
  Eigen::VectorXd x;  // whole vector on every rank, M-normalised
  double rigid_share;
};

// The rigid basis's M-products and the inverse of its Gram matrix, for the share
// of each mode in the rigid space: share(x) = b^T G^{-1} b with b = R^T M x,
// G = R^T M R, x M-normalised.
struct RigidSpace {
  std::vector<OwnedVec> MR;
  Eigen::MatrixXd G, Ginv;  // G = R^T M R
};

RigidSpace rigidSpace(Mat M, const Eigen::MatrixXd& rigid) {
  const long r = rigid.cols();
  RigidSpace rs{std::vector<OwnedVec>(static_cast<std::size_t>(r)), Eigen::MatrixXd(r, r), Eigen::MatrixXd()};
  std::vector<OwnedVec>& MR = rs.MR;
  Eigen::MatrixXd& G = rs.G;
  {
    std::vector<OwnedVec> R(static_cast<std::size_t>(r));
    for (long j = 0; j < r; ++j) {
      R[static_cast<std::size_t>(j)] = toPetsc(M, rigid.col(j));
      check(MatCreateVecs(M, nullptr, &MR[static_cast<std::size_t>(j)]), "MatCreateVecs");
      check(MatMult(M, R[static_cast<std::size_t>(j)], MR[static_cast<std::size_t>(j)]), "MatMult");
    }
    for (long i = 0; i < r; ++i)
      for (long j = 0; j < r; ++j) {
        PetscScalar d;
        check(VecDot(R[static_cast<std::size_t>(i)], MR[static_cast<std::size_t>(j)], &d), "VecDot");
        G(i, j) = d;
      }
  }
  rs.Ginv = r ? Eigen::MatrixXd(G.ldlt().solve(Eigen::MatrixXd::Identity(r, r))) : Eigen::MatrixXd();
  return rs;
}

// Krylov-Schur on K x = lambda M x, shift-invert about sigma through MUMPS; the
// preconditioner (its factorisation) is returned for the memory report.
PC setUpEigenSolver(EPS eps, Mat K, Mat M, long nev, long massive, double tolerance, double shift) {
  check(EPSSetOperators(eps, K, M), "EPSSetOperators");
  check(EPSSetProblemType(eps, EPS_GHEP), "EPSSetProblemType");
  check(EPSSetType(eps, EPSKRYLOVSCHUR), "EPSSetType");
  // SLEPc's default basis size max(2 nev, nev + 15), but with its residual
  // vector no larger than the DOF that carry mass: a Krylov vector beyond
  // them has an M-norm of round-off, which SLEPc reports as "indefinite
  // matrix".
  const PetscInt ncv = static_cast<PetscInt>(std::max<long>(nev, std::min<long>(std::max<long>(2 * nev, nev + 15), nev + (massive - nev) / 2)));
  check(EPSSetDimensions(eps, nev, ncv, PETSC_DEFAULT), "EPSSetDimensions");
  check(EPSSetTolerances(eps, tolerance, 1000), "EPSSetTolerances");
  check(EPSSetTarget(eps, shift), "EPSSetTarget");
  check(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
  ST st;
  KSP ksp;
  PC pc;
  check(EPSGetST(eps, &st), "EPSGetST");
  check(STSetType(st, STSINVERT), "STSetType");
  check(STGetKSP(st, &ksp), "STGetKSP");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  // K - sigma M is symmetric positive definite for sigma < 0 (or sigma = 0 and
  // a constrained K): Cholesky halves MUMPS's work and memory against LU.
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  // A nonzero shift forms K - sigma M in K's own storage (restored when the
  // solve ends, STPostSolve) instead of a copy of K: one matrix of K's size
  // less at the factorisation's peak. M's pattern is within K's (the same
  // element pattern, or node-local blocks for a lumped mass), so the
  // addition does not reallocate K.
  if (shift != 0.0) {
    check(STSetMatMode(st, ST_MATMODE_INPLACE), "STSetMatMode");
    check(STSetMatStructure(st, SUBSET_NONZERO_PATTERN), "STSetMatStructure");
  }
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  return pc;
}

// EPSSolve; a failure is reported once, as a sentence, not as PETSc's trace.
// With a deflation space: EPSSetUp copies it into the solver's basis, so these
// vectors are released before the iteration (they are not alive at its peak).
void solveOrExplain(OwnedEps& eps, PC pc, long nev, long r, long elastic_available, std::vector<OwnedVec>& deflation) {
  check(PetscPushErrorHandler(recordingErrorHandler, nullptr), "PetscPushErrorHandler");
  PetscErrorCode ierr = 0;
  if (!deflation.empty()) {
    std::vector<Vec> v;
    for (auto& d : deflation) v.push_back(d.h);
    ierr = EPSSetDeflationSpace(eps, static_cast<PetscInt>(v.size()), v.data());
    if (!ierr) ierr = EPSSetUp(eps);
    deflation.clear();
  }
  if (!ierr) ierr = EPSSolve(eps);
  PetscPopErrorHandler();
  if (ierr) {
    // Out of memory in MUMPS or PETSc is said as such, not as a mode count.
    throwIfOutOfMemory(pc, ierr, "K - sigma M");
    // A failed solve can leave SLEPc's work matrices checked out: release
    // the solver now, quietly, so that its clean-up does not print a trace.
    check(PetscPushErrorHandler(recordingErrorHandler, nullptr), "PetscPushErrorHandler");
    EPSDestroy(&eps.h);
    PetscPopErrorHandler();
    eps.h = nullptr;
    const char* text = nullptr;
    PetscErrorMessage(ierr, &text, nullptr);
    throw ModeCountError("the eigen-solver failed for " + std::to_string(nev - r) + " modes (SLEPc: " +
                         (text ? text : "error") + ", code " + std::to_string(ierr) +
                         "); the body has " + std::to_string(elastic_available) +
                         " elastic modes with mass, but the solver's basis lost its M-orthogonality among the "
                         "highest of them (frequencies far above any a multibody run resolves): ask for fewer modes");
  }
}

// The converged pairs, M-normalised, whole on every rank, each with its rigid share.
std::vector<Pair> convergedPairs(EPS eps, Mat K, Mat M, const RigidSpace& rs, PetscInt nconv, long nev, PetscInt N, long r,
                                 long multipliers, const Eigen::MatrixXd* deflated) {
  const std::vector<OwnedVec>& MR = rs.MR;
  const Eigen::MatrixXd& Ginv = rs.Ginv;
  std::vector<Pair> pairs;
  OwnedVec xr, Mx, xall;
  OwnedScatter scatter;
  check(MatCreateVecs(K, &xr, &Mx), "MatCreateVecs");
  OwnedVec rj;
  if (deflated) check(MatCreateVecs(K, &rj, nullptr), "MatCreateVecs");
  check(VecScatterCreateToAll(xr, &scatter, &xall), "VecScatterCreateToAll");
  // R^T M x: the rigid coordinates' right-hand side, for the purification and the share.
  auto rigidDots = [&](Vec x) {
    Eigen::VectorXd b(r);
    for (long j = 0; j < r; ++j) {
      PetscScalar d;
      check(VecDot(x, MR[static_cast<std::size_t>(j)], &d), "VecDot");
      b(j) = d;
    }
    return b;
  };
  for (PetscInt i = 0; i < std::min<PetscInt>(nconv, nev); ++i) {
    PetscScalar kr;
    check(EPSGetEigenpair(eps, i, &kr, nullptr, xr, nullptr), "EPSGetEigenpair");
    if (deflated) {
      // Deflated: the vector is M-orthogonal to the rigid space up to the
      // rounding of the last shift-invert solve (SLEPc's purification),
      // which magnifies rigid components by lambda / |sigma| (~1e3 for the
      // panels) against the elastic ones. Remove them: x -= R G^-1 R^T M x,
      // so that the shape is as free of rigid motion as the undeflated
      // solve's, whose modes are orthogonalised against the rigid pairs.
      const Eigen::VectorXd c = Ginv * rigidDots(xr);
      for (long j = 0; j < r; ++j) {
        setLocal(rj, deflated->col(j));
        check(VecAXPY(xr, -c(j), rj), "VecAXPY");
      }
    }
    check(MatMult(M, xr, Mx), "MatMult");
    PetscScalar xmx;
    check(VecDot(xr, Mx, &xmx), "VecDot");
    check(VecScale(xr, 1.0 / std::sqrt(xmx)), "VecScale");
    check(VecScale(Mx, 1.0 / std::sqrt(xmx)), "VecScale");
    const Eigen::VectorXd b = rigidDots(xr);
    const double share = r ? b.dot(Ginv * b) : 0.0;
    check(VecScatterBegin(scatter, xr, xall, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(scatter, xr, xall, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* a;
    check(VecGetArrayRead(xall, &a), "VecGetArrayRead");
    Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(a, N);
    check(VecRestoreArrayRead(xall, &a), "VecRestoreArrayRead");
    // A sign convention makes files comparable between runs: largest entry positive.
    Eigen::Index imax;
    // (over the nodes' rows: the patches' multiplier rows come last)
    x.head(N - multipliers).cwiseAbs().maxCoeff(&imax);
    if (x(imax) < 0) x = -x;
    pairs.push_back({kr, std::move(x), share});
  }
  return pairs;
}

// The generalised eigenvalues of the rigid basis's projection (R^T K R, R^T M R,
// the latter rigidSpace's G): what a deflated solve reports as the removed
// rigid eigenvalues (~0).
Eigen::VectorXd rigidRayleigh(Mat K, Mat M, const Eigen::MatrixXd& rigid, const RigidSpace& rs) {
  const long r = rigid.cols();
  std::vector<OwnedVec> R(static_cast<std::size_t>(r)), KR(static_cast<std::size_t>(r));
  for (long j = 0; j < r; ++j) {
    const auto u = static_cast<std::size_t>(j);
    R[u] = toPetsc(M, rigid.col(j));
    check(MatCreateVecs(M, nullptr, &KR[u]), "MatCreateVecs");
    check(MatMult(K, R[u], KR[u]), "MatMult");
  }
  Eigen::MatrixXd A(r, r);
  for (long i = 0; i < r; ++i)
    for (long j = 0; j < r; ++j) {
      PetscScalar a;
      check(VecDot(R[static_cast<std::size_t>(i)], KR[static_cast<std::size_t>(j)], &a), "VecDot");
      A(i, j) = a;
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()), 0.5 * (rs.G + rs.G.transpose()),
                                                               Eigen::EigenvaluesOnly);
  return es.eigenvalues();
}

}  // namespace

double rigidNullResidual(Mat K, const Eigen::MatrixXd& rigid) {
  if (rigid.cols() == 0) return 0.0;
  PetscReal knorm;
  check(MatNorm(K, NORM_INFINITY, &knorm), "MatNorm");
  OwnedVec x, y;
  check(MatCreateVecs(K, &x, &y), "MatCreateVecs");
  double worst = 0.0;
  for (long j = 0; j < rigid.cols(); ++j) {
    setLocal(x, rigid.col(j));
    check(MatMult(K, x, y), "MatMult");
    PetscReal ky;
    check(VecNorm(y, NORM_INFINITY, &ky), "VecNorm");
    worst = std::max(worst, ky / (knorm * rigid.col(j).cwiseAbs().maxCoeff()));
  }
  return worst;
}

long masslessDofs(Mat M) {
  OwnedVec d;
  check(MatCreateVecs(M, &d, nullptr), "MatCreateVecs");
  check(MatGetDiagonal(M, d), "MatGetDiagonal");
  const Eigen::VectorXd diag = gatherAll(d);
  const double scale = diag.cwiseAbs().maxCoeff();
  return static_cast<long>((diag.array().abs() <= 1e-14 * scale).count());
}

ModalResult solveModes(MPI_Comm comm, Mat K, Mat M, const Eigen::MatrixXd& rigid, const ModalRequest& request,
                       const std::function<void(long, long)>& progress) {
  PetscInt N;
  check(MatGetSize(K, &N, nullptr), "MatGetSize");
  const long r = rigid.cols();
  // Massless DOF (drilling rotations) are infinite eigenvalues: only
  // N - massless - r elastic modes exist, and SLEPc's Krylov basis must stay
  // within the massive part (below).
  const long massive = N - masslessDofs(M) - request.multipliers;
  const long elastic_available = massive - r;
  if (elastic_available <= 0) throw ModeCountError("the model has no elastic degrees of freedom that carry mass");

  const RigidSpace rs = rigidSpace(M, rigid);

  // The rigid motions as a deflation space: when they are null vectors of K
  // (to rounding, against a bound far below the solver's 1e-10), the r rigid
  // eigenpairs are known exactly and Krylov-Schur need not find them; it
  // works in the M-orthogonal complement of the rigid space (SLEPc
  // M-orthonormalises the space, the GHEP's inner product), where the
  // elastic modes are.
  ModalResult result;
  if (request.deflate_rigid) result.rigid_null_residual = rigidNullResidual(K, rigid);
  const bool deflatable = request.deflate_rigid && r > 0 && result.rigid_null_residual <= kDeflationNullBound;
  // The deflated rigid pairs: the rigid space exactly, with its Rayleigh
  // quotients (computed now, before the factorisation's peak).
  if (deflatable) result.rigid_eigenvalues = rigidRayleigh(K, M, rigid, rs);

  const double lambda_max =
      request.max_frequency_hz > 0 ? std::pow(2 * M_PI * request.max_frequency_hz, 2) : 0.0;
  long wanted = request.modes > 0 ? std::min(request.modes, elastic_available) : std::min<long>(12, elastic_available);

  for (;;) {
    // Deflated only while the Krylov space leaves room beside the deflation
    // space: SLEPc refused (error 95) a free beam's every mode (240 of 240
    // with 6 deflated), which the undeflated solve delivers.
    const bool deflate = deflatable && 2 * wanted <= elastic_available;
    // Rigid pairs the solver still finds, and the Krylov space they take.
    const long r_solved = deflate ? 0 : r;
    const long nev = std::min<long>(wanted + r_solved, massive - (r - r_solved));
    OwnedEps eps;
    check(EPSCreate(comm, &eps), "EPSCreate");
    const double sigma = r > 0 ? request.shift : 0.0;
    const PC pc = setUpEigenSolver(eps, K, M, nev, massive - (r - r_solved), request.tolerance, sigma);
    MonitorContext mctx{&progress, nev};
    check(EPSMonitorSet(eps, monitor, &mctx, nullptr), "EPSMonitorSet");
    check(EPSSetFromOptions(eps), "EPSSetFromOptions");
    std::vector<OwnedVec> deflation;
    if (deflate)
      for (long j = 0; j < r; ++j) deflation.push_back(toPetsc(M, rigid.col(j)));
    solveOrExplain(eps, pc, nev, r_solved, elastic_available, deflation);
    PetscInt nconv, its;
    check(EPSGetConverged(eps, &nconv), "EPSGetConverged");
    check(EPSGetIterationNumber(eps, &its), "EPSGetIterationNumber");
    result.iterations += its;
    result.factorisation = largerMumpsMemory(result.factorisation, mumpsMemory(pc));

    std::vector<Pair> pairs = convergedPairs(eps, K, M, rs, nconv, nev, N, r, request.multipliers, deflate ? &rigid : nullptr);

    if (static_cast<long>(pairs.size()) < nev)
      throw ModeCountError("the eigen-solver converged " + std::to_string(pairs.size()) + " of " +
                           std::to_string(nev) + " modes (rigid ones included); ask for fewer modes");

    // The r modes with the largest rigid share are the rigid ones (deflated:
    // none of the solved ones, whose shares stay at rounding).
    std::vector<SolvedPair> solved;
    for (const Pair& p : pairs) solved.push_back({p.lambda, p.rigid_share});
    const std::optional<ModeSelection> chosen = selectModes(solved, r_solved, lambda_max, nev >= massive, wanted);
    if (!chosen) {
      wanted = std::min<long>(2 * wanted, elastic_available);
      continue;
    }
    const long keep = static_cast<long>(chosen->kept.size());
    result.eigenvalues.resize(keep);
    result.vectors.resize(N, keep);
    for (long k = 0; k < keep; ++k) {
      const Pair& p = pairs[chosen->kept[static_cast<std::size_t>(k)]];
      result.eigenvalues(k) = p.lambda;
      result.vectors.col(k) = p.x;
      result.rigid_projection_max = std::max(result.rigid_projection_max, p.rigid_share);
    }
    result.deflated = deflate;
    if (deflate) result.rigid_projection_min = 1.0;  // the rigid space itself
    else result.rigid_eigenvalues.resize(r);
    for (long k = 0; k < r_solved; ++k) {
      const Pair& p = pairs[chosen->removed[static_cast<std::size_t>(k)]];
      result.rigid_eigenvalues(k) = p.lambda;
      result.rigid_projection_min = std::min(result.rigid_projection_min, p.rigid_share);
    }
    if (request.keep_factor && sigma == 0.0) {
      // The spectral transformation factorised K - 0 M = K: one more
      // reference keeps the factor past the EPS's destruction (which resets
      // its solver and releases the rest).
      Mat F = nullptr;
      check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
      check(PetscObjectReference(reinterpret_cast<PetscObject>(F)), "PetscObjectReference");
      result.factor_of_K = OwnedMat(F);
    }
    break;
  }
  return result;
}

}  // namespace fc::feprep
