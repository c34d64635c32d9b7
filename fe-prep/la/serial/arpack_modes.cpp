// The serial backend's eigen-solve: K x = lambda M x by ARPACK's implicitly
// restarted Lanczos in shift-invert mode (dsaupd/dseupd, mode 3, B = M: what
// CalculiX's *FREQUENCY uses), (K - sigma M)^-1 applied by one
// factorisation (CHOLMOD, or MUMPS's LDL^T for the held patches' saddle
// point: factorisation.h). The rigid motions are solved for with the
// elastic pairs (sigma < 0 below them) and removed by their share of the
// rigid-motion space, as the PETSc path does for beams (modal_solver.h).
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "fe-prep/modal_solver.h"
#include "fe-prep/mode_selection.h"
#include "factorisation.h"

extern "C" {
void dsaupd_(int* ido, const char* bmat, int* n, const char* which, int* nev, double* tol, double* resid, int* ncv,
             double* v, int* ldv, int* iparam, int* ipntr, double* workd, double* workl, int* lworkl, int* info,
             long bmat_len, long which_len);
void dseupd_(int* rvec, const char* howmny, int* select, double* d, double* z, int* ldz, double* sigma,
             const char* bmat, int* n, const char* which, int* nev, double* tol, double* resid, int* ncv, double* v,
             int* ldv, int* iparam, int* ipntr, double* workd, double* workl, int* lworkl, int* info,
             long howmny_len, long bmat_len, long which_len);
}

namespace fc::feprep {
namespace {

struct Pair {
  double lambda;
  long column;  // of the Lanczos basis's storage, M-normalised there
  double rigid_share;
};

// nev eigenpairs of K x = lambda M x nearest sigma (ARPACK mode 3): the
// converged ones (at most nev), their vectors in the first columns of `v`,
// the Lanczos basis's own storage (n x ncv; dseupd may write the Ritz
// vectors over it), so that no second n x nev block is held.
void lanczos(const SparseMatrix& M, const Factorisation& F, double sigma, long nev_l, long ncv_l, double tol,
             Eigen::VectorXd& lambda, std::vector<double>& v, long& iterations) {
  int n = static_cast<int>(F.size()), nev = static_cast<int>(nev_l), ncv = static_cast<int>(ncv_l), ldv = n;
  int lworkl = ncv * (ncv + 8), info = 0, ido = 0;
  v.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(ncv), 0.0);
  std::vector<double> resid(static_cast<std::size_t>(n)), workd(3 * static_cast<std::size_t>(n)),
      workl(static_cast<std::size_t>(lworkl));
  int iparam[11] = {}, ipntr[11] = {};
  iparam[0] = 1;     // exact shifts
  iparam[2] = 1000;  // restarts, as the PETSc path's maximum iterations
  iparam[6] = 3;     // shift-invert, generalized
  auto vec = [&](int k) { return Eigen::Map<Eigen::VectorXd>(&workd[static_cast<std::size_t>(ipntr[k] - 1)], n); };
  for (;;) {
    dsaupd_(&ido, "G", &n, "LM", &nev, &tol, resid.data(), &ncv, v.data(), &ldv, iparam, ipntr, workd.data(),
            workl.data(), &lworkl, &info, 1, 2);
    if (ido == -1) {
      auto out = vec(1);
      out.noalias() = M.selfadjointView<Eigen::Upper>() * vec(0);
      F.solve(out.data(), 1);
    } else if (ido == 1) {
      auto out = vec(1);
      out = vec(2);  // M x, ARPACK's own
      F.solve(out.data(), 1);
    } else if (ido == 2) {
      auto out = vec(1);
      out.noalias() = M.selfadjointView<Eigen::Upper>() * vec(0);
    } else {
      break;
    }
  }
  iterations = iparam[2];
  if (info < 0)
    throw ModeCountError("the eigen-solver (ARPACK dsaupd) failed for " + std::to_string(nev) + " modes (info " +
                         std::to_string(info) + "): ask for fewer modes");
  const int nconv = iparam[4];
  if (nconv <= 0) {
    lambda.resize(0);
    return;
  }
  int rvec = 1, ierr = 0;
  std::vector<int> select(static_cast<std::size_t>(ncv));
  lambda.resize(nev);
  double s = sigma;
  // Z = V: ARPACK's documented use (dseupd.f: "Z may be the same as V").
  dseupd_(&rvec, "A", select.data(), lambda.data(), v.data(), &ldv, &s, "G", &n, "LM", &nev, &tol, resid.data(), &ncv,
          v.data(), &ldv, iparam, ipntr, workd.data(), workl.data(), &lworkl, &ierr, 1, 1, 2);
  if (ierr != 0)
    throw ModeCountError("the eigen-solver (ARPACK dseupd) failed (info " + std::to_string(ierr) + "): ask for fewer modes");
  lambda.conservativeResize(std::min(nconv, nev));
}

}  // namespace

ModalResult solveModes(Comm, SystemMatrix K, SystemMatrix M, const Eigen::MatrixXd& rigid, const ModalRequest& request,
                       const std::function<void(long, long)>& progress) {
  const long N = K->rows(), r = rigid.cols();
  // Massless DOF (drilling rotations) are infinite eigenvalues: only
  // N - massless - r elastic modes exist, and the Lanczos basis must stay
  // within the massive part (below).
  const long massive = N - masslessDofs(M) - request.multipliers;
  const long elastic_available = massive - r;
  if (elastic_available <= 0) throw ModeCountError("the model has no elastic degrees of freedom that carry mass");
  // The rigid share of a mode: b^T G^-1 b, b = R^T M x, G = R^T M R.
  Eigen::MatrixXd MR(N, r);
  for (long j = 0; j < r; ++j) MR.col(j) = multiply(M, rigid.col(j));
  const Eigen::MatrixXd G = rigid.transpose() * MR;
  const Eigen::MatrixXd Ginv = r ? Eigen::MatrixXd(G.ldlt().solve(Eigen::MatrixXd::Identity(r, r))) : Eigen::MatrixXd();
  ModalResult result;
  // Not deflated (optional here): the rigid pairs are solved for and removed.
  if (request.deflate_rigid) result.rigid_null_residual = rigidNullResidual(K, rigid);
  const double lambda_max = request.max_frequency_hz > 0 ? std::pow(2 * M_PI * request.max_frequency_hz, 2) : 0.0;
  long wanted = request.modes > 0 ? std::min(request.modes, elastic_available) : std::min<long>(12, elastic_available);
  const double sigma = r > 0 ? request.shift : 0.0;
  // One factorisation of K - sigma M serves every pass of max_frequency's doubling.
  const std::shared_ptr<Factorisation> F = factorise(*K, sigma != 0.0 ? &*M : nullptr, sigma,
                                                     sigma != 0.0 ? "K - sigma M" : "the stiffness",
                                                     sigma != 0.0 ? "K - sigma M is singular: the shift hit an eigenvalue"
                                                                  : "the stiffness with the reference conditions is singular");
  result.factorisation = F->memory();
  for (;;) {
    const long nev = std::min<long>(wanted + r, massive);
    // The Lanczos basis: nev + 10 vectors, within the DOF that carry mass
    // (a vector beyond them has an M-norm of rounding). Measured against
    // SLEPc's max(2 nev, nev + 15) (docs/fe-prep.md, "Two programs"): the
    // same CPU or less (shift-invert converges in few restarts) and 2.3 /
    // 25 MB less at 1e4 / 1e5 DOF, 20 modes. ARPACK needs nev < ncv <= N.
    long ncv = std::min<long>(nev + 10, nev + std::max<long>((massive - nev) / 2, 1));
    ncv = std::min<long>(std::max<long>(ncv, nev + 1), N);
    if (nev >= ncv)
      throw ModeCountError("the eigen-solver cannot seek " + std::to_string(nev) + " modes (rigid ones included) in " +
                           std::to_string(N) + " DOF: ask for fewer modes");
    Eigen::VectorXd lambda;
    std::vector<double> store;
    long its = 0;
    lanczos(*M, *F, sigma, nev, ncv, request.tolerance, lambda, store, its);
    result.iterations += its;
    if (progress) progress(std::min<long>(lambda.size(), nev), nev);
    if (lambda.size() < nev)
      throw ModeCountError("the eigen-solver converged " + std::to_string(lambda.size()) + " of " + std::to_string(nev) +
                           " modes (rigid ones included); ask for fewer modes");
    std::vector<Pair> pairs;
    Eigen::Map<Eigen::MatrixXd> X(store.data(), N, static_cast<long>(store.size()) / std::max<long>(N, 1));
    for (long i = 0; i < lambda.size(); ++i) {
      auto x = X.col(i);
      x /= std::sqrt(x.dot(multiply(M, x)));
      const Eigen::VectorXd b = MR.transpose() * x;
      const double share = r ? b.dot(Ginv * b) : 0.0;
      // A sign convention makes files comparable between runs: largest entry
      // positive (over the nodes' rows: the patches' multiplier rows come last).
      Eigen::Index imax;
      x.head(N - request.multipliers).cwiseAbs().maxCoeff(&imax);
      if (x(imax) < 0) x = -x;
      pairs.push_back({lambda(i), i, share});
    }
    // The r modes with the largest rigid share are the rigid ones.
    std::vector<SolvedPair> solved;
    for (const Pair& p : pairs) solved.push_back({p.lambda, p.rigid_share});
    const std::optional<ModeSelection> chosen = selectModes(solved, r, lambda_max, nev >= massive, wanted);
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
      result.vectors.col(k) = X.col(p.column);
      result.rigid_projection_max = std::max(result.rigid_projection_max, p.rigid_share);
    }
    result.deflated = false;
    result.rigid_eigenvalues.resize(r);
    for (long k = 0; k < r; ++k) {
      const Pair& p = pairs[chosen->removed[static_cast<std::size_t>(k)]];
      result.rigid_eigenvalues(k) = p.lambda;
      result.rigid_projection_min = std::min(result.rigid_projection_min, p.rigid_share);
    }
    // Shift 0 factorised K itself: kept for the Craig-Bampton constraint modes.
    if (request.keep_factor && sigma == 0.0) result.factor_of_K = FactorHandle(F);
    break;
  }
  return result;
}

}  // namespace fc::feprep
