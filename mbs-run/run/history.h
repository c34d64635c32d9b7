#pragma once
// What a run produced, in memory: Results, its summary (RunSummary: status,
// counts, peaks, logs) and its output rows (History). The one name the
// in-memory simulate() returns and the writers of output/ store; defined here,
// below both, so that the writer does not include the driver.
#include <Eigen/Dense>

#include <vector>

#include "mbs-run/run/run_summary.h"
#include "mbs-run/run/sampling.h"

namespace fc::mbs {

// A run's output rows kept in memory (for tests and small runs; the
// executable streams them to the file instead), one entry per output time.
struct History {
  std::vector<double> time;
  // [body][row] -> 3 or 4 values (global frame).
  std::vector<std::vector<Eigen::Vector3d>> position, velocity, angular_velocity;
  std::vector<std::vector<Eigen::Vector4d>> orientation;
  std::vector<std::vector<Eigen::VectorXd>> modal, modal_rate; // [body][row] (flexible bodies)
  std::vector<std::vector<std::vector<Eigen::VectorXd>>> stress;  // [body][row] (bodies with stress recovery)
  std::vector<std::vector<double>> joint_angle;                // [joint][row] (revolute only)
  std::vector<std::vector<Eigen::Vector3d>> reaction, reaction_torque;  // [joint][row]
  std::vector<double> kinetic, potential, strain, dissipated, applied_work, violation;
  std::vector<std::vector<int>> limit_state;       // [joint][row] (joints with limits, else empty)
  std::vector<std::vector<double>> limit_torque;   // [joint][row]
  std::vector<std::vector<double>> distances;      // [pair of Model::distance_pairs][row] [m]
  std::vector<std::vector<double>> contact_force, contact_penetration;  // [Model::contactElements][row]

  void append(const Sample& s);
  Sample row(std::size_t i) const;  // the row as it was taken
};

struct Results : RunSummary, History {};

}  // namespace fc::mbs
