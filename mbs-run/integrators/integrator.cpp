#include "mbs-run/integrators/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

Eigen::MatrixXd finiteDifferenceJacobian(const Rhs& f, double t, const Eigen::VectorXd& y,
                                         const Eigen::VectorXd& f0, const Tolerances& tol) {
  const Eigen::Index n = y.size();
  const double floor = tol.rtol > 0 ? tol.atol / tol.rtol : 1.0;
  Eigen::MatrixXd J(n, n);
  Eigen::VectorXd yp = y, fp(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double dy = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(floor, std::abs(y[j]));
    yp[j] = y[j] + dy;
    f(t, yp, fp);
    J.col(j) = (fp - f0) / (yp[j] - y[j]);
    yp[j] = y[j];
  }
  return J;
}

}  // namespace fc::mbs
