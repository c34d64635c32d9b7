#include "mbs-run/flexible/flexible_inertia.h"

#include <stdexcept>
#include <string>

#include "common/rotations.h"

namespace fc::mbs {

namespace {

// The w-dependent sums every term needs, evaluated once per call.
struct Deformed {
  Eigen::Vector3d S;      // sum m s
  Eigen::Matrix3d E;      // sum m s s^T
  Eigen::MatrixXd B;      // (9, nm): row 3a+b = sum m s_a Phi_b
};

Deformed deformed(const InertiaInvariants& inv, const Eigen::VectorXd& w) {
  const int nm = inv.n_modes;
  if (w.size() != nm)
    throw std::invalid_argument("flexible body: " + std::to_string(w.size()) +
                                " modal coordinates for a body with " + std::to_string(nm) + " modes");
  Deformed d;
  d.S = inv.first_moment + inv.modal_first_moment * w;
  d.E = inv.second_moment;
  d.B = inv.modal_second_moment;
  if (nm == 0) return d;
  const Eigen::VectorXd cw = inv.modal_second_moment * w;  // (9): C_ab . w
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const Eigen::VectorXd wS = inv.modal_products[3 * a + b].transpose() * w;  // (w^T S_ab)^T
      d.E(a, b) += cw(3 * a + b) + cw(3 * b + a) + wS.dot(w);
      d.B.row(3 * a + b) += wS.transpose();
    }
  return d;
}

Eigen::Matrix3d translationalInertia(const Eigen::Matrix3d& E) {
  return E.trace() * Eigen::Matrix3d::Identity() - E;
}

// Rows of sum m s~ Phi: row a = eps_abc B_bc.
Eigen::MatrixXd crossCoupling(const Eigen::MatrixXd& B) {
  Eigen::MatrixXd c(3, B.cols());
  c.row(0) = B.row(3 * 1 + 2) - B.row(3 * 2 + 1);
  c.row(1) = B.row(3 * 2 + 0) - B.row(3 * 0 + 2);
  c.row(2) = B.row(3 * 0 + 1) - B.row(3 * 1 + 0);
  return c;
}

Eigen::MatrixXd massMatrix(const InertiaInvariants& inv, const Eigen::Matrix3d& A, const Deformed& d) {
  const int nm = inv.n_modes;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6 + nm, 6 + nm);
  M.block<3, 3>(0, 0) = inv.mass * Eigen::Matrix3d::Identity();
  M.block<3, 3>(0, 3) = -A * skew(d.S);
  M.block<3, 3>(3, 3) = translationalInertia(d.E) + inv.rotary_inertia;
  if (nm > 0) {
    M.block(0, 6, 3, nm) = A * inv.modal_first_moment;
    M.block(3, 6, 3, nm) = crossCoupling(d.B) + inv.rotary_modal;
    M.block(6, 6, nm, nm) = inv.modalMass();
  }
  // Lower triangle by symmetry.
  M.triangularView<Eigen::StrictlyLower>() = M.transpose().triangularView<Eigen::StrictlyLower>();
  return M;
}

}  // namespace

Eigen::MatrixXd flexibleMassMatrix(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                   const Eigen::VectorXd& w) {
  return massMatrix(inv, A, deformed(inv, w));
}

FlexibleInertia flexibleInertia(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                const Eigen::VectorXd& w, const Eigen::VectorXd& wdot,
                                const Eigen::Vector3d& omega) {
  const int nm = inv.n_modes;
  if (wdot.size() != nm)
    throw std::invalid_argument("flexible body: " + std::to_string(wdot.size()) +
                                " modal rates for a body with " + std::to_string(nm) + " modes");
  const Deformed d = deformed(inv, w);
  FlexibleInertia out;
  out.M = massMatrix(inv, A, d);

  const Eigen::Matrix3d Wt = skew(omega);
  const Eigen::Matrix3d W2 = Wt * Wt;
  out.Qv = Eigen::VectorXd::Zero(6 + nm);
  Eigen::Vector3d s1wd = Eigen::Vector3d::Zero();  // sum m Phi wdot
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();     // G_ab = sum m s_a Phi_b wdot
  if (nm > 0) {
    s1wd = inv.modal_first_moment * wdot;
    const Eigen::VectorXd g = d.B * wdot;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) G(a, b) = g(3 * a + b);
  }
  out.Qv.head<3>() = -A * (W2 * d.S + 2.0 * Wt * s1wd);
  Eigen::Vector3d h_rot = inv.rotary_inertia * omega;
  if (nm > 0) h_rot += inv.rotary_modal * wdot;
  out.Qv.segment<3>(3) = -Wt * (translationalInertia(d.E) * omega) -
                         2.0 * (omega * G.trace() - G.transpose() * omega) - Wt * h_rot;
  if (nm > 0) {
    Eigen::VectorXd qf = Eigen::VectorXd::Zero(nm);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        qf += W2(a, b) * d.B.row(3 * b + a).transpose();
        if (Wt(a, b) != 0.0) qf += 2.0 * Wt(a, b) * (inv.modal_products[3 * a + b] * wdot);
      }
    out.Qv.tail(nm) = -qf;
  }
  return out;
}

double kineticEnergy(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                     const Eigen::VectorXd& w, const Eigen::VectorXd& v) {
  return 0.5 * v.dot(flexibleMassMatrix(inv, A, w) * v);
}

Eigen::Vector3d linearMomentum(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                               const Eigen::VectorXd& w, const Eigen::VectorXd& v) {
  return (flexibleMassMatrix(inv, A, w) * v).head<3>();
}

Eigen::Vector3d angularMomentum(const InertiaInvariants& inv, const Eigen::Vector3d& r,
                                const Eigen::Matrix3d& A, const Eigen::VectorXd& w,
                                const Eigen::VectorXd& v) {
  const Eigen::VectorXd p = flexibleMassMatrix(inv, A, w) * v;
  return r.cross(Eigen::Vector3d(p.head<3>())) + A * p.segment<3>(3);
}

Eigen::Vector3d deformedCenterOfMass(const InertiaInvariants& inv, const Eigen::VectorXd& w) {
  return deformed(inv, w).S / inv.mass;
}

}  // namespace fc::mbs
