#include "mbs-run/run/switch_trial.h"

#include <algorithm>
#include <cstdio>

namespace fc::mbs {

std::string SwitchTrial::describe() const {
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "trial over %.3g s: dopri5 work %.4g evaluations, %s %.4g (%ld evaluations, %ld steps tried, "
                "%ld split renewals), end states %.3g tolerance units apart%s",
                window, explicit_work, candidate.c_str(), implicit_work, implicit_evaluations, implicit_attempts,
                implicit_split_renewals, difference,
                implicit_ok ? "" : " (it failed)");
  return buf;
}

TrialCosts trialCosts(int state_size, const StiffModalPart& split) {
  const double n = state_size, nm = split.modes(), m = nm + split.elements();
  const double nv = nm > 0 ? double(split.response.rows()) : std::max(1.0, (n - 2.0) / 2.0);
  TrialCosts c;
  c.evaluation = 2.0 / 3.0 * nv * nv * nv + 2.0 * nv * nv;
  if (nm > 0) {
    c.attempted_step = 2.0 / 3.0 * m * m * m + 2.0 * m * m * nm + 6.0 * (2.0 * m * m + 4.0 * nv * m);
    c.split_renewal = 2.0 / 3.0 * nv * nv * nv + 2.0 * m * nv * nv;
  } else {
    c.attempted_step = 2.0 / 3.0 * n * n * n + 6.0 * n * n;
  }
  return c;
}

SwitchTrial trialImplicit(const Rhs& f, const MethodFactory& candidate, const Tolerances& tol, double t,
                          const Eigen::VectorXd& y, double window, const TrialCosts& costs,
                          const Eigen::VectorXd& rate_scale) {
  SwitchTrial r;
  r.window = window;
  long count = 0;
  const Rhs counted = [&](double tt, const Eigen::VectorXd& yy, Eigen::VectorXd& d) {
    ++count;
    f(tt, yy, d);
  };
  auto run = [&](std::unique_ptr<Integrator> m, long& evaluations, long& attempts, bool& ok) {
    count = 0;
    m->reset(t, y);
    ok = true;
    while (m->t() < t + window)
      if (!m->step(t + window)) {
        ok = false;
        break;
      }
    evaluations = count;
    attempts = m->steps + m->rejected;
    return Eigen::VectorXd(m->y());
  };
  long explicit_attempts = 0;
  const Eigen::VectorXd ye = run(makeDormandPrince(counted, tol), r.explicit_evaluations, explicit_attempts, r.explicit_ok);
  std::unique_ptr<Integrator> implicit = candidate(counted, &r.implicit_split_renewals);
  r.candidate = implicit->name();
  const Eigen::VectorXd yi = run(std::move(implicit), r.implicit_evaluations, r.implicit_attempts, r.implicit_ok);
  // Work in evaluations of f: Dormand-Prince's is its evaluations alone.
  r.explicit_work = double(r.explicit_evaluations);
  r.implicit_work = double(r.implicit_evaluations) +
                    (double(r.implicit_attempts) * costs.attempted_step +
                     double(r.implicit_split_renewals) * costs.split_renewal) / costs.evaluation;
  if (!r.explicit_ok || !r.implicit_ok) return r;
  if (rate_scale.size() == y.size()) {
    const Eigen::VectorXd se = ye.cwiseProduct(rate_scale), si = yi.cwiseProduct(rate_scale);
    r.difference = weightedRmsNorm(si - se, se, si, tol);
  } else {
    r.difference = weightedRmsNorm(yi - ye, ye, yi, tol);
  }
  r.implicit_better = r.implicit_work < kTrialCostRatio * r.explicit_work &&
                      r.difference <= kTrialAgree;
  return r;
}

}  // namespace fc::mbs
