// Issue 17, long rigid chains: N rods (bench/mbs-run/chain_scene.h) on
// revolute joints released from the horizontal, N = 10, 50, 200, 1000.
// Prints markdown tables for docs/benchmarks.md:
//  1. us per right-hand side (and per body) with each linear solver of
//     AlSolver: is the evaluation O(N)?
//  2. a run of t_end simulated seconds with dopri5 at rtol 1e-6 (the
//     default atol 1e-9): steps, evaluations, projections, CPU per simulated
//     second; and the steps the same Dormand-Prince code (makeDormandPrince,
//     same rtol, atol, step control) takes on the minimal-coordinate model of
//     the same chain (tests/mbs-run/chain_reference.h, N <= 200: its dense
//     mass matrix is O(N^3)): are the steps the physics' or ours?
// Usage: bench_chains [t_end [N ...]]   (default 1 s; N = 10 50 200 1000)
//        bench_chains tip N t_end rtol   (one run, one line: CPU s, steps,
//        evaluations, free end (x, z) at t_end; for the side by side with
//        Exudyn, bench/mbs-run/exudyn_chains.py)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "../../tests/mbs-run/chain_reference.h"
#include "common/rotations.h"
#include "../../tests/mbs-run/helpers.h"
#include "chain_scene.h"
#include "mbs-run/integrator.h"
#include "mbs-run/simulation.h"
#include "mbs-run/system.h"

namespace {

using fc::mbs::AlMethod;

std::string simulation(double t_end, const char* solver) {
  char sim[200];
  std::snprintf(sim, sizeof sim, "{t_end: %g, output_step: %g, rtol: 1e-6, integrator: dopri5, linear_solver: %s}",
                t_end, t_end / 10, solver);
  return sim;
}

double usPerRhs(int n, const char* solver) {
  const fc::mbs::Model m = fc::mbs::test::sceneFromText(fc::mbs::bench::rodChainScene(n, simulation(1.0, solver)));
  fc::mbs::System sys(m);
  Eigen::VectorXd y = sys.initialState(), yd;
  sys.initializeJoints(y);
  sys.project(0.0, y);
  const int reps = std::max(5, 40000 / n);
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < reps; ++k) sys.derivative(0.0, y, yd);
  return 1e6 * double(std::clock() - c0) / CLOCKS_PER_SEC / reps;
}

// Steps of dopri5 on the minimal-coordinate chain (rods as chain_scene.h:
// 0.1 m, 0.1 kg, 10 mm diameter) from the horizontal at rest.
struct MinimalRun {
  long steps = 0, rejected = 0;
  double cpu = 0;
};
MinimalRun minimalCoordinates(int n, double t_end) {
  const double l = 0.1, m = 0.1, r2 = 0.25 * 0.01 * 0.01;
  const fc::mbs::test::MinimalChain c(n, l, m, m * (3 * r2 + l * l) / 12, 9.81);
  fc::mbs::Tolerances tol;
  tol.rtol = 1e-6;
  tol.atol = 1e-9;
  tol.max_step = t_end;  // mbs-run's limit is ten output steps = t_end here
  tol.mask = Eigen::VectorXd::Ones(2 * n);
  auto integ = fc::mbs::makeDormandPrince(
      [&](double, const Eigen::VectorXd& y, Eigen::VectorXd& d) { d = c.f(y); }, tol);
  const std::clock_t c0 = std::clock();
  integ->reset(0.0, Eigen::VectorXd::Zero(2 * n));
  while (integ->t() < t_end && integ->step(t_end)) {
  }
  return {integ->steps, integ->rejected, double(std::clock() - c0) / CLOCKS_PER_SEC};
}

}  // namespace

int tipRun(int n, double t_end, double rtol) {
  char sim[200];
  std::snprintf(sim, sizeof sim, "{t_end: %.17g, output_step: %.17g, rtol: %.17g, integrator: dopri5}", t_end,
                t_end / 10, rtol);
  const fc::mbs::Results r =
      fc::mbs::simulate(fc::mbs::test::sceneFromText(fc::mbs::bench::rodChainScene(n, sim)), {true});
  const Eigen::Vector3d tip =
      r.position[n].back() + fc::rotationMatrix(r.orientation[n].back()) * Eigen::Vector3d(0.05, 0, 0);
  std::printf("cpu %.6f steps %ld evals %ld tip %.15e %.15e status %s\n", r.cpu_seconds, r.steps, r.evaluations,
              tip.x(), tip.z(), r.status.c_str());
  return r.status == "completed" ? 0 : 1;
}

int main(int argc, char** argv) {
  if (argc == 5 && std::string(argv[1]) == "tip") return tipRun(std::atoi(argv[2]), std::atof(argv[3]), std::atof(argv[4]));
  const double t_end = argc > 1 ? std::atof(argv[1]) : 1.0;
  std::vector<int> sizes;
  for (int k = 2; k < argc; ++k) sizes.push_back(std::atoi(argv[k]));
  if (sizes.empty()) sizes = {10, 50, 200, 1000};

  std::printf("\n### 1. us per right-hand side (us per body)\n\n| N | rows | dense S (schur) | sparse S (sparse_schur) | "
              "sparse LDL^T of K (sparse) | auto uses |\n|---|---|---|---|---|---|\n");
  for (int n : sizes) {
    const double dense = n <= 200 ? usPerRhs(n, "schur") : 0.0;  // m^3/3 per factorisation: 1000 rods take seconds
    const double ss = usPerRhs(n, "sparse_schur"), sp = usPerRhs(n, "sparse");
    char d[64] = "-";
    if (n <= 200) std::snprintf(d, sizeof d, "%.1f (%.2f)", dense, dense / n);
    std::printf("| %d | %d | %s | %.1f (%.2f) | %.1f (%.2f) | %s |\n", n, 5 * n, d, ss, ss / n, sp, sp / n,
                5 * n <= fc::mbs::AlSolver::kMaxDenseSchurRows ? "dense S" : "sparse S");
    std::fflush(stdout);
  }

  std::printf("\n### 2. %g s from the horizontal, dopri5, rtol 1e-6 (linear_solver: auto)\n\n", t_end);
  std::printf("| N | CPU s / sim s | CPU s / sim s / N [ms] | steps | rejected | rhs evals | projections | "
              "minimal-coordinate steps (rejected) | status |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int n : sizes) {
    const fc::mbs::Results r = fc::mbs::simulate(
        fc::mbs::test::sceneFromText(fc::mbs::bench::rodChainScene(n, simulation(t_end, "auto"))), {true});
    char mc[64] = "-";
    if (n <= 200) {
      const MinimalRun mr = minimalCoordinates(n, t_end);
      std::snprintf(mc, sizeof mc, "%ld (%ld)", mr.steps, mr.rejected);
    }
    const double per = r.cpu_seconds / r.t_reached;
    std::printf("| %d | %.3g | %.3g | %ld | %ld | %ld | %ld | %s | %s |\n", n, per, 1e3 * per / n, r.steps,
                r.rejected_steps, r.evaluations, r.projections, mc, r.status.substr(0, 12).c_str());
    std::fflush(stdout);
  }
}
