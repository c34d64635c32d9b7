#include "fe-prep/elements/shell_triangle.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "fe-prep/elements/membrane_triangle.h"
#include "fe-prep/elements/plate_bending.h"
#include "fe-prep/elements/shell_frame.h"

namespace fc::fe {
namespace {

// Local DOF per node: [u v w theta_x theta_y theta_z] (same order as the body
// DOF, so the transformation is block-diagonal).
constexpr int kU = 0, kV = 1, kW = 2, kTx = 3, kTy = 4, kTz = 5;

Matrix18d localStiffness(const TriangleGeometry& g, const LaminateStiffness& lam,
                         ShellKind kind, double drilling) {
  const DiscretePlateTriangle plate(g, lam.D, lam.As, kind == ShellKind::DST);
  const Eigen::Matrix<double, 3, 6> Bm = membraneStrain(g);
  // Maps of the sub-element DOF into the 18 local DOF.
  int mem[6], ben[9], dri[9];
  for (int i = 0; i < 3; ++i) {
    mem[2 * i] = 6 * i + kU;
    mem[2 * i + 1] = 6 * i + kV;
    ben[3 * i] = 6 * i + kW;
    ben[3 * i + 1] = 6 * i + kTx;
    ben[3 * i + 2] = 6 * i + kTy;
    dri[3 * i] = 6 * i + kU;
    dri[3 * i + 1] = 6 * i + kV;
    dri[3 * i + 2] = 6 * i + kTz;
  }
  // Generalised strains [eps; kappa] at a point as one 6x18 operator, so that
  // A, B and D enter through the single ABD matrix.
  Eigen::Matrix<double, 6, 6> ABD;
  ABD << lam.A, lam.B, lam.B, lam.D;
  Matrix18d K = Matrix18d::Zero();
  const TrianglePoint* rule = quadraticRule();
  for (int q = 0; q < 3; ++q) {
    Eigen::Matrix<double, 6, 18> B = Eigen::Matrix<double, 6, 18>::Zero();
    const Eigen::Matrix<double, 3, 9> Bb = plate.curvature(rule[q].L);
    for (int c = 0; c < 6; ++c) B.block<3, 1>(0, mem[c]) = Bm.col(c);
    for (int c = 0; c < 9; ++c) B.block<3, 1>(3, ben[c]) = Bb.col(c);
    // Coefficient-wise (lazyProduct): at 18 x 6 x 18 Eigen's blocked GEMM costs
    // more in set-up than in arithmetic (a fifth of the element's time).
    const Eigen::Matrix<double, 6, 18> DB = ABD * B;
    K.noalias() += (rule[q].weight_fraction * g.area) * B.transpose().lazyProduct(DB);
  }
  Eigen::Matrix<double, 9, 9> Ks = Eigen::Matrix<double, 9, 9>::Zero();
  for (int q = 0; q < 3; ++q) {
    const Eigen::Matrix<double, 2, 9> Bs = plate.shearStrain(rule[q].L);
    Ks += (rule[q].weight_fraction * g.area) * Bs.transpose() * lam.As * Bs;
  }
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) K(ben[r], ben[c]) += Ks(r, c);

  if (drilling > 0.0) {
    double kmin = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) kmin = std::min({kmin, K(6 * i + kTx, 6 * i + kTx),
                                                 K(6 * i + kTy, 6 * i + kTy)});
    // The penalty's own theta_z diagonal is c A / 6: scale it to drilling * kmin.
    const Eigen::Matrix<double, 9, 9> Kd = drillingPenalty(g, 6.0 * drilling * kmin / g.area);
    for (int r = 0; r < 9; ++r)
      for (int c = 0; c < 9; ++c) K(dri[r], dri[c]) += Kd(r, c);
  }
  return K;
}

// Through-thickness kinematics u(z) = u0 + z theta_y, v(z) = v0 - z theta_x,
// w(z) = w0 give the kinetic energy density
//   I0 |u0'|^2 + 2 I1 (u0' theta_y' - v0' theta_x') + I2 (theta_x'^2 + theta_y'^2);
// all six fields interpolated linearly (int L_i L_j dA = A (1 + delta_ij)/12).
Matrix18d localConsistentMass(const TriangleGeometry& g, const LaminateStiffness& lam) {
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
  m(kU, kU) = m(kV, kV) = m(kW, kW) = lam.mass_per_area;
  m(kTx, kTx) = m(kTy, kTy) = lam.rotary_per_area;
  m(kU, kTy) = m(kTy, kU) = lam.first_moment;
  m(kV, kTx) = m(kTx, kV) = -lam.first_moment;
  Matrix18d M;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M.block<6, 6>(6 * i, 6 * j) = (g.area * (i == j ? 2.0 : 1.0) / 12.0) * m;
  return M;
}

// T^T A T with T = diag(R, ..., R) (q_local = T q_body), block by block: the
// dense 18x18 triple product would dominate the element's cost. Symmetrised
// against roundoff.
Matrix18d toBody(const Matrix18d& A, const Eigen::Matrix3d& R) {
  Matrix18d B;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) {
      const Eigen::Matrix3d b = R.transpose() * A.block<3, 3>(3 * i, 3 * j) * R;
      const Eigen::Matrix3d bt = R.transpose() * A.block<3, 3>(3 * j, 3 * i) * R;
      const Eigen::Matrix3d sym = 0.5 * (b + bt.transpose());
      B.block<3, 3>(3 * i, 3 * j) = sym;
      B.block<3, 3>(3 * j, 3 * i) = sym.transpose();
    }
  return B;
}

void checkLaminate(const LaminateStiffness& lam) {
  if (!(lam.mass_per_area > 0.0))
    throw std::invalid_argument("shell triangle: laminate mass per area must be positive");
  if (!(lam.rotary_per_area >= 0.0))
    throw std::invalid_argument("shell triangle: laminate rotary inertia must be non-negative");
  if (lam.D.llt().info() != Eigen::Success)
    throw std::invalid_argument("shell triangle: bending stiffness D must be positive definite");
}

}  // namespace

ShellMatrices shellTriangle(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam,
                            ShellKind kind, const Eigen::Vector3d& material_x,
                            double drilling) {
  checkLaminate(lam);
  const ShellFrame frame = shellFrame(xyz, material_x);
  const TriangleGeometry g = triangleGeometry(frame.xy);

  ShellMatrices out;
  out.K = toBody(localStiffness(g, lam, kind, drilling), frame.R);
  out.M = toBody(localConsistentMass(g, lam), frame.R);

  // Lumped: a third of the mass at each node; the rotary inertia of the
  // thickness, I2 A/3 (1 - n n^T) per node, is diagonal only in a frame
  // containing the normal, so keep its diagonal in body axes (this preserves
  // its trace, i.e. the sum of the three rotary inertias).
  const Eigen::Vector3d n = frame.R.row(2).transpose();
  const double m_node = lam.mass_per_area * g.area / 3.0;
  const double j_node = lam.rotary_per_area * g.area / 3.0;
  for (int i = 0; i < 3; ++i) {
    for (int d = 0; d < 3; ++d) {
      out.lumped(6 * i + d) = m_node;
      out.lumped(6 * i + 3 + d) = j_node * (1.0 - n(d) * n(d));
    }
  }
  return out;
}

Eigen::Matrix<double, 6, 18> shellStrainOperator(const Eigen::Matrix3d& xyz, const LaminateStiffness& lam,
                                                 ShellKind kind, const Eigen::Vector3d& material_x,
                                                 const Eigen::Vector3d& L) {
  checkLaminate(lam);
  const ShellFrame frame = shellFrame(xyz, material_x);
  const TriangleGeometry g = triangleGeometry(frame.xy);
  const DiscretePlateTriangle plate(g, lam.D, lam.As, kind == ShellKind::DST);
  const Eigen::Matrix<double, 3, 6> Bm = membraneStrain(g);
  const Eigen::Matrix<double, 3, 9> Bb = plate.curvature(L);
  // Same DOF maps as localStiffness: membrane [u v] and bending [w tx ty] per node.
  Eigen::Matrix<double, 6, 18> local = Eigen::Matrix<double, 6, 18>::Zero();
  for (int i = 0; i < 3; ++i) {
    local.block<3, 1>(0, 6 * i + kU) = Bm.col(2 * i);
    local.block<3, 1>(0, 6 * i + kV) = Bm.col(2 * i + 1);
    local.block<3, 1>(3, 6 * i + kW) = Bb.col(3 * i);
    local.block<3, 1>(3, 6 * i + kTx) = Bb.col(3 * i + 1);
    local.block<3, 1>(3, 6 * i + kTy) = Bb.col(3 * i + 2);
  }
  // q_local = diag(R, ..., R) q_body.
  Eigen::Matrix<double, 6, 18> G;
  for (int b = 0; b < 6; ++b) G.middleCols<3>(3 * b) = local.middleCols<3>(3 * b) * frame.R;
  return G;
}

}  // namespace fc::fe
