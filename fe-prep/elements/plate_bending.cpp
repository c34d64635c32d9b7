#include "fe-prep/elements/plate_bending.h"

#include <stdexcept>

namespace fc::fe {
namespace {

// Side k joins nodes k and k+1; its bubble is P_k = 4 L_k L_{k+1}.
Eigen::Vector2d bubbleGradient(const TriangleGeometry& g, int k, const Eigen::Vector3d& L) {
  const int j = (k + 1) % 3;
  return 4.0 * (L(j) * g.grad.row(k) + L(k) * g.grad.row(j)).transpose();
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
  // Side-wise shear relation: along side k the plate is a Timoshenko strip,
  // T_s = D_ss beta_s,ss with beta_s,ss = -8 dbeta_k / l^2 (the bubble), so
  //   gamma_sk = -(8 D_ss / (As_ss l^2)) dbeta_k,
  // D_ss = r^T D r, r = [t_x^2, t_y^2, 2 t_x t_y] (bending stiffness for
  // curvature along t) and As_ss = t^T As t. Each dbeta_k then depends only on
  // its own side, as in DKT, which keeps beta conforming between elements.
  Eigen::Vector3d a = Eigen::Vector3d::Constant(2.0 / 3.0);
  if (shear_) {
    if (As_.llt().info() != Eigen::Success || As_.determinant() <= 0.0)
      throw std::invalid_argument(
          "DST triangle: the transverse shear stiffness As must be positive definite");
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d t = g.tangent.row(k).transpose();
      const Eigen::Vector3d r(t(0) * t(0), t(1) * t(1), 2.0 * t(0) * t(1));
      a(k) += 8.0 * r.dot(D_ * r) / (t.dot(As_ * t) * g.side_length(k) * g.side_length(k));
    }
  }
  H_ = a.cwiseInverse().asDiagonal() * R;
  if (shear_) {
    // Side shear strains from the constraint, gamma_s = (2/3) dbeta - R, and the
    // linear field gamma = c + b (-(y - yc), x - xc) whose tangential component
    // is constant on every side and equal to gamma_sk there (rotated Raviart-
    // Thomas field, the assumed shear of DKMT / MITC3).
    Eigen::Matrix3d Tm;
    const Eigen::Vector2d xc = g.xy.colwise().mean().transpose();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d d = g.xy.row(k).transpose() - xc;
      Tm(k, 0) = g.tangent(k, 0);
      Tm(k, 1) = g.tangent(k, 1);
      Tm(k, 2) = d(0) * g.tangent(k, 1) - d(1) * g.tangent(k, 0);
    }
    shear_coef_ = Tm.partialPivLu().solve((2.0 / 3.0) * H_ - R);
  }
}

Eigen::Matrix<double, 2, 9> DiscretePlateTriangle::rotation(const Eigen::Vector3d& L) const {
  Eigen::Matrix<double, 2, 9> beta = Eigen::Matrix<double, 2, 9>::Zero();
  for (int i = 0; i < 3; ++i) {
    beta(0, 3 * i + 2) = L(i);   // beta_x = theta_y
    beta(1, 3 * i + 1) = -L(i);  // beta_y = -theta_x
  }
  for (int k = 0; k < 3; ++k) {
    const double P = 4.0 * L(k) * L((k + 1) % 3);
    beta.row(0) += P * g_.tangent(k, 0) * H_.row(k);
    beta.row(1) += P * g_.tangent(k, 1) * H_.row(k);
  }
  return beta;
}

Eigen::Matrix<double, 2, 9> DiscretePlateTriangle::shearStrain(const Eigen::Vector3d& L) const {
  if (!shear_) return Eigen::Matrix<double, 2, 9>::Zero();
  const Eigen::Vector2d x =
      g_.xy.transpose() * L - g_.xy.colwise().mean().transpose();
  Eigen::Matrix<double, 2, 3> P;
  P << 1.0, 0.0, -x(1), 0.0, 1.0, x(0);
  return P * shear_coef_;
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
  if (shear_) {
    for (int q = 0; q < 3; ++q) {
      const Eigen::Matrix<double, 2, 9> Bs = shearStrain(rule[q].L);
      K += (rule[q].weight_fraction * g_.area) * Bs.transpose() * As_ * Bs;
    }
  }
  return K;
}

}  // namespace fc::fe
