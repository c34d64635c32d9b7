#pragma once
// Bending part of the flat triangle: DKT (Batoz, Bathe & Ho 1980) and DST
// (Batoz & Lardeur 1989), written in area coordinates.
//
// Local bending DOF per node [w, theta_x, theta_y] (rotation vector). The normal
// rotations beta (u = z beta_x, v = z beta_y) are beta_x = theta_y,
// beta_y = -theta_x. Inside the element beta is quadratic:
//   beta = sum_i L_i beta_i + sum_k P_k t_k dbeta_k,   P_k = 4 L_k L_{k+1},
// the bubble on side k pointing along its tangent t_k (so the normal rotation is
// linear along each side). The side unknowns dbeta_k follow from the discrete
// constraint   int_side (w_,s + beta_s) ds = l_k gamma_sk,   with w cubic along
// the side; gamma_sk = 0 gives DKT, and DST takes gamma = As^-1 T with the shear
// forces T from moment equilibrium T_x = M_x,x + M_xy,y, T_y = M_xy,x + M_y,y
// (constant, because M = D kappa is linear). See docs/elements.md.
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
