#pragma once
// Geometric (membrane-stress) stiffness of the flat laminated DKT/DST shell
// triangle (shell_triangle.h), for fe-prep's geometric_stiffness
// (docs/elements.md "Geometric stiffness of the shell triangle").
//
// A membrane prestress N = [N_xx, N_yy, N_xy] (constant over the element, in its
// laminate axes) does work through the second-order part of the Green-Lagrange
// membrane strain, E_ab = (u_a,b + u_b,a)/2 + (u_,a . u_,b)/2 over all three
// displacement components u = (u, v, w):
//   U_G = 1/2 int [N_xx |u_,x|^2 + N_yy |u_,y|^2 + 2 N_xy u_,x . u_,y] dA
//       = 1/2 q^T K_G q,   K_G = int G^T diag(S, S, S) G dA,  S = [N_xx N_xy; N_xy N_yy],
// G = d[u v w]/d[x y] per component (Cook, Malkus, Plesha & Witt, Concepts and
// Applications of Finite Element Analysis, 4th ed., Wiley 2002, ch. 18 "Stress
// stiffening and buckling", the K_sigma = int G^T S G form; von Karman keeps only
// the w terms). The in-plane terms are kept: a strip spun in its own plane gets
// its lead-lag stiffening from N_xx v_,x^2 exactly as a beam from T v'^2, and
// with all three components treated alike K_G is the same whichever way the
// element faces (a folded or curved shell's elements agree).
// Interpolations: u, v linear (the CST's, constant gradients); the slopes of w
// from the element's own rotation field rather than a separately assumed cubic
// w: Kirchhoff (DKT) w_,x = -beta_x, w_,y = -beta_y with the quadratic beta of
// plate_bending.h, the "consistent" choice of Lucena Neto et al., An explicit
// consistent geometric stiffness matrix for the DKT element, Lat. Am. J. Solids
// Struct. 14 (2017) 613-628; DST: grad w = gamma - beta with its shear strain.
// It reproduces grad w exactly for every quadratic w (DKT), so K_G passes the
// constant-curvature patch test. Integrated exactly (the integrand is quartic:
// 6-point degree-4 rule).
#include <Eigen/Dense>
#include <array>

#include "common/laminate.h"
#include "fe-prep/elements/shell_triangle.h"

namespace fc::fe {

// Membrane stress resultants [N_xx, N_yy, N_xy] in the element's laminate axes
// (shellFrame(xyz, material_x)) of the 18 body-frame DOF q: N = A eps + B kappa
// at the centroid (eps is constant in the CST; kappa is linear, so this is the
// element mean).
Eigen::Vector3d shellMembraneForces(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam, ShellKind kind,
                                    const Eigen::Vector3d& material_x, const Vector18d& q);

// K_G in the BODY frame (the 18 DOF of shellTriangle) for the constant membrane
// resultants N in the element's laminate axes. Linear in N.
Matrix18d shellGeometricStiffness(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam, ShellKind kind,
                                  const Eigen::Vector3d& material_x, const Eigen::Vector3d& N);

// The three unit matrices K_G(e_1), K_G(e_2), K_G(e_3) at once (one element
// setup): K_G(N) = sum_j N_j units[j].
std::array<Matrix18d, 3> shellGeometricStiffnessUnits(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam,
                                                      ShellKind kind, const Eigen::Vector3d& material_x);

}  // namespace fc::fe
