// Measurements of the integrators, one table each, printed as markdown
// (docs/benchmarks.md quotes them):
//  A. a flexible beam pendulum (pinned-root modes of a Hermite beam, written
//     by tests/mbs-run/beam_body.h) with 4..200 modes: CPU per simulated
//     second of `imex` (and `dopri5` where it finishes in reasonable time);
//  N. the two forms of the flexible inertia's second-order terms per
//     evaluation (flexible/nodal_inertia.h) on bodies moving along every
//     axis, n nodes x nm modes: what nodalFormCheaper's rule is set from;
//  S. dense against sparse joint-space Schur complement (linear_solver
//     schur / sparse_schur) per evaluation on a flexible chain: where
//     AlSolver's automatic switch (kMaxDenseSchurRows) should sit;
//  B. the stiff beam pendulum (4 modes, first mode 145 Hz) at rtol 1e-6:
//     real-time factor of `dopri5` and `imex`;
// (Rigid chains, the third part: bench_chains.cpp.)
// Usage: bench_integrators [A|N|S|B]... [modes] (all when none given; modes:
// only that row of A, for profiling; "AE": A's per-evaluation rows only).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>

#include "../../tests/mbs-run/beam_body.h"
#include "../../tests/mbs-run/flexible/random_body.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/constrained/system.h"

namespace {

using fc::mbs::Results;

std::string pendulumScene(const std::string& file, int modes, const std::string& sim) {
  return "bodies:\n  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n"
         "  - name: beam\n    flexible: {file: " + file + ", modes: " + std::to_string(modes) +
         ", damping_ratio: 0.0}\njoints:\n  - {name: pivot, type: revolute, bodies: [ground, beam], points: [[0, 0, "
         "0], root], axes: [[0, 0, 1], [0, 0, 1]]}\nforces:\n  - {type: gravity, g: [0, -9.81, 0]}\nsimulation: " +
         sim + "\n";
}

double tip(const fc::FlexBody& b, const Eigen::VectorXd& w) {
  return b.interface("tip").shapes.col(1).head(w.size()).dot(w);
}

Results run(const std::string& file, int modes, const char* integ, double rtol, double t_end) {
  char sim[200];
  std::snprintf(sim, sizeof sim, "{t_end: %g, output_step: 0.01, rtol: %g, integrator: %s}", t_end, rtol, integ);
  return fc::mbs::simulate(fc::mbs::test::sceneFromText(pendulumScene(file, modes, sim)), {true});
}

// evaluations_only ("AE"): the per-evaluation rows alone, no runs.
void modes(int only, bool evaluations_only) {
  std::printf("\n### A. Beam pendulum, modes kept (from the horizontal, 0.5 s up to 16 modes, 0.1 s above; pinned-root modes, undamped)\n\n");
  std::printf("| modes | omega_max [rad/s] | integrator | rtol | CPU s / sim s | steps | rhs evals | tip [m] | tip diff vs rtol 1e-6 [m] | status |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (int nm : {4, 16, 64, 100, 200}) {
    if (only > 0 && nm != only) continue;
    fc::mbs::test::BeamSpec s;
    s.elements = std::max(20, nm / 2 + 1);
    s.modes = nm;
    s.ei = 20.0;
    s.pinned_root = true;
    const auto bm = fc::mbs::test::cantileverBeam(s);
    const std::string file = fc::mbs::test::writeBeam(bm, "bench_modes");
    {
      // Per right-hand side and per renewal of the IMEX split, at the
      // initial state (the costs do not depend on the state's values).
      const fc::mbs::Model m = fc::mbs::test::sceneFromText(
          pendulumScene(file, nm, "{t_end: 0.1, output_step: 0.01, rtol: 1e-4, integrator: imex}"));
      // The invariant form forced, for the before/after comparison.
      fc::mbs::Model mi = m;
      auto fi = std::make_shared<fc::mbs::FlexibleBodyData>(*m.bodies[1].flex);
      const char* form = fi->nodal ? "node form" : "invariants";
      fi->nodal.reset();
      mi.bodies[1].flex = fi;
      const int reps = std::max(200, 2000000 / (nm * nm));
      auto perEvaluation = [&](const fc::mbs::Model& model) {
        fc::mbs::System s(model);
        Eigen::VectorXd y = s.initialState(), yd;
        s.initializeJoints(y);
        s.project(0.0, y);
        s.derivative(0.0, y, yd);  // warm
        const std::clock_t c = std::clock();
        for (int k = 0; k < reps; ++k) s.derivative(0.0, y, yd);
        return 1e6 * double(std::clock() - c) / CLOCKS_PER_SEC / reps;
      };
      const double us_rhs = perEvaluation(m), us_inv = perEvaluation(mi);
      fc::mbs::System sys(m);
      Eigen::VectorXd yv = sys.initialState();
      sys.initializeJoints(yv);
      sys.project(0.0, yv);
      std::clock_t c0 = std::clock();
      for (int k = 0; k < std::max(3, reps / nm); ++k) sys.modalSplit(0.0, yv);
      const double us_split = 1e6 * double(std::clock() - c0) / CLOCKS_PER_SEC / std::max(3, reps / nm);
      std::printf("| %d | per evaluation | %.1f us (%.3f us per mode, %s; invariants %.1f us) | modal split (response) | %.0f us | | | | | |\n",
                  nm, us_rhs, us_rhs / nm, form, us_inv, us_split);
    }
    if (evaluations_only) {
      std::filesystem::remove(file);
      continue;
    }
    // Shorter spans for many modes (each run is one measurement, not a loop).
    const double t_end = nm <= 16 ? 0.5 : 0.1;
    // Above 16 modes rtol 1e-4 only (the undamped high modes ring at the
    // level of rtol 1e-6 and are resolved: minutes per case).
    const double tight = nm <= 16 ? 1e-6 : 1e-4;
    const Results ref = run(file, nm, "imex", tight, t_end);
    for (const char* integ : {"imex", "dopri5"}) {
      if (std::string(integ) == "dopri5" && nm > 16) continue;  // 119 s per simulated s at 64 modes
      for (double rtol : {1e-4, 1e-6}) {
        if (rtol < tight) continue;
        const Results r = (std::string(integ) == "imex" && rtol == tight) ? ref : run(file, nm, integ, rtol, t_end);
        const double tp = tip(bm.body, r.modal[1].back());
        std::printf("| %d | %.3g | %s | %.0e | %.3g | %ld | %ld | %.6e | %.2e | %s |\n", nm,
                    std::sqrt(bm.body.eigenvalues(nm - 1)), integ, rtol, r.cpu_seconds / r.t_reached, r.steps,
                    r.evaluations, tp, std::abs(tp - tip(bm.body, ref.modal[1].back())), r.status.substr(0, 12).c_str());
        std::fflush(stdout);
      }
    }
    std::filesystem::remove(file);
  }
}

// Part N: per evaluation of flexibleInertiaRows, both forms, random bodies
// whose modes move every node along every axis (r = 3 n rows).
void forms() {
  std::printf("\n### N. Second-order inertia terms per evaluation: invariants (nm x nm) against the node form (r = 3 n rows)\n\n");
  std::printf("| nodes n | modes nm | 6 r / 9 nm | invariants [us] | node form [us] | ratio node / invariants |\n|---|---|---|---|---|---|\n");
  for (int nm : {16, 64, 100, 200})
    for (int n : {nm / 8, nm / 4, nm / 2, nm}) {
      if (n < 4) continue;
      const fc::FlexBody body = fc::testing::randomBody(n, nm, 3);
      const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
      const fc::mbs::NodalInertia ni = fc::mbs::nodalInertia(body, nm);
      const Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
      const Eigen::VectorXd w = 0.01 * Eigen::VectorXd::Ones(nm), wd = Eigen::VectorXd::Ones(nm);
      const Eigen::Vector3d om(0.1, 0.2, 0.3);
      const int reps = std::max(200, 20000000 / (nm * nm + 3 * n * nm));
      double us[2];
      for (int f = 0; f < 2; ++f) {
        double sink = 0;
        const std::clock_t c = std::clock();
        for (int k = 0; k < reps; ++k) sink += fc::mbs::flexibleInertiaRows(inv, A, w, wd, om, f ? &ni : nullptr).Qv[6];
        us[f] = 1e6 * double(std::clock() - c) / CLOCKS_PER_SEC / reps;
        if (sink == 42.0) std::printf(" ");
      }
      std::printf("| %d | %d | %.2f | %.2f | %.2f | %.2f |\n", n, nm, 6.0 * double(ni.rows()) / (9.0 * nm), us[0], us[1],
                  us[1] / us[0]);
      std::fflush(stdout);
    }
}

// Part S: a chain of N flexible beams (8 pinned-root modes, 10 elements),
// tip of one pinned to the root of the next (revolute about z: 5 rows per
// joint), per evaluation with each joint-space solver.
void schurCrossover() {
  std::printf("\n### S. Flexible chain: dense against sparse joint-space Schur complement per evaluation\n\n");
  std::printf("| beams | constraint rows | dense S (schur) [us] | sparse S (sparse_schur) [us] | sparse / dense |\n|---|---|---|---|---|\n");
  fc::mbs::test::BeamSpec bs;
  bs.elements = 10;
  bs.modes = 8;
  bs.pinned_root = true;
  const auto bm = fc::mbs::test::cantileverBeam(bs);
  const std::string file = fc::mbs::test::writeBeam(bm, "bench_schur");
  for (int n : {8, 16, 20, 24, 28, 32, 48}) {
    double us[2];
    int k = 0;
    for (const char* solver : {"schur", "sparse_schur"}) {
      std::string y = "bodies:\n  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n";
      std::string j = "joints:\n";
      for (int b = 0; b < n; ++b) {
        y += "  - {name: B" + std::to_string(b) + ", position: [" + std::to_string(b) +
             ", 0, 0], flexible: {file: " + file + ", modes: 8}}\n";
        j += "  - {name: J" + std::to_string(b) + ", type: revolute, bodies: [" +
             (b ? "B" + std::to_string(b - 1) : std::string("ground")) + ", B" + std::to_string(b) + "], points: [" +
             (b ? std::string("tip") : std::string("[0, 0, 0]")) + ", root], axes: [[0, 0, 1], [0, 0, 1]]}\n";
      }
      const fc::mbs::Model m = fc::mbs::test::sceneFromText(
          y + j + "forces:\n  - {type: gravity, g: [0, -9.81, 0]}\nsimulation: {t_end: 1, linear_solver: " + solver + "}\n");
      fc::mbs::System sys(m);
      Eigen::VectorXd yv = sys.initialState(), yd;
      sys.initializeJoints(yv);
      sys.project(0.0, yv);
      sys.derivative(0.0, yv, yd);
      const int reps = std::max(50, 20000 / n);
      const std::clock_t c = std::clock();
      for (int r = 0; r < reps; ++r) sys.derivative(0.0, yv, yd);
      us[k++] = 1e6 * double(std::clock() - c) / CLOCKS_PER_SEC / reps;
    }
    std::printf("| %d | %d | %.1f | %.1f | %.2f |\n", n, 5 * n, us[0], us[1], us[1] / us[0]);
    std::fflush(stdout);
  }
  std::filesystem::remove(file);
}

void stiff() {
  std::printf("\n### B. Stiff beam pendulum (4 pinned-root modes, first mode 145 Hz), 1 s, rtol 1e-6\n\n");
  fc::mbs::test::BeamSpec s;
  s.elements = 20;
  s.modes = 4;
  s.ei = 80.0;
  s.pinned_root = true;
  // Pinned-free beam: omega_1 = 15.42 sqrt(EI / (rho A L^4)); 145 Hz asks
  // for EI = 3 494 N m^2, 43.7 x the default.
  s.stiffness_scale = 43.7;
  const auto bm = fc::mbs::test::cantileverBeam(s);
  const std::string file = fc::mbs::test::writeBeam(bm, "bench_stiff");
  std::printf("first mode %.1f Hz, fourth %.1f Hz\n\n", bm.body.frequencies_hz(0), bm.body.frequencies_hz(3));
  std::printf("| integrator | CPU s | real-time factor (sim s / CPU s) | steps | rhs evals | angle [rad] | status |\n|---|---|---|---|---|---|---|\n");
  for (const char* integ : {"dopri5", "imex", "auto"}) {
    const Results r = run(file, 4, integ, 1e-6, 1.0);
    std::printf("| %s | %.3f | %.2f | %ld | %ld | %.9f | %s |\n", integ, r.cpu_seconds, r.t_reached / r.cpu_seconds,
                r.steps, r.evaluations, 2.0 * std::atan2(r.orientation[1].back()(3), r.orientation[1].back()(0)),
                r.status.substr(0, 12).c_str());
    std::fflush(stdout);
  }
  std::filesystem::remove(file);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "ANSB";
  if (which.find('A') != std::string::npos) modes(argc > 2 ? std::atoi(argv[2]) : 0, which.find('E') != std::string::npos);
  if (which.find('N') != std::string::npos) forms();
  if (which.find('S') != std::string::npos) schurCrossover();
  if (which.find('B') != std::string::npos) stiff();
}
