#pragma once
// Uniform straight beam with a fully coupled 6x6 section stiffness S, in its
// local frame (x1 along the axis from node a at x=0 to node b at x=L).
//
// Generalised strains (VABS order) e = [u1', u2' - th3, u3' + th2, th1', th2', th3']
// and section forces s = S e. Under end loads P = [F; M] applied at node b
// (node a clamped), equilibrium gives the exact section forces
//   s(x) = T(x) P,   T(x) = I + (L - x) E,   E(4,2) = -1, E(5,1) = +1
// (M2 = M2_tip - (L-x) F3, M3 = M3_tip + (L-x) F2). The unit-load method then
// gives the exact tip flexibility and displacement field of a uniform beam:
//   F = int_0^L T^T S^-1 T dx,   d(x) = int_0^x G(x,xi)^T S^-1 T(xi) dxi P,
// with G(x, xi) = I + (x - xi) E. No interpolation is assumed, so one element
// is exact in linear statics whatever the coupling (shear, offsets, extension-
// twist), and d(x) serves as the element's shape functions for the mass.
#include <Eigen/Dense>

#include "common/materials.h"

namespace fc::fe {

using Matrix12d = Eigen::Matrix<double, 12, 12>;

class UniformBeam {
 public:
  // Throws std::invalid_argument unless L > 0 and S is symmetric positive definite.
  UniformBeam(const Matrix6d& S, double L);

  const Matrix6d& tipFlexibility() const { return F_; }
  // Local 12x12 stiffness, DOF [u_a, th_a, u_b, th_b] in the local frame.
  Matrix12d stiffness() const;
  // Displacements and rotations at x (local) as a function of the 12 nodal DOF:
  // the exact static field for end loads plus the rigid motion of node a.
  Eigen::Matrix<double, 6, 12> shape(double x) const;
  // int_0^L N^T Ms N dx (exact: N is cubic in x, 4-point Gauss).
  Matrix12d consistentMass(const Matrix6d& Ms) const;
  // Section forces and moments s(x) = T(x) P (VABS order [N, V2, V3, T, M2, M3],
  // on the face whose outward normal is +x1: N > 0 in tension) as a function of
  // the 12 nodal DOF: P = K_tip Gamma q is the end load at node b that the
  // element's stiffness puts there, carried to x by equilibrium. Exact for a
  // beam loaded at its nodes only (the element's own assumption).
  Eigen::Matrix<double, 6, 12> sectionForces(double x) const;

 private:
  Matrix6d C_;  // section compliance S^-1
  double L_;
  Matrix6d F_, K_tip_;
  Eigen::Matrix<double, 6, 12> Gamma_;  // tip deformation = Gamma q
};

}  // namespace fc::fe
