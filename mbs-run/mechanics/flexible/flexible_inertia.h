#pragma once
// Inertia of a reduced flexible body in the floating frame of reference with
// lumped nodal masses (the paper's eqs. (5)-(6): u' = X w, modal mass block I;
// Ambrosio & Goncalves, Multibody Syst. Dyn. 6 (2001) 163-182; Shabana, Dynamics
// of Multibody Systems, 3rd ed., sec. 5.5), evaluated from the invariants of
// common/flexbody.h, or for many modes on few nodes their second-order
// terms as sums over the nodes (nodal_inertia.h: O(r nm) instead of O(nm^2)).
//
// Velocity coordinates v = [rdot (3, global), omega' (3, body axes), wdot (nm)].
// With s(w) = s0 + Phi w per node, S(w) = S0 + S1 w, B_ab(w) = C_ab + w^T S_ab
// (= sum m s_a Phi_b, a 1 x nm row) and E(w) = sum m s s^T:
//   M_rr = m I                M_rt = -A S(w)~           M_rf = A S1
//   M_tt = tr(E) I - E + Jr   M_tf = [eps_abc B_bc] + Jt  M_ff = sum_a S_aa + Jtt
// and from d'Alembert per node (node acceleration in body axes
// c_k = w~ w~ s_k + 2 w~ Phi_k wdot at vdot = 0) plus the rotary Lagrangian:
//   Q_r = -A (w~ w~ S + 2 w~ S1 wdot)
//   Q_t = -w~ I_t w - 2 (w tr G - G^T w) - w~ (Jr w + Jt wdot),  G_ab = B_ab wdot
//   Q_f = -sum_ab (w~ w~)_ab B_ba^T - 2 sum_ab (w~)_ab S_ab wdot
// (I_t = tr(E) I - E, the translational part of M_tt). The equations of motion
// are M vdot = Q_ext + Q_v - [0; 0; Lambda w + D wdot]. With nm = 0 these are
// exactly the rigid body's M and Q_v (origin off the centre of mass allowed).
#include <Eigen/Dense>
#include <cstddef>

#include "common/flexbody.h"
#include "mbs-run/mechanics/flexible/modal_products.h"
#include "mbs-run/mechanics/flexible/nodal_inertia.h"

namespace fc::mbs {

// How the second-order terms in w are evaluated, chosen once at load
// (FlexibleBodyData::secondOrder()): the node form (nodal_inertia.h), the
// invariants' S_ab over their non-zero entries (modal_products.h), or, with
// neither, the dense S_ab. All three give the same values to rounding.
struct SecondOrderForm {
  const NodalInertia* nodal = nullptr;
  const SparseModalProducts* sparse = nullptr;
  SecondOrderForm() = default;
  SecondOrderForm(std::nullptr_t) {}                               // NOLINT: the dense S_ab
  SecondOrderForm(const NodalInertia* n) : nodal(n) {}             // NOLINT: as the node form was passed
  SecondOrderForm(const SparseModalProducts* s) : sparse(s) {}     // NOLINT
  SecondOrderForm(const NodalInertia* n, const SparseModalProducts* s) : nodal(n), sparse(s) {}
};

struct FlexibleInertia {
  Eigen::MatrixXd M;   // (6+nm, 6+nm), symmetric positive definite
  Eigen::VectorXd Qv;  // (6+nm): quadratic velocity (gyroscopic, centrifugal, Coriolis) forces
};

// A: body->global rotation; w, wdot: modal coordinates and rates; omega: omega'.
FlexibleInertia flexibleInertia(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                const Eigen::VectorXd& w, const Eigen::VectorXd& wdot,
                                const Eigen::Vector3d& omega, SecondOrderForm form = {});
// form (every function here): the node form of the second-order terms, the
// same values to rounding at O(r nm) instead of O(nm^2) (nodal_inertia.h), or
// the S_ab over their pattern (modal_products.h); empty: the dense S_ab.
// The same without the constant modal block: the first six rows of M, whose
// last nm columns are the coupling C = [M_rf; M_tf] (M = [top; C^T M_ff]).
// O(nm) storage, for the solvers that use the structure of M (a diagonal
// M_ff for mass-normalised modes: mbs-run/constrained/augmented_lagrangian.h, arrow blocks).
struct FlexibleInertiaRows {
  Eigen::MatrixXd top;  // (6, 6+nm)
  Eigen::VectorXd Qv;   // (6+nm)
};
FlexibleInertiaRows flexibleInertiaRows(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                        const Eigen::VectorXd& w, const Eigen::VectorXd& wdot,
                                        const Eigen::Vector3d& omega, SecondOrderForm form = {});
// Only the mass matrix (what an implicit integrator's iteration matrix needs).
Eigen::MatrixXd flexibleMassMatrix(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                                   const Eigen::VectorXd& w, SecondOrderForm form = {});

// T = 1/2 v^T M(w) v for v = [rdot, omega', wdot].
double kineticEnergy(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                     const Eigen::VectorXd& w, const Eigen::VectorXd& v,
                     SecondOrderForm form = {});
// Global linear momentum dT/drdot, and angular momentum about the global origin
// r x L + A dT/domega' (dT/domega' is the body-axes momentum about the body origin).
Eigen::Vector3d linearMomentum(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                               const Eigen::VectorXd& w, const Eigen::VectorXd& v);
Eigen::Vector3d angularMomentum(const InertiaInvariants& inv, const Eigen::Vector3d& r,
                                const Eigen::Matrix3d& A, const Eigen::VectorXd& w,
                                const Eigen::VectorXd& v);

// Position of the deformed centre of mass in body axes, S(w) / m.
Eigen::Vector3d deformedCenterOfMass(const InertiaInvariants& inv, const Eigen::VectorXd& w);

}  // namespace fc::mbs
