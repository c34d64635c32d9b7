#include "mbs-run/run/history.h"

namespace fc::mbs {

void History::append(const Sample& s) {
  const std::size_t nb = s.bodies.size(), nj = s.joints.size();
  if (position.size() != nb) {
    for (auto* v : {&position, &velocity, &angular_velocity}) v->resize(nb);
    orientation.resize(nb);
    modal.resize(nb);
    modal_rate.resize(nb);
    stress.resize(nb);
  }
  if (reaction.size() != nj) {
    joint_angle.resize(nj);
    reaction.resize(nj);
    reaction_torque.resize(nj);
    limit_state.resize(nj);
    limit_torque.resize(nj);
  }
  if (distances.size() != s.distances.size()) distances.resize(s.distances.size());
  for (std::size_t k = 0; k < s.distances.size(); ++k) distances[k].push_back(s.distances[k]);
  if (contact_force.size() != s.contact_force.size()) {
    contact_force.resize(s.contact_force.size());
    contact_penetration.resize(s.contact_force.size());
  }
  for (std::size_t k = 0; k < s.contact_force.size(); ++k) {
    contact_force[k].push_back(s.contact_force[k]);
    contact_penetration[k].push_back(s.contact_penetration[k]);
  }
  time.push_back(s.time);
  for (std::size_t k = 0; k < nb; ++k) {
    const BodySample& b = s.bodies[k];
    position[k].push_back(b.position);
    orientation[k].push_back(b.orientation);
    velocity[k].push_back(b.velocity);
    angular_velocity[k].push_back(b.angular_velocity);
    modal[k].push_back(b.modal);
    modal_rate[k].push_back(b.modal_rate);
    stress[k].push_back(b.stress);
  }
  for (std::size_t j = 0; j < nj; ++j) {
    reaction[j].push_back(s.joints[j].reaction_force);
    reaction_torque[j].push_back(s.joints[j].reaction_torque);
    joint_angle[j].push_back(s.joints[j].angle);
    limit_state[j].push_back(s.joints[j].limit_state);
    limit_torque[j].push_back(s.joints[j].limit_torque);
  }
  kinetic.push_back(s.energy.kinetic);
  potential.push_back(s.energy.potential);
  strain.push_back(s.energy.strain);
  dissipated.push_back(s.energy.dissipated);
  applied_work.push_back(s.energy.applied_work);
  violation.push_back(s.violation);
}

Sample History::row(std::size_t i) const {
  Sample s;
  s.time = time[i];
  s.bodies.resize(position.size());
  for (std::size_t k = 0; k < position.size(); ++k) {
    BodySample& b = s.bodies[k];
    b.position = position[k][i];
    b.orientation = orientation[k][i];
    b.velocity = velocity[k][i];
    b.angular_velocity = angular_velocity[k][i];
    b.modal = modal[k][i];
    b.modal_rate = modal_rate[k][i];
    b.stress = stress[k][i];
  }
  s.joints.resize(reaction.size());
  for (std::size_t j = 0; j < reaction.size(); ++j) {
    s.joints[j].angle = joint_angle[j][i];
    s.joints[j].reaction_force = reaction[j][i];
    s.joints[j].reaction_torque = reaction_torque[j][i];
    s.joints[j].limit_state = limit_state[j][i];
    s.joints[j].limit_torque = limit_torque[j][i];
  }
  for (std::size_t k = 0; k < distances.size(); ++k) s.distances.push_back(distances[k][i]);
  for (std::size_t k = 0; k < contact_force.size(); ++k) {
    s.contact_force.push_back(contact_force[k][i]);
    s.contact_penetration.push_back(contact_penetration[k][i]);
  }
  s.energy.kinetic = kinetic[i];
  s.energy.potential = potential[i];
  s.energy.strain = strain[i];
  s.energy.dissipated = dissipated[i];
  s.energy.applied_work = applied_work[i];
  s.violation = violation[i];
  return s;
}

}  // namespace fc::mbs
