#pragma once
// Modal stiffness, damping and the body forces that do not depend on joints:
// the elastic terms Lambda w + D wdot of the paper's eq. (6) (Lambda = diag
// omega_j^2 for mass-normalised modes) with modal damping D = diag(2 zeta omega_j),
// and uniform gravity.
#include <Eigen/Dense>

#include "common/flexbody.h"

namespace fc::mbs {

struct ModalProperties {
  Eigen::VectorXd stiffness;  // Lambda_jj = omega_j^2 [1/s^2]
  Eigen::VectorXd damping;    // D_jj = 2 zeta omega_j [1/s]
};

// From the body file's eigenvalues (first nm used). Throws std::invalid_argument
// for a negative eigenvalue (a rigid-body mode left in the file) or zeta < 0.
ModalProperties modalProperties(const Eigen::VectorXd& eigenvalues, double damping_ratio);

// Lambda w + D wdot: subtracted from the modal rows of the equations of motion.
Eigen::VectorXd elasticForces(const ModalProperties& p, const Eigen::VectorXd& w,
                              const Eigen::VectorXd& wdot);
// U = 1/2 w^T Lambda w.
double strainEnergy(const ModalProperties& p, const Eigen::VectorXd& w);
// Energy of each mode, E_j = 1/2 Lambda_jj w_j^2 + 1/2 wdot_j^2: the
// modal oscillator's strain and kinetic energy (M-orthonormal modes), so
// sum_j of the strain parts is strainEnergy, and a freely vibrating decoupled
// mode keeps its E_j. It measures which modes a run excites.
Eigen::VectorXd modalEnergies(const ModalProperties& p, const Eigen::VectorXd& w, const Eigen::VectorXd& wdot);
// Power dissipated by modal damping, wdot^T D wdot (>= 0).
double dissipatedPower(const ModalProperties& p, const Eigen::VectorXd& wdot);

// Generalized force of uniform gravity g (global) on every lumped mass:
//   [m g; S(w)~ A^T g; S1^T A^T g]  (6+nm), S(w) = S0 + S1 w.
Eigen::VectorXd gravityForces(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                              const Eigen::VectorXd& w, const Eigen::Vector3d& g);
// Its potential, -g . (m r + A S(w)), whose negative gradient is gravityForces.
double gravityPotential(const InertiaInvariants& inv, const Eigen::Vector3d& r,
                        const Eigen::Matrix3d& A, const Eigen::VectorXd& w,
                        const Eigen::Vector3d& g);

}  // namespace fc::mbs
