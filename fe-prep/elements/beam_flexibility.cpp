#include "fe-prep/elements/beam_flexibility.h"

#include <cmath>
#include <stdexcept>

namespace fc::fe {
namespace {

Matrix6d transferE() {
  Matrix6d E = Matrix6d::Zero();
  E(4, 2) = -1.0;
  E(5, 1) = 1.0;
  return E;
}

// Rigid motion carried from node a to a point at distance x along e1:
// u(x) = u_a + th_a x (x e1) = u_a - skew(x e1) th_a, th(x) = th_a.
Matrix6d rigidTransfer(double x) {
  Matrix6d R = Matrix6d::Identity();
  R(1, 5) = x;   // u2 += x th3
  R(2, 4) = -x;  // u3 -= x th2
  return R;
}

// Gauss-Legendre on [0, 1].
constexpr double kG2x[2] = {0.21132486540518711775, 0.78867513459481288225};
constexpr double kG4x[4] = {0.06943184420297371239, 0.33000947820757186760,
                            0.66999052179242813240, 0.93056815579702628761};
constexpr double kG4w[4] = {0.17392742256872692869, 0.32607257743127307131,
                            0.32607257743127307131, 0.17392742256872692869};

}  // namespace

UniformBeam::UniformBeam(const Matrix6d& S, double L) : L_(L) {
  if (!(L > 0.0)) throw std::invalid_argument("beam element: zero or negative length");
  if (!S.isApprox(S.transpose(), 1e-10))
    throw std::invalid_argument("beam element: section stiffness is not symmetric");
  Eigen::LLT<Matrix6d> llt(S);
  if (llt.info() != Eigen::Success)
    throw std::invalid_argument("beam element: section stiffness is not positive definite");
  C_ = llt.solve(Matrix6d::Identity());
  const Matrix6d E = transferE();
  // T = I + (L - x) E:  F = L C + L^2/2 (E^T C + C E) + L^3/3 E^T C E (exact).
  F_ = L * C_ + 0.5 * L * L * (E.transpose() * C_ + C_ * E) +
       (L * L * L / 3.0) * E.transpose() * C_ * E;
  F_ = 0.5 * (F_ + F_.transpose()).eval();
  K_tip_ = F_.llt().solve(Matrix6d::Identity());
  Gamma_.leftCols<6>() = -rigidTransfer(L);
  Gamma_.rightCols<6>() = Matrix6d::Identity();
}

Matrix12d UniformBeam::stiffness() const {
  Matrix12d K = Gamma_.transpose() * K_tip_ * Gamma_;
  return 0.5 * (K + K.transpose());
}

Eigen::Matrix<double, 6, 12> UniformBeam::shape(double x) const {
  const Matrix6d E = transferE();
  // Phi(x) = int_0^x (I + (x-xi) E)^T C (I + (L-xi) E) dxi, quadratic integrand.
  Matrix6d Phi = Matrix6d::Zero();
  for (double g : kG2x) {
    const double xi = g * x;
    const Matrix6d Gx = Matrix6d::Identity() + (x - xi) * E;
    const Matrix6d Tx = Matrix6d::Identity() + (L_ - xi) * E;
    Phi += (0.5 * x) * Gx.transpose() * C_ * Tx;
  }
  Eigen::Matrix<double, 6, 12> N = Phi * K_tip_ * Gamma_;
  N.leftCols<6>() += rigidTransfer(x);
  return N;
}

Eigen::Matrix<double, 6, 12> UniformBeam::sectionForces(double x) const {
  const Matrix6d Tx = Matrix6d::Identity() + (L_ - x) * transferE();
  return Tx * K_tip_ * Gamma_;
}

Matrix12d UniformBeam::consistentMass(const Matrix6d& Ms) const {
  Matrix12d M = Matrix12d::Zero();
  for (int q = 0; q < 4; ++q) {
    const Eigen::Matrix<double, 6, 12> N = shape(kG4x[q] * L_);
    M += (kG4w[q] * L_) * N.transpose() * Ms * N;
  }
  return 0.5 * (M + M.transpose());
}

}  // namespace fc::fe
