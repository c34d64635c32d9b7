#include "mbs-run/run/run_summary.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/mechanics/flexible/modal.h"
#include "mbs-run/mechanics/flexible/section_forces.h"
#include "mbs-run/monitors/stress_recovery.h"
#include "mbs-run/monitors/stress_recovery_mixed.h"

namespace fc::mbs {

namespace {
void raise(RunSummary::Peak& p, double value, double time, const std::string& where) {
  if (value > p.value) p = {value, time, where};
}
}  // namespace

void RunSummary::observe(const Model& m, const Sample& s) {
  ++samples;
  max_violation = std::max(max_violation, s.violation);
  raise(peak_violation, s.violation, s.time, "");
  for (std::size_t j = 0; j < s.joints.size(); ++j) {
    raise(peak_reaction_force, s.joints[j].reaction_force.norm(), s.time, m.joints[j].name);
    if (m.joints[j].type != JointType::Spherical)
      raise(peak_reaction_torque, s.joints[j].reaction_torque.norm(), s.time, m.joints[j].name);
  }
  for (std::size_t k = 0; k < s.bodies.size(); ++k)
    for (Eigen::Index i = 0; i < s.bodies[k].modal.size(); ++i)
      raise(peak_modal_coordinate, std::abs(s.bodies[k].modal[i]), s.time,
            m.bodies[k].name + " mode " + std::to_string(i + 1));
  if (peak_modal_energy.size() != s.bodies.size()) {
    peak_modal_energy.assign(s.bodies.size(), Eigen::VectorXd());
    peak_fixed_interface_energy.assign(s.bodies.size(), Eigen::VectorXd());
    for (std::size_t k = 0; k < s.bodies.size(); ++k) {
      peak_modal_energy[k] = Eigen::VectorXd::Zero(m.bodies[k].flex ? m.bodies[k].modes : 0);
      if (m.bodies[k].flex && m.bodies[k].flex->fixed_interface_coordinates.size())
        peak_fixed_interface_energy[k] = Eigen::VectorXd::Zero(m.bodies[k].flex->fixed_interface_eigenvalues.size());
    }
  }
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    if (!m.bodies[k].flex || m.bodies[k].modes == 0) continue;
    const FlexibleBodyData& fb = *m.bodies[k].flex;
    peak_modal_energy[k] = peak_modal_energy[k].cwiseMax(modalEnergies(fb.modal, s.bodies[k].modal, s.bodies[k].modal_rate));
    if (fb.fixed_interface_coordinates.size())
      peak_fixed_interface_energy[k] =
          peak_fixed_interface_energy[k].cwiseMax(fixedInterfaceStrainEnergies(fb, s.bodies[k].modal));
  }
  if (stress_envelopes.size() != s.bodies.size()) stress_envelopes.assign(s.bodies.size(), StressEnvelope());
  for (std::size_t k = 0; k < s.bodies.size() && k < m.bodies.size(); ++k)
    if (const auto& r = m.bodies[k].stress) stress_envelopes[k].observe(*r, s.bodies[k].stress, s.time);
  for (std::size_t k = 0; k < s.bodies.size() && k < m.bodies.size(); ++k) {
    const auto& r = m.bodies[k].stress;
    if (!r || r->failure_output < 0 || s.bodies[k].stress.size() != r->outputs.size()) continue;
    const FailureLocation at = largestFailureIndex(*r, s.bodies[k].stress[static_cast<std::size_t>(r->failure_output)]);
    if (at.element >= 0 && (!peak_failure_index.found || at.value > peak_failure_index.value))
      peak_failure_index = {true, at.value, s.time, m.bodies[k].name, at.element, at.ply};
    if (body_failure_peaks.size() != s.bodies.size()) body_failure_peaks.resize(s.bodies.size());
    FailurePeak& bp = body_failure_peaks[k];
    if (at.element >= 0 && (!bp.found || at.value > bp.value)) bp = {true, at.value, s.time, m.bodies[k].name, at.element, at.ply};
  }
  for (std::size_t k = 0; k < s.bodies.size() && k < m.bodies.size(); ++k) {
    const auto& r = m.bodies[k].stress;
    // Beam bodies' section forces, and a mixed body's beams' (sectionForcesField).
    const Eigen::VectorXd* forces = r ? sectionForcesField(*r, s.bodies[k].stress) : nullptr;
    if (!forces) continue;
    const SectionForcePeak at = largestSectionForces(*forces);
    if (at.bending_element >= 0 && (!peak_section_moment.found || at.bending > peak_section_moment.value))
      peak_section_moment = {true, at.bending, s.time, m.bodies[k].name, at.bending_element};
  }
  if (smallest_distance.size() != s.distances.size())
    smallest_distance.assign(s.distances.size(), Peak{std::numeric_limits<double>::infinity(), 0.0, ""});
  for (std::size_t k = 0; k < s.distances.size(); ++k)
    if (s.distances[k] < smallest_distance[k].value) smallest_distance[k] = {s.distances[k], s.time, ""};
  if (peak_contact_force.size() != s.contact_force.size()) {
    peak_contact_force.assign(s.contact_force.size(), Peak{0.0, 0.0, ""});
    peak_contact_penetration.assign(s.contact_force.size(),
                                    Peak{-std::numeric_limits<double>::infinity(), 0.0, ""});
  }
  for (std::size_t k = 0; k < s.contact_force.size(); ++k) {
    if (s.contact_force[k] > peak_contact_force[k].value) peak_contact_force[k] = {s.contact_force[k], s.time, ""};
    if (s.contact_penetration[k] > peak_contact_penetration[k].value)
      peak_contact_penetration[k] = {s.contact_penetration[k], s.time, ""};
  }
  margins.observe(m, s);
  energy_dissipated = s.energy.dissipated;
  energy_scale = std::max({energy_scale, std::abs(s.energy.kinetic), std::abs(s.energy.potential), s.energy.dissipated});
  energy_sensitivity.absolute = std::max(energy_sensitivity.absolute, s.energy_sensitivity.absolute);
  energy_sensitivity.relative = std::max(energy_sensitivity.relative, s.energy_sensitivity.relative);
  for (const BodySample& b : s.bodies) length_scale = std::max(length_scale, b.position.norm());
}

double highestModesEnergyShare(const Eigen::VectorXd& peaks, int* count) {
  const long n = peaks.size();
  const long top = n == 0 ? 0 : std::max<long>(1, (n + 3) / 4);
  if (count) *count = static_cast<int>(top);
  const double total = peaks.sum();
  return total > 0 ? peaks.tail(top).sum() / total : 0.0;
}

ModeRanking rankByPeakEnergy(const Eigen::VectorXd& peaks, const std::vector<long>& numbers) {
  std::vector<long> order(static_cast<std::size_t>(peaks.size()));
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = static_cast<long>(j);
  std::stable_sort(order.begin(), order.end(), [&](long a, long b) { return peaks(a) > peaks(b); });
  ModeRanking r;
  const double total = peaks.sum();
  for (long j : order) {
    r.modes.push_back(static_cast<std::size_t>(j) < numbers.size() ? numbers[static_cast<std::size_t>(j)] : j + 1);
    r.share.push_back(total > 0 ? peaks(j) / total : 0.0);
  }
  return r;
}

std::string timeLabel(double t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "t=%.10g:", t);
  return buf;
}

}  // namespace fc::mbs
