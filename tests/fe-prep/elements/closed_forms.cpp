#include "closed_forms.h"

#include <algorithm>
#include <cmath>
#include <vector>

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

namespace {

// Legendre P_0..P_n at x with first and second derivatives (Bonnet's recursion
// and its derivatives).
void legendre(int n, double x, std::vector<double>& P, std::vector<double>& dP,
              std::vector<double>& d2P) {
  P.assign(n + 1, 0.0);
  dP.assign(n + 1, 0.0);
  d2P.assign(n + 1, 0.0);
  P[0] = 1.0;
  if (n == 0) return;
  P[1] = x;
  dP[1] = 1.0;
  for (int k = 1; k < n; ++k) {
    P[k + 1] = ((2 * k + 1) * x * P[k] - k * P[k - 1]) / (k + 1);
    dP[k + 1] = ((2 * k + 1) * (P[k] + x * dP[k]) - k * dP[k - 1]) / (k + 1);
    d2P[k + 1] = ((2 * k + 1) * (2 * dP[k] + x * d2P[k]) - k * d2P[k - 1]) / (k + 1);
  }
}

// Gauss-Legendre points and weights on [-1, 1] (Newton on P_n from the
// Chebyshev-like first guess).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  std::vector<double> P, dP, d2P;
  for (int i = 0; i < n; ++i) {
    double t = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      legendre(n, t, P, dP, d2P);
      const double dt = P[n] / dP[n];
      t -= dt;
      if (std::fabs(dt) < 1e-16) break;
    }
    legendre(n, t, P, dP, d2P);
    x[i] = t;
    w[i] = 2.0 / ((1 - t * t) * dP[n] * dP[n]);
  }
}

}  // namespace

std::vector<double> ritzClampedPlateOmegas(const Eigen::Matrix3d& D, double I0, double a,
                                           double b, int p, int count) {
  // Integrands are polynomials of degree <= 2 (p + 4) per direction.
  const int nq = p + 6;
  std::vector<double> gx, gw;
  gaussLegendre(nq, gx, gw);
  // Per direction: phi_i = f P_i, f = (1 - x^2)^2, and its first two derivatives.
  Eigen::MatrixXd v(nq, p + 1), d1(nq, p + 1), d2(nq, p + 1);
  std::vector<double> P, dP, d2P;
  for (int q = 0; q < nq; ++q) {
    const double x = gx[q], f = (1 - x * x) * (1 - x * x), f1 = -4 * x * (1 - x * x),
                 f2 = -4 + 12 * x * x;
    legendre(p, x, P, dP, d2P);
    for (int i = 0; i <= p; ++i) {
      v(q, i) = f * P[i];
      d1(q, i) = f1 * P[i] + f * dP[i];
      d2(q, i) = f2 * P[i] + 2 * f1 * dP[i] + f * d2P[i];
    }
  }
  const int n = (p + 1) * (p + 1);
  const double jx = 2.0 / a, jy = 2.0 / b;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd B(3, n);
  Eigen::VectorXd W(n);
  for (int qx = 0; qx < nq; ++qx)
    for (int qy = 0; qy < nq; ++qy) {
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= p; ++j) {
          const int c = i * (p + 1) + j;
          // Curvatures [-w_xx, -w_yy, -2 w_xy] (the sign does not enter the energy).
          B(0, c) = -d2(qx, i) * jx * jx * v(qy, j);
          B(1, c) = -v(qx, i) * d2(qy, j) * jy * jy;
          B(2, c) = -2 * d1(qx, i) * jx * d1(qy, j) * jy;
          W(c) = v(qx, i) * v(qy, j);
        }
      const double wq = gw[qx] * gw[qy] * a * b / 4;
      K.noalias() += wq * B.transpose() * D * B;
      M.noalias() += (wq * I0) * W * W.transpose();
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::EigenvaluesOnly);
  std::vector<double> w;
  for (int i = 0; i < count; ++i) w.push_back(std::sqrt(es.eigenvalues()(i)));
  return w;
}

}  // namespace fc::fe::test
