#include "fe-prep/elements/plate_bending.h"

#include <stdexcept>

namespace fc::fe {
namespace {

// Side k joins nodes k and k+1; its bubble is P_k = 4 L_k L_{k+1}.
Eigen::Vector2d bubbleGradient(const TriangleGeometry& g, int k, const Eigen::Vector3d& L) {
  const int j = (k + 1) % 3;
  return 4.0 * (L(j) * g.grad.row(k) + L(k) * g.grad.row(j)).transpose();
}

Eigen::Matrix2d bubbleHessian(const TriangleGeometry& g, int k) {
  const int j = (k + 1) % 3;
  const Eigen::Vector2d gi = g.grad.row(k).transpose(), gj = g.grad.row(j).transpose();
  return 4.0 * (gi * gj.transpose() + gj * gi.transpose());
}

// Shear forces T = G dbeta from moment equilibrium: only the bubbles have
// second derivatives.
Eigen::Matrix<double, 2, 3> shearForceOperator(const TriangleGeometry& g,
                                               const Eigen::Matrix3d& D) {
  Eigen::Matrix<double, 2, 3> G;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix2d h = bubbleHessian(g, k);
    const double tx = g.tangent(k, 0), ty = g.tangent(k, 1);
    // beta_a,bc = h(b,c) t_a
    const double bx_xx = h(0, 0) * tx, bx_xy = h(0, 1) * tx, bx_yy = h(1, 1) * tx;
    const double by_xx = h(0, 0) * ty, by_xy = h(0, 1) * ty, by_yy = h(1, 1) * ty;
    const Eigen::Vector3d kappa_x(bx_xx, by_xy, bx_xy + by_xx);
    const Eigen::Vector3d kappa_y(bx_xy, by_yy, bx_yy + by_xy);
    const Eigen::Vector3d Mx = D * kappa_x, My = D * kappa_y;
    G(0, k) = Mx(0) + My(2);
    G(1, k) = Mx(2) + My(1);
  }
  return G;
}

}  // namespace

DiscretePlateTriangle::DiscretePlateTriangle(const TriangleGeometry& g,
                                             const Eigen::Matrix3d& D,
                                             const Eigen::Matrix2d& As, bool shear)
    : g_(g), D_(D), As_(As), shear_(shear) {
  // Right-hand side of the side constraint, per unit side length:
  //   (2/3) dbeta_k - gamma_sk = -(w_j - w_i)/l - (beta_s,i + beta_s,j)/2,
  // with beta_s = t . beta = t_x theta_y - t_y theta_x.
  Eigen::Matrix<double, 3, 9> R = Eigen::Matrix<double, 3, 9>::Zero();
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    const double l = g.side_length(k), tx = g.tangent(k, 0), ty = g.tangent(k, 1);
    R(k, 3 * k) += 1.0 / l;
    R(k, 3 * j) -= 1.0 / l;
    for (int n : {k, j}) {
      R(k, 3 * n + 1) += 0.5 * ty;
      R(k, 3 * n + 2) -= 0.5 * tx;
    }
  }
  Eigen::Matrix3d A = (2.0 / 3.0) * Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 2, 3> shear_of_dbeta = Eigen::Matrix<double, 2, 3>::Zero();
  if (shear_) {
    Eigen::LLT<Eigen::Matrix2d> llt(As_);
    if (llt.info() != Eigen::Success || As_.determinant() <= 0.0)
      throw std::invalid_argument(
          "DST triangle: the transverse shear stiffness As must be positive definite");
    shear_of_dbeta = llt.solve(shearForceOperator(g, D_));  // gamma = As^-1 G dbeta
    A -= g.tangent * shear_of_dbeta;                         // gamma_sk = t_k . gamma
  }
  H_ = A.partialPivLu().solve(R);
  if (shear_) Bs_ = shear_of_dbeta * H_;
}

Eigen::Matrix<double, 3, 9> DiscretePlateTriangle::curvature(const Eigen::Vector3d& L) const {
  // dbeta_x/dx etc. as rows acting on u: beta gradients [bx_x, bx_y, by_x, by_y].
  Eigen::Matrix<double, 4, 9> dbeta = Eigen::Matrix<double, 4, 9>::Zero();
  for (int i = 0; i < 3; ++i) {
    // beta_x = theta_y, beta_y = -theta_x at the corners.
    dbeta(0, 3 * i + 2) += g_.grad(i, 0);
    dbeta(1, 3 * i + 2) += g_.grad(i, 1);
    dbeta(2, 3 * i + 1) -= g_.grad(i, 0);
    dbeta(3, 3 * i + 1) -= g_.grad(i, 1);
  }
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d dP = bubbleGradient(g_, k, L);
    const double tx = g_.tangent(k, 0), ty = g_.tangent(k, 1);
    dbeta.row(0) += dP(0) * tx * H_.row(k);
    dbeta.row(1) += dP(1) * tx * H_.row(k);
    dbeta.row(2) += dP(0) * ty * H_.row(k);
    dbeta.row(3) += dP(1) * ty * H_.row(k);
  }
  Eigen::Matrix<double, 3, 9> B;
  B.row(0) = dbeta.row(0);
  B.row(1) = dbeta.row(3);
  B.row(2) = dbeta.row(1) + dbeta.row(2);
  return B;
}

Matrix9d DiscretePlateTriangle::stiffness() const {
  Matrix9d K = Matrix9d::Zero();
  const TrianglePoint* rule = quadraticRule();
  for (int q = 0; q < 3; ++q) {
    const Eigen::Matrix<double, 3, 9> B = curvature(rule[q].L);
    K += (rule[q].weight_fraction * g_.area) * B.transpose() * D_ * B;
  }
  if (shear_) K += g_.area * Bs_.transpose() * As_ * Bs_;
  return K;
}

}  // namespace fc::fe
