#pragma once
// Independent reference for geometric stiffening: a converged
// Euler-Bernoulli finite-element eigen-analysis of a uniform cantilever spinning
// about an axis through its root, perpendicular to the beam, written here from
// the textbook equations and sharing no code with fe-prep or mbs-run.
//   flapwise (out of the plane of rotation):
//     EI w'''' - (T w')' + rho A w_tt = 0
//   lead-lag (in the plane of rotation), the same plus the centrifugal softening:
//     EI v'''' - (T v')' - rho A Omega^2 v + rho A v_tt = 0
//   T(x) = rho A Omega^2 (L^2 - x^2) / 2 (x from the root; axial stretch and the
//   Coriolis coupling with it neglected, as in the published tables).
// Hermite cubic elements, consistent mass, geometric stiffness int T N'^T N' dx
// by 4-point Gauss (exact: the integrand is a polynomial of degree 6).
// (Optionally a hanging beam's gravity tension, a constant tip tension, and a
// tip point mass M that adds M to the tip's translational mass and M Omega^2 L
// to the tension everywhere, below.)
// Checked in tests/fe-prep/test_geometric_stiffness.cpp
// (RotatingBeamReferenceMatchesPublishedTables): its convergence under
// refinement, the cantilever's closed form at rest, Southwell's coefficients,
// and the flapwise values attributed to Wright, Smith, Thresher & Wang, J. Appl.
// Mech. 49 (1982) 197-202, and Hodges & Rutkowski, AIAA J. 19 (1981) 1459-1466
// (quoted from memory: no copy of those tables was found to cite; see there).
#include <Eigen/Dense>

#include <cmath>

namespace fc::test {

// Angular frequencies [rad/s] of the first n modes; lag: the in-plane family.
// g_axial: an additional uniform axial acceleration field pulling the beam
// away from its root (a hanging beam under gravity g: T += rho A g (L - x)).
// tip_tension: a constant axial force P pulling the tip (T += P); tip_mass: a
// point mass M at the tip (mass M on the tip's deflection, T += M Omega^2 L and,
// lead-lag, its own centrifugal softening -M Omega^2).
inline Eigen::VectorXd rotatingBeamFrequencies(double L, double EI, double rhoA, double Omega, bool lag,
                                               int elements = 40, int n = 3, double g_axial = 0.0,
                                               double tip_tension = 0.0, double tip_mass = 0.0) {
  const int ndof = 2 * (elements + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(ndof, ndof), M = Eigen::MatrixXd::Zero(ndof, ndof);
  const double h = L / elements;
  Eigen::Matrix4d ke, me;
  ke << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h, 2 * h * h,
      -6 * h, 4 * h * h;
  ke *= EI / (h * h * h);
  me << 156, 22 * h, 54, -13 * h, 22 * h, 4 * h * h, 13 * h, -3 * h * h, 54, 13 * h, 156, -22 * h, -13 * h,
      -3 * h * h, -22 * h, 4 * h * h;
  me *= rhoA * h / 420;
  const double gx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  for (int e = 0; e < elements; ++e) {
    Eigen::Matrix4d kg = Eigen::Matrix4d::Zero();
    for (int g = 0; g < 4; ++g) {
      const double xi = 0.5 * (gx[g] + 1.0), x = (e + xi) * h;
      const double T = 0.5 * rhoA * Omega * Omega * (L * L - x * x) + rhoA * g_axial * (L - x) + tip_tension +
                       tip_mass * Omega * Omega * L;
      Eigen::Vector4d dN;  // dN/dx of the Hermite cubics
      dN << (-6 * xi + 6 * xi * xi) / h, 1 - 4 * xi + 3 * xi * xi, (6 * xi - 6 * xi * xi) / h, -2 * xi + 3 * xi * xi;
      kg += 0.5 * h * gw[g] * T * dN * dN.transpose();
    }
    Eigen::Matrix4d kt = ke + kg;
    if (lag) kt -= Omega * Omega * me;
    K.block<4, 4>(2 * e, 2 * e) += kt;
    M.block<4, 4>(2 * e, 2 * e) += me;
  }
  M(ndof - 2, ndof - 2) += tip_mass;
  if (lag) K(ndof - 2, ndof - 2) -= tip_mass * Omega * Omega;
  // Clamped root: drop the first two DOF.
  const Eigen::MatrixXd Kr = K.bottomRightCorner(ndof - 2, ndof - 2), Mr = M.bottomRightCorner(ndof - 2, ndof - 2);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kr, Mr);
  return es.eigenvalues().head(n).cwiseMax(0.0).cwiseSqrt();
}

}  // namespace fc::test
