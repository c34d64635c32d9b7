#include "mbs-run/integrator.h"

#include <algorithm>
#include <cmath>

namespace fc::mbs {

double weightedRmsNorm(const Eigen::VectorXd& e, const Eigen::VectorXd& y0, const Eigen::VectorXd& y1,
                       const Tolerances& tol) {
  double s = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < e.size(); ++i) {
    if (tol.mask.size() == e.size() && tol.mask[i] == 0.0) continue;
    const double r = e[i] / (tol.atol + tol.rtol * std::max(std::abs(y0[i]), std::abs(y1[i])));
    s += r * r;
    ++n;
  }
  return n ? std::sqrt(s / n) : 0.0;
}

}  // namespace fc::mbs
