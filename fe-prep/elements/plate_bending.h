#pragma once
// Bending part of the flat triangle: DKT (Batoz, Bathe & Ho 1980) and DST, the
// discrete shear triangle (Batoz & Lardeur 1989) in its side-local form (Katili
// 1993, "DKMT"; Katili, Maknun, Batoz & Katili 2019 compare both), written in
// area coordinates.
//
// Local bending DOF per node [w, theta_x, theta_y] (rotation vector). The normal
// rotations beta (u = z beta_x, v = z beta_y) are beta_x = theta_y,
// beta_y = -theta_x. Inside the element beta is quadratic:
//   beta = sum_i L_i beta_i + sum_k P_k t_k dbeta_k,   P_k = 4 L_k L_{k+1},
// the bubble on side k pointing along its tangent t_k (so the normal rotation is
// linear along each side). The side unknowns dbeta_k follow from the discrete
// constraint   int_side (w_,s + beta_s) ds = l_k gamma_sk,   with w cubic along
// the side. DKT: gamma_sk = 0. DST: gamma_sk from the side's own Timoshenko
// relation gamma_sk = -(8 D_ss / (As_ss l_k^2)) dbeta_k, and the element's shear
// strain is the linear field whose tangential component on side k is gamma_sk.
// The original DST takes gamma from the element's moment equilibrium instead;
// that couples the three sides, and then fails the constant-curvature patch test
// (measured here; see docs/elements.md), hence the side-local form.
#include <Eigen/Dense>

#include "fe-prep/elements/triangle_geometry.h"

namespace fc::fe {

using Matrix9d = Eigen::Matrix<double, 9, 9>;

class DiscretePlateTriangle {
 public:
  // D: bending stiffness [k_x, k_y, k_xy]; As: transverse shear [xz, yz]
  // (ignored when shear is false: DKT).
  DiscretePlateTriangle(const TriangleGeometry& g, const Eigen::Matrix3d& D,
                        const Eigen::Matrix2d& As, bool shear);

  // kappa = curvature(L) * u at area coordinates L; u = 9 bending DOF.
  Eigen::Matrix<double, 3, 9> curvature(const Eigen::Vector3d& L) const;
  // beta = [beta_x, beta_y] = rotation(L) * u: the element's quadratic rotation
  // field (the geometric stiffness takes the slopes from it,
  // shell_geometric_stiffness.h).
  Eigen::Matrix<double, 2, 9> rotation(const Eigen::Vector3d& L) const;
  // gamma = [gamma_xz, gamma_yz] = shearStrain(L) * u (linear; zero for DKT).
  Eigen::Matrix<double, 2, 9> shearStrain(const Eigen::Vector3d& L) const;
  // dbeta = sideRotations() * u: the tangential bubble amplitudes.
  const Eigen::Matrix<double, 3, 9>& sideRotations() const { return H_; }

  // Bending plus shear stiffness, exact integration.
  Matrix9d stiffness() const;

 private:
  TriangleGeometry g_;
  Eigen::Matrix3d D_;
  Eigen::Matrix2d As_;
  bool shear_;
  Eigen::Matrix<double, 3, 9> H_;
  Eigen::Matrix<double, 3, 9> shear_coef_ = Eigen::Matrix<double, 3, 9>::Zero();
};

}  // namespace fc::fe
