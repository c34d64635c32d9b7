#include "closed_forms.h"

#include <algorithm>
#include <cmath>

namespace fc::fe::test {

double navierClassicalOmega(const Eigen::Matrix3d& D, double I0, double a, double b, int m,
                            int n) {
  const double al = m * M_PI / a, be = n * M_PI / b;
  const double k = D(0, 0) * std::pow(al, 4) + 2 * (D(0, 1) + 2 * D(2, 2)) * al * al * be * be +
                   D(1, 1) * std::pow(be, 4);
  return std::sqrt(k / I0);
}

double navierMindlinOmega(const Eigen::Matrix3d& D, const Eigen::Matrix2d& As, double I0,
                          double I2, double a, double b, int m, int n) {
  const double al = m * M_PI / a, be = n * M_PI / b;
  const double A55 = As(0, 0), A44 = As(1, 1);
  Eigen::Matrix3d S;
  S(0, 0) = A55 * al * al + A44 * be * be;
  S(0, 1) = A55 * al;
  S(0, 2) = A44 * be;
  S(1, 1) = D(0, 0) * al * al + D(2, 2) * be * be + A55;
  S(1, 2) = (D(0, 1) + D(2, 2)) * al * be;
  S(2, 2) = D(2, 2) * al * al + D(1, 1) * be * be + A44;
  S(1, 0) = S(0, 1);
  S(2, 0) = S(0, 2);
  S(2, 1) = S(1, 2);
  const Eigen::Matrix3d Mm = Eigen::Vector3d(I0, I2, I2).asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(S, Mm, Eigen::EigenvaluesOnly);
  return std::sqrt(es.eigenvalues()(0));
}

std::vector<double> lowestNavier(bool mindlin, const Eigen::Matrix3d& D,
                                 const Eigen::Matrix2d& As, double I0, double I2, double a,
                                 double b, int count) {
  std::vector<double> w;
  for (int m = 1; m <= 8; ++m)
    for (int n = 1; n <= 8; ++n)
      w.push_back(mindlin ? navierMindlinOmega(D, As, I0, I2, a, b, m, n)
                          : navierClassicalOmega(D, I0, a, b, m, n));
  std::sort(w.begin(), w.end());
  w.resize(count);
  return w;
}

double cantileverRoot(int n) {
  double x = (2 * n - 1) * M_PI / 2;
  for (int it = 0; it < 50; ++it) {
    const double f = 1 + std::cos(x) * std::cosh(x);
    const double df = -std::sin(x) * std::cosh(x) + std::cos(x) * std::sinh(x);
    x -= f / df;
  }
  return x;
}

double timoshenkoSimplySupportedOmega(double EI, double kGA, double mu, double rhoI,
                                      double L, int n) {
  const double k = n * M_PI / L;
  Eigen::Matrix2d S, Mm;
  S << kGA * k * k, kGA * k, kGA * k, EI * k * k + kGA;
  Mm << mu, 0, 0, rhoI;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(S, Mm, Eigen::EigenvaluesOnly);
  return std::sqrt(es.eigenvalues()(0));
}

}  // namespace fc::fe::test
