// Issue 17: the integrators must never report `completed` with a wrong answer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "beam_body.h"
#include "helpers.h"
#include "mbs-run/integrator.h"
#include "mbs-run/simulation.h"
#include "mbs-run/system.h"

namespace fc::mbs::test {
namespace {

double tipDeflection(const FlexBody& b, const Eigen::VectorXd& w) {
  return b.interface("tip").shapes.col(1).head(w.size()).dot(w);
}
double angleZ(const Eigen::Vector4d& p) { return 2.0 * std::atan2(p(3), p(0)); }

std::string pendulumScene(const std::string& file, int modes, const std::string& sim) {
  char s[1024];
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: %s, modes: %d, damping_ratio: 0.0}
joints:
  - {name: pivot, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], root], axes: [[0, 0, 1], [0, 0, 1]]}
forces:
  - {type: gravity, g: [0, -9.81, 0]}
simulation: %s
)",
                file.c_str(), modes, sim.c_str());
  return s;
}

TEST(IntegratorCorrectness, JacobianProbe) {
  BeamSpec s;
  s.elements = 40;
  s.modes = 16;
  s.ei = 20.0;
  const BeamModel bm = cantileverBeam(s);
  const std::string file = writeBeam(bm, "corrj");
  const Model m = sceneFromText(pendulumScene(file, 16, "{t_end: 0.3, output_step: 0.01, rtol: 1e-8, integrator: dopri5}"));
  System sys(m);
  Eigen::VectorXd y = sys.initialState();
  sys.initializeJoints(y);
  sys.project(0.0, y);
  sys.initializeJoints(y);
  Rhs f = [&sys](double t, const Eigen::VectorXd& yy, Eigen::VectorXd& yd) { sys.derivative(t, yy, yd); };
  Tolerances tol; tol.rtol = 1e-8; tol.atol = 1e-11; tol.mask = Eigen::VectorXd::Ones(sys.size());
  auto I = makeDormandPrince(f, tol);
  I->reset(0, y);
  while (I->t() < 0.3) I->step(0.3);
  y = I->y();
  Eigen::VectorXd f0(y.size());
  f(0.3, y, f0);
  for (double rt : {1e-4, 1e-6}) {
    Tolerances t2; t2.rtol = rt; t2.atol = 1e-3 * rt;
    const Eigen::MatrixXd J = finiteDifferenceJacobian(f, 0.3, y, f0, t2);
    // central differences at several increments
    for (double d : {1e-4, 1e-5, 1e-6, 1e-7}) {
      Eigen::MatrixXd Jc(y.size(), y.size());
      for (int j = 0; j < y.size(); ++j) {
        Eigen::VectorXd yp = y, ym = y, fp(y.size()), fm(y.size());
        const double h = d * std::max(1e-3, std::abs(y[j]));
        yp[j] += h; ym[j] -= h;
        f(0.3, yp, fp); f(0.3, ym, fm);
        Jc.col(j) = (fp - fm) / (2 * h);
      }
      Eigen::Index r, c;
      const double e = (J - Jc).cwiseAbs().maxCoeff(&r, &c);
      std::printf("rtol %g, central d %g: max |J - Jc| %.3e at (%ld,%ld) |Jc| %.3e\n", rt, d, e, long(r), long(c), Jc.cwiseAbs().maxCoeff());
    }
    Eigen::EigenSolver<Eigen::MatrixXd> es(J.topLeftCorner(y.size() - 2, y.size() - 2));
    Eigen::VectorXd mags = es.eigenvalues().cwiseAbs();
    std::sort(mags.data(), mags.data() + mags.size());
    std::printf("largest |eig| %.3e %.3e %.3e; max real %.3e\n", mags(mags.size()-1), mags(mags.size()-3), mags(mags.size()-5), es.eigenvalues().real().maxCoeff());
  }
  std::filesystem::remove(file);
}

TEST(IntegratorCorrectness, TraceTrbdf2) {
  BeamSpec s;
  s.elements = 40;
  s.modes = 16;
  s.ei = 20.0;
  s.pinned_root = getenv("PINNED") != nullptr;
  const BeamModel bm = cantileverBeam(s);
  const std::string file = writeBeam(bm, "corrt");
  const Model m = sceneFromText(pendulumScene(file, 16, "{t_end: 0.3, output_step: 0.01, rtol: 1e-4, integrator: trbdf2}"));
  System sys(m);
  Eigen::VectorXd y = sys.initialState();
  sys.initializeJoints(y);
  sys.project(0.0, y);
  sys.initializeJoints(y);
  Rhs f = [&sys](double t, const Eigen::VectorXd& yy, Eigen::VectorXd& yd) { sys.derivative(t, yy, yd); };
  Tolerances tol; tol.rtol = 1e-4; tol.atol = 1e-7; tol.mask = Eigen::VectorXd::Ones(sys.size()); tol.mask.tail(2).setZero();
  tol.max_step = 0.1;
  auto I = makeTrBdf2(f, tol);
  if (getenv("SWITCH")) {
    auto D = makeDormandPrince(f, tol);
    D->reset(0, y);
    while (D->stiffness() < 2000) D->step(1.0);
    y = D->y();
    std::printf("switch at %g h %g\n", D->t(), D->t() - D->tPrevious());
    I->reset(D->t(), y);
  } else {
    I->reset(0, y);
  }
  const double e0 = sys.energies(0, y).total();
  long k = 0;
  while (I->t() < 1.0 && k < 200000) {
    if (!I->step(1.0)) { std::printf("fail at %g\n", I->t()); break; }
    ++k;
    const double e = sys.energies(I->t(), I->y()).total();
    const auto v = sys.violations(I->t(), I->y());
    if (k % 200 == 0 || std::abs(e - e0) > 1e-2) {
      std::printf("step %ld t %.6g h %.3g dE %.3e viol %.2e %.2e rej %ld\n", k, I->t(), I->t() - I->tPrevious(), e - e0, v.position, v.velocity, I->rejected);
      if (std::abs(e - e0) > 1e-2) {
        Eigen::VectorXd yy = I->y(), f0(yy.size());
        f(I->t(), yy, f0);
        const Eigen::MatrixXd J = finiteDifferenceJacobian(f, I->t(), yy, f0, tol);
        Eigen::EigenSolver<Eigen::MatrixXd> es(J.topLeftCorner(yy.size() - 2, yy.size() - 2));
        Eigen::Index im;
        const double mr = es.eigenvalues().real().maxCoeff(&im);
        std::printf("|p| = %.12f; max real eig %.3e (imag %.3e); modal q: ", yy.segment<4>(3).norm(), mr, es.eigenvalues()(im).imag());
        for (int j = 0; j < 16; ++j) std::printf("%.2e ", yy(7 + j));
        std::printf("\nmodal rates: ");
        for (int j = 0; j < 16; ++j) std::printf("%.2e ", yy(23 + 6 + j));
        std::printf("\n");
        break;
      }
    }
  }
  std::filesystem::remove(file);
}

TEST(IntegratorCorrectness, Explore) {
  BeamSpec s;
  s.elements = 40;
  s.modes = 16;
  s.ei = 20.0;
  s.pinned_root = getenv("PINNED") != nullptr;
  const BeamModel bm = cantileverBeam(s);
  std::printf("omega_1 %.3g omega_16 %.3g rad/s\n", std::sqrt(bm.body.eigenvalues(0)), std::sqrt(bm.body.eigenvalues(15)));
  const std::string file = writeBeam(bm, "corr16");
  for (const char* integ : {"dopri5", "trbdf2", "auto"}) {
    for (double rtol : {1e-4, 1e-6}) {
      char sim[200];
      std::snprintf(sim, sizeof sim, "{t_end: 1.0, output_step: 0.01, rtol: %g, integrator: %s}", rtol, integ);
      const Results r = simulate(sceneFromText(pendulumScene(file, 16, sim)), {true});
      std::printf("%s rtol %g: status %s, %s, angle %.6f tip %.6e, steps %ld rej %ld, evals %ld, cpu %.2f, ebal %.3g, escale %.3g viol %.3g\n",
                  integ, rtol, r.status.c_str(), r.integrator.c_str(), angleZ(r.orientation[1].back()),
                  tipDeflection(bm.body, r.modal[1].back()), r.steps, r.rejected_steps, r.evaluations, r.cpu_seconds,
                  r.energy_balance_error, r.energy_scale, r.max_violation);
    }
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace fc::mbs::test
