#include "mbs-run/mechanics/flexible/modal.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fc::mbs {

ModalProperties modalProperties(const Eigen::VectorXd& eigenvalues, double damping_ratio) {
  if (damping_ratio < 0.0)
    throw std::invalid_argument("damping_ratio must be >= 0, got " + std::to_string(damping_ratio));
  ModalProperties p;
  p.stiffness = eigenvalues;
  p.damping.resize(eigenvalues.size());
  for (Eigen::Index j = 0; j < eigenvalues.size(); ++j) {
    if (eigenvalues(j) < 0.0)
      throw std::invalid_argument("mode " + std::to_string(j + 1) + " has a negative eigenvalue (" +
                                  std::to_string(eigenvalues(j)) +
                                  "): a rigid-body mode left in the body file?");
    p.damping(j) = 2.0 * damping_ratio * std::sqrt(eigenvalues(j));
  }
  return p;
}

Eigen::VectorXd elasticForces(const ModalProperties& p, const Eigen::VectorXd& w,
                              const Eigen::VectorXd& wdot) {
  return p.stiffness.cwiseProduct(w) + p.damping.cwiseProduct(wdot);
}

double strainEnergy(const ModalProperties& p, const Eigen::VectorXd& w) {
  return 0.5 * w.dot(p.stiffness.cwiseProduct(w));
}

Eigen::VectorXd modalEnergies(const ModalProperties& p, const Eigen::VectorXd& w, const Eigen::VectorXd& wdot) {
  return 0.5 * (p.stiffness.cwiseProduct(w.cwiseAbs2()) + wdot.cwiseAbs2());
}

double dissipatedPower(const ModalProperties& p, const Eigen::VectorXd& wdot) {
  return wdot.dot(p.damping.cwiseProduct(wdot));
}

Eigen::VectorXd gravityForces(const InertiaInvariants& inv, const Eigen::Matrix3d& A,
                              const Eigen::VectorXd& w, const Eigen::Vector3d& g) {
  const int nm = inv.n_modes;
  const Eigen::Vector3d S = inv.first_moment + inv.modal_first_moment * w;
  const Eigen::Vector3d gb = A.transpose() * g;
  Eigen::VectorXd q(6 + nm);
  q.head<3>() = inv.mass * g;
  q.segment<3>(3) = S.cross(gb);
  if (nm > 0) q.tail(nm) = inv.modal_first_moment.transpose() * gb;
  return q;
}

double gravityPotential(const InertiaInvariants& inv, const Eigen::Vector3d& r,
                        const Eigen::Matrix3d& A, const Eigen::VectorXd& w,
                        const Eigen::Vector3d& g) {
  const Eigen::Vector3d S = inv.first_moment + inv.modal_first_moment * w;
  return -g.dot(inv.mass * r + A * S);
}

}  // namespace fc::mbs
