#pragma once
// Closed-form references for the element tests.
#include <Eigen/Dense>
#include <vector>

namespace fc::fe::test {

// Classical (Kirchhoff) simply supported rectangular plate, specially orthotropic
// (D16 = D26 = 0) (Reddy 2004, ch. 5 Navier solution; Leissa 1969 for isotropic):
//   omega^2 = pi^4 [D11 (m/a)^4 + 2 (D12 + 2 D66) (m/a)^2 (n/b)^2 + D22 (n/b)^4] / I0.
double navierClassicalOmega(const Eigen::Matrix3d& D, double I0, double a, double b, int m,
                           int n);

// First-order shear deformation (Mindlin) Navier solution of a simply supported
// cross-ply plate with B = 0 (Reddy 2004, ch. 6 Navier solution): the lowest root of the
// 3x3 problem in (W, X, Y) with rotary inertia I2.
double navierMindlinOmega(const Eigen::Matrix3d& D, const Eigen::Matrix2d& As, double I0,
                         double I2, double a, double b, int m, int n);

// The lowest `count` frequencies over (m, n) = 1..8, sorted.
std::vector<double> lowestNavier(bool mindlin, const Eigen::Matrix3d& D,
                                 const Eigen::Matrix2d& As, double I0, double I2, double a,
                                 double b, int count);

// Classical (Kirchhoff) rectangular plate [0,a] x [0,b] with a general D,
// bending-twist terms D16 and D26 included, clamped on all four edges: the Ritz
// method of Reddy 2004, ch. 5 (anisotropic plates, no Navier solution), with
// the trial functions w = (1 - xi^2)^2 (1 - eta^2)^2 P_i(xi) P_j(eta), P the
// Legendre polynomials of degree 0..p on xi, eta in [-1, 1]. The basis is
// complete and satisfies w = w_,n = 0 on every edge, so the frequencies fall
// monotonically and fast with p (p = 12 and 16 agree to 1e-5 for the first six
// modes of a single 45-degree ply). Energies by Gauss-Legendre quadrature,
// exact for the polynomial integrands. Rotary inertia neglected (thin plate).
// The lowest `count` angular frequencies, ascending.
std::vector<double> ritzClampedPlateOmegas(const Eigen::Matrix3d& D, double I0, double a,
                                           double b, int p, int count);

// Cantilever Euler-Bernoulli roots beta_n L of 1 + cos(bL) cosh(bL) = 0, solved
// by Newton from the asymptotic (2n-1) pi/2.
double cantileverRoot(int n);

// Simply supported Timoshenko beam (Timoshenko 1921 / Han, Benaroya & Wei 1999):
// lowest root omega of the 2x2 problem for mode n,
//   [kGA k^2 - mu w^2,  kGA k; kGA k, EI k^2 + kGA - rhoI w^2] = 0, k = n pi / L.
double timoshenkoSimplySupportedOmega(double EI, double kGA, double mu, double rhoI,
                                      double L, int n);

}  // namespace fc::fe::test
