#include "mbs-run/sampling.h"

namespace fc::mbs {

Sample takeSample(System& sys, double t, Eigen::VectorXd y) {
  const Model& m = sys.model();
  for (const Body& b : m.bodies)
    if (!b.fixed) y.segment<4>(b.pos_index + 3).normalize();
  std::vector<BodyPose> P;  // (modal coordinates come with the poses)
  sys.poses(y, P);
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
  }
  const std::vector<Eigen::Vector3d> reac = sys.reactions(t, y);
  s.joints.resize(m.joints.size());
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    s.joints[j].reaction_force = reac[j];
    s.joints[j].angle = m.joints[j].type == JointType::Revolute ? sys.jointAngle(int(j), y) : 0.0;
  }
  s.energy = sys.energies(t, y);
  s.violation = sys.constraintViolation(t, y);
  return s;
}

}  // namespace fc::mbs
