#pragma once
// Statistics of a run: why it ended, what the integrators did, and the
// accuracy diagnostics (constraint violation, energy balance), gathered as the
// run goes and written as the results file's root attributes and the summary.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mbs-run/run/sampling.h"
#include "mbs-run/run/margins.h"
#include "mbs-run/monitors/stress_envelope.h"

namespace fc::mbs {

struct RunSummary {
  std::string status = "completed";
  std::string integrator;
  // "tree" (joint coordinates, kinematic_tree.h) or "constrained", with why
  // when auto could not use the tree: "constrained (flexible body B)".
  std::string formulation = "constrained";
  std::vector<std::string> event_log;       // "t=...: what"
  std::vector<std::string> integrator_log;  // "t=...: method (why)", automatic switches
  long steps = 0, rejected_steps = 0, evaluations = 0;
  long projections = 0;  // steps after which the drift exceeded atol/10 and was projected away
  double cpu_seconds = 0.0, t_reached = 0.0;
  long samples = 0;                  // output rows written
  double max_violation = 0.0;        // over the output samples
  double energy_balance_error = 0.0; // max |T + V + D - W - E_ref| per event-free segment
  double energy_scale = 0.0;         // max of |T|, |V|, D over the run, to make it relative
  double energy_dissipated = 0.0;    // D at the last output row [J]: damping, friction, impacts
  EnergySensitivity energy_sensitivity;  // max of each over the run (mechanics/energy_sensitivity.h)
  double length_scale = 1.0;         // max(1 m, largest body position over the samples)
  int max_al_iterations = 0;
  // Impacts on stops, per joint (empty for joints without limits): time,
  // angle rate before and after [rad/s], impulse [N m s], energy lost [J].
  std::vector<std::vector<std::array<double, 5>>> limit_impacts;
  // Peak values over the output rows: magnitude, where (joint, or "body mode
  // k"), when.
  struct Peak {
    double value = 0.0, time = 0.0;
    std::string where;
  };
  Peak peak_reaction_force, peak_reaction_torque, peak_violation, peak_modal_coordinate;
  // Peak over the output rows of each mode's energy (modalEnergies), per body
  // (empty for rigid bodies): which modes the run excited.
  std::vector<Eigen::VectorXd> peak_modal_energy;
  // Craig-Bampton bodies: peak over the output rows of each fixed-interface
  // mode's strain energy lambda_j eta_j^2 / 2, eta = F^T q (flexible_body.h);
  // empty for other bodies. The ranking fe-prep's modes: {keep: [...]} needs.
  std::vector<Eigen::VectorXd> peak_fixed_interface_energy;
  // Largest failure index over the bodies with stress recovery, their
  // elements (0-based, rows of /mesh/centroids), plies (0-based, bottom up)
  // and output rows; found = false when no body has one.
  struct FailurePeak {
    bool found = false;
    double value = 0.0, time = 0.0;
    std::string body;
    long element = -1, ply = -1;
  };
  FailurePeak peak_failure_index;
  // The same per body (found = false for bodies without a failure index): each
  // member's peak over the run, the margins table /margins/failure_index. For
  // beams, element is the station and ply the section element.
  std::vector<FailurePeak> body_failure_peaks;
  // Largest bending moment |(M2, M3)| over the beam bodies with section
  // forces (outputs.stresses), their elements (0-based) and output rows.
  struct SectionMomentPeak {
    bool found = false;
    double value = 0.0, time = 0.0;  // [N m], [s]
    std::string body;
    long element = -1;
  };
  SectionMomentPeak peak_section_moment;
  // Per body (empty for bodies without stress recovery): the envelope of its
  // recovered fields over every output row (stress_envelope.h), written as
  // /bodies/NAME/failure_index_peak etc. Its largest failure_index_peak is
  // peak_failure_index.value: both fold the same rows.
  std::vector<StressEnvelope> stress_envelopes;
  // Smallest distance of each contact-monitor pair (Model::distance_pairs).
  std::vector<Peak> smallest_distance;
  // Per contact force element (Model::contactElements): its largest force
  // [N] and largest penetration [m] over the output rows, with when.
  std::vector<Peak> peak_contact_force, peak_contact_penetration;
  // Buckling of the named beams, every joint's peak reactions, the latches (margins.h).
  Margins margins;
  std::vector<std::string> warnings;  // e.g. an output step that undersamples the modes

  // Folds one output row into the statistics (joint and body names from the model).
  void observe(const Model& m, const Sample& s);
};

// The mode numbers of a Craig-Bampton body's fixed-interface modes ordered by
// their peak strain energy, most excited first (ties keep the lower number),
// and the share of the summed peaks each carries: what a body YAML's
// modes: {keep: [...]} can take from a run with many modes (docs/mbs-run.md).
struct ModeRanking {
  std::vector<long> modes;
  std::vector<double> share;
};
ModeRanking rankByPeakEnergy(const Eigen::VectorXd& peaks, const std::vector<long>& numbers);

// The share of the summed per-mode peak energies carried by the highest
// quarter of the kept modes (at least one mode): near 0 when the cut left
// nothing excited above it, large when the highest kept modes matter and more
// may be needed. `count` receives how many modes that quarter holds.
double highestModesEnergyShare(const Eigen::VectorXd& peaks, int* count = nullptr);

// "t=...:" prefix of the event and integrator logs.
std::string timeLabel(double t);

// The energy balance T + V + E_dissipated - W_applied = E_ref over an
// event-free segment (an event changes the potential, so each segment has its
// own reference), checked at every accepted step.
class EnergyBalance {
 public:
  void startSegment(double total) { reference_ = total; }
  void check(double total, RunSummary& r) const {
    r.energy_balance_error = std::max(r.energy_balance_error, std::abs(total - reference_));
  }

 private:
  double reference_ = 0.0;
};

}  // namespace fc::mbs
