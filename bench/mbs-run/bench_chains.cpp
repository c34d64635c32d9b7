// N rods (bench/mbs-run/chain_scene.h) on
// revolute joints released from the horizontal, N = 10, 50, 200, 1000.
// Prints markdown tables for docs/benchmarks.md:
//  1. us per right-hand side (and per body): the joint-coordinate path
//     (kinematic_tree.h: treePoses + treeAccelerations, all a gravity-only
//     chain's evaluation does) and the constrained path with each linear
//     solver of AlSolver: is the evaluation O(N)?
//  2. a run of t_end simulated seconds with dopri5 at rtol 1e-6 (the
//     default atol 1e-9) in each formulation: steps, evaluations,
//     projections, CPU per simulated second;
//  3. us per output row (Dynamics::sample: poses, velocities, reactions,
//     energies, angles of one row) in each formulation, at a state in motion.
// Usage: bench_chains [t_end [N ...]]   (default 1 s; N = 10 50 200 1000)
//        bench_chains rows [N ...]      (table 3 alone)
//        bench_chains tip N t_end rtol [auto|tree|constrained]   (one run,
//        one line: CPU s, steps, evaluations, free end (x, z) at t_end; for
//        the side by side with Exudyn, bench/mbs-run/exudyn_chains.py)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "common/rotations.h"
#include "../../tests/mbs-run/helpers.h"
#include "chain_scene.h"
#include "mbs-run/integrators/integrator.h"
#include "mbs-run/tree/kinematic_tree.h"
#include "mbs-run/run/constrained_dynamics.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/run/tree_dynamics.h"
#include "mbs-run/constrained/system.h"

namespace {

using fc::mbs::AlMethod;

std::string simulation(double t_end, const char* solver, const char* formulation = "auto") {
  char sim[240];
  std::snprintf(sim, sizeof sim,
                "{t_end: %g, output_step: %g, rtol: 1e-6, integrator: dopri5, linear_solver: %s, formulation: %s}",
                t_end, t_end / 10, solver, formulation);
  return sim;
}

// One joint-coordinate evaluation at a state in motion (angles and rates
// spread over +-1 rad, +-2 rad/s).
double usPerTreeRhs(int n) {
  const fc::mbs::Model m = fc::mbs::test::sceneFromText(fc::mbs::bench::rodChainScene(n, simulation(1.0, "auto")));
  fc::mbs::System sys(m);
  Eigen::VectorXd y = sys.initialState();
  sys.initializeJoints(y);
  sys.project(0.0, y);
  std::vector<fc::mbs::BodyPose> P;
  sys.poses(y, P);
  const fc::mbs::KinematicTree tree = fc::mbs::buildKinematicTree(m, P);
  std::srand(1);
  const Eigen::VectorXd q = Eigen::VectorXd::Random(n), qd = 2.0 * Eigen::VectorXd::Random(n);
  fc::mbs::TreeWorkspace ws;
  Eigen::VectorXd qdd;
  const Eigen::VectorXd none;
  const int reps = std::max(20, 400000 / n);
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < reps; ++k) {
    fc::mbs::treePoses(tree, q, qd, P);
    fc::mbs::treeAccelerations(m, tree, P, qd, none, ws, qdd);
  }
  return 1e6 * double(std::clock() - c0) / CLOCKS_PER_SEC / reps;
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

// One output row of each formulation at a state in motion: the tree's joint
// angles and rates spread over +-1 rad, +-2 rad/s; the constrained row at the
// Cartesian state those imply (the same motion).
struct RowCost {
  double tree_us, constrained_us;
};
RowCost usPerRow(int n) {
  const fc::mbs::Model m = fc::mbs::test::sceneFromText(fc::mbs::bench::rodChainScene(n, simulation(1.0, "auto")));
  std::vector<std::string> log;
  const std::unique_ptr<fc::mbs::Dynamics> tree = fc::mbs::makeTreeDynamics(m);
  Eigen::VectorXd z = tree->start(1e-9, log);
  std::srand(1);
  z.head(n) = Eigen::VectorXd::Random(n);
  z.segment(n, n) = 2.0 * Eigen::VectorXd::Random(n);
  const fc::mbs::Sample s = tree->sample(0.0, z);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(m.nq + m.nv + 2);
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const fc::mbs::Body& b = m.bodies[k];
    if (b.fixed) continue;
    y.segment<3>(b.pos_index) = s.bodies[k].position;
    y.segment<4>(b.pos_index + 3) = s.bodies[k].orientation;
    y.segment<3>(m.nq + b.dof_index) = s.bodies[k].velocity;
    y.segment<3>(m.nq + b.dof_index + 3) =
        fc::rotationMatrix(s.bodies[k].orientation).transpose() * s.bodies[k].angular_velocity;
  }
  const std::unique_ptr<fc::mbs::Dynamics> cons = fc::mbs::makeConstrainedDynamics(m, "bench");
  cons->start(1e-9, log);
  auto time = [n](fc::mbs::Dynamics& d, const Eigen::VectorXd& x) {
    const int reps = std::max(5, 20000 / n);
    const std::clock_t c0 = std::clock();
    double sink = 0.0;
    for (int k = 0; k < reps; ++k) sink += d.sample(0.0, x).joints[0].reaction_force.norm();
    if (!(sink > 0.0)) std::printf("(no reaction?)\n");
    return 1e6 * double(std::clock() - c0) / CLOCKS_PER_SEC / reps;
  };
  return {time(*tree, z), time(*cons, y)};
}

void rowTable(const std::vector<int>& sizes) {
  std::printf("\n### 3. us per output row (us per body)\n\n| N | tree | constrained |\n|---|---|---|\n");
  for (int n : sizes) {
    const RowCost c = usPerRow(n);
    std::printf("| %d | %.1f (%.2f) | %.1f (%.2f) |\n", n, c.tree_us, c.tree_us / n, c.constrained_us,
                c.constrained_us / n);
    std::fflush(stdout);
  }
}

}  // namespace

int tipRun(int n, double t_end, double rtol, const char* formulation) {
  char sim[240];
  std::snprintf(sim, sizeof sim,
                "{t_end: %.17g, output_step: %.17g, rtol: %.17g, integrator: dopri5, formulation: %s}", t_end,
                t_end / 10, rtol, formulation);
  const fc::mbs::Results r =
      fc::mbs::simulate(fc::mbs::test::sceneFromText(fc::mbs::bench::rodChainScene(n, sim)), {true});
  const Eigen::Vector3d tip =
      r.position[n].back() + fc::rotationMatrix(r.orientation[n].back()) * Eigen::Vector3d(0.05, 0, 0);
  std::printf("cpu %.6f steps %ld evals %ld tip %.15e %.15e status %s\n", r.cpu_seconds, r.steps, r.evaluations,
              tip.x(), tip.z(), r.status.c_str());
  return r.status == "completed" ? 0 : 1;
}

int main(int argc, char** argv) {
  if ((argc == 5 || argc == 6) && std::string(argv[1]) == "tip")
    return tipRun(std::atoi(argv[2]), std::atof(argv[3]), std::atof(argv[4]), argc == 6 ? argv[5] : "auto");
  const bool rows_only = argc > 1 && std::string(argv[1]) == "rows";
  const double t_end = argc > 1 && !rows_only ? std::atof(argv[1]) : 1.0;
  std::vector<int> sizes;
  for (int k = 2; k < argc; ++k) sizes.push_back(std::atoi(argv[k]));
  if (sizes.empty()) sizes = {10, 50, 200, 1000};
  if (rows_only) {
    rowTable(sizes);
    return 0;
  }

  std::printf("\n### 1. us per right-hand side (us per body)\n\n| N | joint coordinates (tree) | rows | dense S (schur) | "
              "sparse S (sparse_schur) | sparse LDL^T of K (sparse) | constrained auto uses |\n|---|---|---|---|---|---|---|\n");
  for (int n : sizes) {
    const double tr = usPerTreeRhs(n);
    const double dense = n <= 200 ? usPerRhs(n, "schur") : 0.0;  // m^3/3 per factorisation: 1000 rods take seconds
    const double ss = usPerRhs(n, "sparse_schur"), sp = usPerRhs(n, "sparse");
    char d[64] = "-";
    if (n <= 200) std::snprintf(d, sizeof d, "%.1f (%.2f)", dense, dense / n);
    std::printf("| %d | %.2f (%.3f) | %d | %s | %.1f (%.2f) | %.1f (%.2f) | %s |\n", n, tr, tr / n, 5 * n, d, ss, ss / n,
                sp, sp / n, 5 * n <= fc::mbs::AlSolver::kMaxDenseSchurRows ? "dense S" : "sparse S");
    std::fflush(stdout);
  }

  std::printf("\n### 2. %g s from the horizontal, dopri5, rtol 1e-6\n\n", t_end);
  std::printf("| N | formulation | CPU s / sim s | CPU s / sim s / N [ms] | steps | rejected | rhs evals | projections | "
              "status |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int n : sizes) {
    for (const char* formulation : {"tree", "constrained"}) {
      const fc::mbs::Results r = fc::mbs::simulate(
          fc::mbs::test::sceneFromText(fc::mbs::bench::rodChainScene(n, simulation(t_end, "auto", formulation))),
          {true});
      const double per = r.cpu_seconds / r.t_reached;
      std::printf("| %d | %s | %.3g | %.3g | %ld | %ld | %ld | %ld | %s |\n", n, formulation, per, 1e3 * per / n,
                  r.steps, r.rejected_steps, r.evaluations, r.projections, r.status.substr(0, 12).c_str());
      std::fflush(stdout);
    }
  }
  rowTable(sizes);
}
