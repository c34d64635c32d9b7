#include "mbs-run/mechanics/energy_sensitivity.h"

#include <cmath>

#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/mechanics/flexible/modal.h"
#include "mbs-run/mechanics/rigid_body.h"

namespace fc::mbs {

using Eigen::VectorXd;

EnergySensitivity energySensitivity(const Model& model, const std::vector<BodyPose>& P, const VectorXd& Qall,
                                    double dissipated, double applied_work) {
  EnergySensitivity e;
  auto add = [&e](double g, double y_i) {
    e.absolute += std::abs(g);
    e.relative += std::abs(g * y_i);
  };
  for (std::size_t k = 0; k < model.bodies.size(); ++k) {
    const Body& b = model.bodies[k];
    if (b.fixed) continue;
    VectorXd v(b.nv());
    v << P[k].rdot, P[k].w, P[k].modal_rate;
    const VectorXd p = b.flex ? VectorXd(flexibleMassMatrix(b.flex->inertia, P[k].A, P[k].modal, b.flex->secondOrder()) * v)
                              : VectorXd(rigidMassMatrix(b.mass, b.com, b.inertia_com, P[k].A) * v);
    for (int i = 0; i < b.nv(); ++i) add(p[i], v[i]);
    const VectorXd Q = Qall.segment(b.dof_index, b.nv());
    for (int i = 0; i < 3; ++i) add(Q[i], P[k].r[i]);
    for (int i = 3; i < 6; ++i) add(2.0 * Q[i], 1.0);
    if (b.modes > 0) {
      const VectorXd f = Q.tail(b.modes) - elasticForces(b.flex->modal, P[k].modal, VectorXd::Zero(b.modes));
      for (int j = 0; j < b.modes; ++j) add(f[j], P[k].modal[j]);
    }
  }
  add(1.0, dissipated);
  add(1.0, applied_work);
  return e;
}

}  // namespace fc::mbs
