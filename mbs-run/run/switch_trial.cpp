#include "mbs-run/run/switch_trial.h"

#include <cstdio>
#include <ctime>

namespace fc::mbs {

std::string SwitchTrial::describe() const {
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "trial over %.3g s: dopri5 %.3g s CPU (%ld evaluations), %s %.3g s CPU (%ld), end states %.3g "
                "tolerance units apart%s",
                window, explicit_cpu, explicit_evaluations, candidate.c_str(), implicit_cpu, implicit_evaluations,
                difference,
                implicit_ok ? "" : " (it failed)");
  return buf;
}

SwitchTrial trialImplicit(const Rhs& f, const MethodFactory& candidate, const Tolerances& tol, double t,
                          const Eigen::VectorXd& y, double window, const Eigen::VectorXd& rate_scale) {
  SwitchTrial r;
  r.window = window;
  long count = 0;
  const Rhs counted = [&](double tt, const Eigen::VectorXd& yy, Eigen::VectorXd& d) {
    ++count;
    f(tt, yy, d);
  };
  auto run = [&](std::unique_ptr<Integrator> m, long& evaluations, double& cpu, bool& ok) {
    count = 0;
    const std::clock_t c0 = std::clock();
    m->reset(t, y);
    ok = true;
    while (m->t() < t + window)
      if (!m->step(t + window)) {
        ok = false;
        break;
      }
    evaluations = count;
    cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    return Eigen::VectorXd(m->y());
  };
  const Eigen::VectorXd ye = run(makeDormandPrince(counted, tol), r.explicit_evaluations, r.explicit_cpu, r.explicit_ok);
  std::unique_ptr<Integrator> implicit = candidate(counted);
  r.candidate = implicit->name();
  const Eigen::VectorXd yi = run(std::move(implicit), r.implicit_evaluations, r.implicit_cpu, r.implicit_ok);
  if (!r.explicit_ok || !r.implicit_ok) return r;
  if (rate_scale.size() == y.size()) {
    const Eigen::VectorXd se = ye.cwiseProduct(rate_scale), si = yi.cwiseProduct(rate_scale);
    r.difference = weightedRmsNorm(si - se, se, si, tol);
  } else {
    r.difference = weightedRmsNorm(yi - ye, ye, yi, tol);
  }
  r.implicit_better = r.implicit_cpu < kTrialCostRatio * r.explicit_cpu &&
                      r.difference <= kTrialAgree;
  return r;
}

}  // namespace fc::mbs
