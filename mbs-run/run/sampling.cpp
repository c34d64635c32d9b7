#include "mbs-run/run/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "mbs-run/mechanics/force_elements.h"
#include "mbs-run/monitors/bounding_volume_tree.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/monitors/stress_recovery.h"

namespace fc::mbs {

std::vector<std::string> samplingWarnings(const Model& m) {
  double f_max = 0.0;
  std::string body;
  for (const Body& b : m.bodies) {
    if (!b.flex || b.fixed) continue;
    const Eigen::VectorXd& lambda = b.flex->modal.stiffness;  // omega^2 of the kept modes
    const Eigen::Index n = std::min<Eigen::Index>(lambda.size(), b.modes);
    if (n == 0) continue;
    const double f = std::sqrt(lambda.head(n).maxCoeff()) / (2.0 * M_PI);
    if (f > f_max) {
      f_max = f;
      body = b.name;
    }
  }
  std::vector<std::string> w;
  if (f_max > 0.0 && m.settings.output_step > 0.5 / f_max) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "output_step %.4g s cannot resolve the highest kept mode (%.4g Hz, body %s): the output "
                  "rows alias it (Nyquist: output_step <= 1/(2 f) = %.4g s); the integration is not affected",
                  m.settings.output_step, f_max, body.c_str(), 0.5 / f_max);
    w.push_back(buf);
  }
  // A body named in outputs.stresses whose plies lack strengths gets its ply
  // stresses but no failure index: say so rather than leave it to be missed.
  for (const Body& b : m.bodies)
    if (b.stress && b.stress->kind == BodyStressRecovery::Kind::Shell && b.stress->failure_output < 0)
      w.push_back("outputs.stresses: body " + b.name + ": not every ply's material has `strength`, so its ply stresses "
                  "are written but no failure_index");
  return w;
}

Sample samplePoses(const Model& m, double t, const std::vector<BodyPose>& P, const std::vector<char>& force_on) {
  Sample s;
  s.time = t;
  s.bodies.resize(m.bodies.size());
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    BodySample& b = s.bodies[k];
    b.position = P[k].r;
    b.orientation = P[k].p;
    b.velocity = P[k].rdot;
    b.angular_velocity = P[k].A * P[k].w;
    b.modal = P[k].modal;
    b.modal_rate = P[k].modal_rate;
    if (m.bodies[k].stress) m.bodies[k].stress->recover(b.modal, b.stress);
  }
  s.joints.resize(m.joints.size());
  // Contact monitor: smallest distance between each named pair's geometry
  // (broad phase, bounding_volume_tree.h); each body placed once for all its pairs.
  std::vector<std::unique_ptr<PlacedGeometry>> placed(m.bodies.size());
  auto place = [&](int k) -> PlacedGeometry& {
    if (!placed[k]) {
      const Body& b = m.bodies[k];
      if (!b.geometry || !b.geometry_tree)
        throw std::logic_error("contact monitor: body '" + b.name + "' has no geometry tree (parseOutputs builds it)");
      placed[k] = std::make_unique<PlacedGeometry>(*b.geometry, *b.geometry_tree, P[k].r, P[k].A, P[k].modal);
    }
    return *placed[k];
  };
  for (const auto& pr : m.distance_pairs) s.distances.push_back(treeDistance(place(pr[0]), place(pr[1])));
  for (int f : m.contactElements()) {
    const ContactState cs = contactState(m.forces[static_cast<std::size_t>(f)], P);
    s.contact_force.push_back(force_on[static_cast<std::size_t>(f)] ? cs.force : 0.0);
    s.contact_penetration.push_back(reportedPenetration(cs));
  }
  return s;
}

Sample takeSample(System& sys, double t, Eigen::VectorXd y) {
  const Model& m = sys.model();
  for (const Body& b : m.bodies)
    if (!b.fixed) y.segment<4>(b.pos_index + 3).normalize();
  std::vector<BodyPose> P;  // (modal coordinates come with the poses)
  sys.poses(y, P);
  std::vector<char> force_on(m.forces.size());
  for (std::size_t f = 0; f < m.forces.size(); ++f) force_on[f] = sys.forceEnabled(int(f));
  Sample s = samplePoses(m, t, P, force_on);
  const std::vector<JointReaction> reac = sys.reactions(t, y);
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    s.joints[j].reaction_force = reac[j].force;
    s.joints[j].reaction_torque = reac[j].torque;
    // The angle at the poses already taken (System::jointAngle would take
    // them again for every joint: O(N^2) per row on a chain of N).
    const Joint& jt = m.joints[j];
    s.joints[j].angle =
        jt.type == JointType::Revolute ? revoluteAngle(jt, sys.jointRuntime(int(j)), P[jt.body_i], P[jt.body_j]) : 0.0;
    if (m.joints[j].limits.any()) {  // reads the multipliers reactions() left
      const JointRuntime& rt = sys.jointRuntime(int(j));
      s.joints[j].limit_state = rt.locked ? 2 : rt.contact;
      s.joints[j].limit_torque = rt.locked || rt.contact != 0 ? sys.holdingTorque(int(j)) : 0.0;
    }
  }
  s.energy = sys.energies(t, y);
  s.energy_sensitivity = sys.energySensitivity(t, y);
  s.violation = sys.constraintViolation(t, y);
  return s;
}

}  // namespace fc::mbs
