#include "mbs-run/mechanics/flexible/flexible_inertia.h"

#include <stdexcept>
#include <string>

#include "common/rotations.h"

namespace fc::mbs {

namespace {

// S^T x and S x in one pass over the columns of S (memory, not arithmetic,
// bounds these products at the sizes of many modes).
void transposedAndDirectProducts(const Eigen::MatrixXd& S, const Eigen::VectorXd& x, Eigen::VectorXd& St_x,
                                 Eigen::VectorXd& S_x) {
  const Eigen::Index n = S.cols();
  S_x.setZero(S.rows());
  St_x.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto col = S.col(j);
    St_x[j] = col.dot(x);
    S_x.noalias() += x[j] * col;
  }
}

// The w-dependent sums every term needs, evaluated once per call.
struct Deformed {
  Eigen::Vector3d S;      // sum m s
  Eigen::Matrix3d E;      // sum m s s^T
  Eigen::MatrixXd B;      // (9, nm): row 3a+b = sum m s_a Phi_b
  // Node form with rates: sum_{a<b} 2 omega~_ab (S_ab - S_ab^T) wdot (nm); empty otherwise.
  Eigen::VectorXd coriolis;
};

// form: the node form of the second-order terms (nodal_inertia.h), the
// sparse S_ab or the dense ones; wdot (with the node form) also gives the
// Coriolis rows.
Deformed deformed(const InertiaInvariants& inv, const SecondOrderForm& form, const Eigen::VectorXd& w,
                  const Eigen::VectorXd* wdot = nullptr, const Eigen::Vector3d& omega = Eigen::Vector3d::Zero()) {
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
  if (const NodalInertia* nodal = form.nodal) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) d.E(a, b) += cw(3 * a + b) + cw(3 * b + a);
    if (wdot) d.coriolis = Eigen::VectorXd::Zero(nm);
    addNodalSecondOrder(*nodal, w, wdot, omega, d.B, d.E, wdot ? &d.coriolis : nullptr);
    return d;
  }
  // S_ba = S_ab^T, so S_ab^T w and S_ba^T w = S_ab w come from one pass over
  // S_ab (a <= b): six nm x nm matrices read instead of nine. These products
  // (the second-order terms in w) are the only O(nm^2) work per evaluation.
  Eigen::VectorXd wS_ab(nm), wS_ba(nm);
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      if (form.sparse) sparseTransposedAndDirect(form.sparse->products[3 * a + b], w, wS_ab, wS_ba);
      else transposedAndDirectProducts(inv.modal_products[3 * a + b], w, wS_ab, wS_ba);
      d.B.row(3 * a + b) += wS_ab.transpose();
      const double q = wS_ab.dot(w);
      d.E(a, b) += cw(3 * a + b) + cw(3 * b + a) + q;
      if (b != a) {
        d.B.row(3 * b + a) += wS_ba.transpose();
        d.E(b, a) += cw(3 * b + a) + cw(3 * a + b) + q;
      }
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

// The first six rows of M, [M_rr M_rt M_rf; M_tr M_tt M_tf] (6, 6+nm): with
// the constant modal block M_ff they are the whole (symmetric) matrix.
Eigen::MatrixXd topRows(const InertiaInvariants& inv, const Eigen::Matrix3d& A, const Deformed& d) {
  const int nm = inv.n_modes;
  Eigen::MatrixXd T(6, 6 + nm);
  T.block<3, 3>(0, 0) = inv.mass * Eigen::Matrix3d::Identity();
  T.block<3, 3>(0, 3) = -A * skew(d.S);
  T.block<3, 3>(3, 0) = T.block<3, 3>(0, 3).transpose();
  T.block<3, 3>(3, 3) = translationalInertia(d.E) + inv.rotary_inertia;
  if (nm > 0) {
    T.block(0, 6, 3, nm) = A * inv.modal_first_moment;
    T.block(3, 6, 3, nm) = crossCoupling(d.B) + inv.rotary_modal;
  }
  return T;
}

Eigen::MatrixXd massMatrix(const InertiaInvariants& inv, const Eigen::Matrix3d& A, const Deformed& d) {
  const int nm = inv.n_modes;
  Eigen::MatrixXd M(6 + nm, 6 + nm);
  M.topRows(6) = topRows(inv, A, d);
  if (nm > 0) {
    M.bottomLeftCorner(nm, 6) = M.topRightCorner(6, nm).transpose();
    M.bottomRightCorner(nm, nm) = inv.modalMass();
  }
  return M;
}

// Q_v from the deformed sums (see the header).
Eigen::VectorXd quadraticVelocity(const InertiaInvariants& inv, const Eigen::Matrix3d& A, const Deformed& d,
                                  const Eigen::VectorXd& wdot, const Eigen::Vector3d& omega,
                                  const SparseModalProducts* sparse) {
  const int nm = inv.n_modes;
  if (wdot.size() != nm)
    throw std::invalid_argument("flexible body: " + std::to_string(wdot.size()) +
                                " modal rates for a body with " + std::to_string(nm) + " modes");
  const Eigen::Matrix3d Wt = skew(omega);
  const Eigen::Matrix3d W2 = Wt * Wt;
  Eigen::VectorXd Qv = Eigen::VectorXd::Zero(6 + nm);
  Eigen::Vector3d s1wd = Eigen::Vector3d::Zero();  // sum m Phi wdot
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();     // G_ab = sum m s_a Phi_b wdot
  if (nm > 0) {
    s1wd = inv.modal_first_moment * wdot;
    const Eigen::VectorXd g = d.B * wdot;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) G(a, b) = g(3 * a + b);
  }
  Qv.head<3>() = -A * (W2 * d.S + 2.0 * Wt * s1wd);
  Eigen::Vector3d h_rot = inv.rotary_inertia * omega;
  if (nm > 0) h_rot += inv.rotary_modal * wdot;
  Qv.segment<3>(3) = -Wt * (translationalInertia(d.E) * omega) -
                     2.0 * (omega * G.trace() - G.transpose() * omega) - Wt * h_rot;
  if (nm > 0) {
    Eigen::VectorXd qf = Eigen::VectorXd::Zero(nm);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) qf += W2(a, b) * d.B.row(3 * b + a).transpose();
    // sum_ab 2 Wt_ab S_ab wdot over a != b, Wt skew: 2 Wt_ab (S_ab - S_ab^T) wdot for a < b.
    Eigen::VectorXd St_wd(nm), S_wd(nm);
    if (d.coriolis.size() == nm) qf += d.coriolis;  // node form: already summed over the nodes
    else for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b) {
        if (Wt(a, b) == 0.0) continue;
        if (sparse) sparseTransposedAndDirect(sparse->products[3 * a + b], wdot, St_wd, S_wd);
        else transposedAndDirectProducts(inv.modal_products[3 * a + b], wdot, St_wd, S_wd);
        qf += 2.0 * Wt(a, b) * (S_wd - St_wd);
      }
    Qv.tail(nm) = -qf;
  }
  return Qv;
}

}  // namespace

Eigen::MatrixXd flexibleMassMatrix(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                   const Eigen::VectorXd& w, SecondOrderForm form) {
  return massMatrix(inv, A, deformed(inv, form, w));
}

FlexibleInertia flexibleInertia(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                const Eigen::VectorXd& w, const Eigen::VectorXd& wdot,
                                const Eigen::Vector3d& omega, SecondOrderForm form) {
  const Deformed d = deformed(inv, form, w, &wdot, omega);
  FlexibleInertia out;
  out.Qv = quadraticVelocity(inv, A, d, wdot, omega, form.sparse);
  out.M = massMatrix(inv, A, d);
  return out;
}

FlexibleInertiaRows flexibleInertiaRows(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                        const Eigen::VectorXd& w, const Eigen::VectorXd& wdot,
                                        const Eigen::Vector3d& omega, SecondOrderForm form) {
  const Deformed d = deformed(inv, form, w, &wdot, omega);
  FlexibleInertiaRows out;
  out.Qv = quadraticVelocity(inv, A, d, wdot, omega, form.sparse);
  out.top = topRows(inv, A, d);
  return out;
}

double kineticEnergy(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                     const Eigen::VectorXd& w, const Eigen::VectorXd& v, SecondOrderForm form) {
  return 0.5 * v.dot(flexibleMassMatrix(inv, A, w, form) * v);
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
  return deformed(inv, nullptr, w).S / inv.mass;
}

}  // namespace fc::mbs
