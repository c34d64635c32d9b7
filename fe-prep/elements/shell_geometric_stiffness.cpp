#include "fe-prep/elements/shell_geometric_stiffness.h"

#include <array>

#include "fe-prep/elements/membrane_triangle.h"
#include "fe-prep/elements/plate_bending.h"
#include "fe-prep/elements/shell_frame.h"

namespace fc::fe {
namespace {

// Degree-4 rule on the triangle, 6 points (Dunavant, Int. J. Numer. Meth. Eng.
// 21 (1985) 1129, table for p = 4): area coordinates and weight fractions.
struct Point6 {
  double a, b, c, w;
};
constexpr double kA1 = 0.445948490915965, kW1 = 0.223381589678011;
constexpr double kA2 = 0.091576213509771, kW2 = 0.109951743655322;
constexpr Point6 kRule4[6] = {
    {kA1, kA1, 1 - 2 * kA1, kW1}, {kA1, 1 - 2 * kA1, kA1, kW1}, {1 - 2 * kA1, kA1, kA1, kW1},
    {kA2, kA2, 1 - 2 * kA2, kW2}, {kA2, 1 - 2 * kA2, kA2, kW2}, {1 - 2 * kA2, kA2, kA2, kW2},
};

// Local DOF per node [u v w theta_x theta_y theta_z], as shell_triangle.cpp.
constexpr int kU = 0, kV = 1, kW = 2, kTx = 3, kTy = 4;

// Unit geometric stiffnesses in the LOCAL frame: row j of S_j picks N_j.
std::array<Matrix18d, 3> localUnits(const TriangleGeometry& g, const LaminateStiffness& lam, ShellKind kind) {
  const DiscretePlateTriangle plate(g, lam.D, lam.As, kind == ShellKind::DST);
  const int ben[9] = {kW, kTx, kTy, 6 + kW, 6 + kTx, 6 + kTy, 12 + kW, 12 + kTx, 12 + kTy};
  std::array<Matrix18d, 3> out;
  for (auto& m : out) m.setZero();
  for (const Point6& p : kRule4) {
    const Eigen::Vector3d L(p.a, p.b, p.c);
    // Rows: [u_x u_y v_x v_y w_x w_y].
    Eigen::Matrix<double, 6, 18> G = Eigen::Matrix<double, 6, 18>::Zero();
    for (int i = 0; i < 3; ++i) {
      G(0, 6 * i + kU) = g.grad(i, 0);
      G(1, 6 * i + kU) = g.grad(i, 1);
      G(2, 6 * i + kV) = g.grad(i, 0);
      G(3, 6 * i + kV) = g.grad(i, 1);
    }
    // grad w = gamma - beta (gamma = 0 for DKT).
    const Eigen::Matrix<double, 2, 9> slope = plate.shearStrain(L) - plate.rotation(L);
    for (int c = 0; c < 9; ++c) G.block<2, 1>(4, ben[c]) = slope.col(c);
    const double w = p.w * g.area;
    // S = e_x e_x^T (N_xx), e_y e_y^T (N_yy), e_x e_y^T + e_y e_x^T (N_xy), per component.
    for (int comp = 0; comp < 3; ++comp) {
      const auto gx = G.row(2 * comp), gy = G.row(2 * comp + 1);
      out[0] += w * gx.transpose() * gx;
      out[1] += w * gy.transpose() * gy;
      out[2] += w * (gx.transpose() * gy + gy.transpose() * gx);
    }
  }
  return out;
}

Matrix18d toBody(const Matrix18d& A, const Eigen::Matrix3d& R) {
  Matrix18d T = Matrix18d::Zero();
  for (int b = 0; b < 6; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  Matrix18d B = T.transpose() * A * T;
  return 0.5 * (B + B.transpose());
}

}  // namespace

Eigen::Vector3d shellMembraneForces(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam, ShellKind kind,
                                    const Eigen::Vector3d& material_x, const Vector18d& q) {
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
  const Eigen::Matrix<double, 6, 1> e = shellStrainOperator(xyz, lam, kind, material_x, centre) * q;
  return lam.A * e.head<3>() + lam.B * e.tail<3>();
}

std::array<Matrix18d, 3> shellGeometricStiffnessUnits(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam,
                                                      ShellKind kind, const Eigen::Vector3d& material_x) {
  const ShellFrame frame = shellFrame(xyz, material_x);
  const TriangleGeometry g = triangleGeometry(frame.xy);
  std::array<Matrix18d, 3> out = localUnits(g, lam, kind);
  for (auto& m : out) m = toBody(m, frame.R);
  return out;
}

Matrix18d shellGeometricStiffness(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam, ShellKind kind,
                                  const Eigen::Vector3d& material_x, const Eigen::Vector3d& N) {
  const std::array<Matrix18d, 3> u = shellGeometricStiffnessUnits(xyz, lam, kind, material_x);
  return N(0) * u[0] + N(1) * u[1] + N(2) * u[2];
}

}  // namespace fc::fe
