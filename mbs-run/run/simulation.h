#pragma once
// The run loop: integrate with error control, project onto the constraints
// after every accepted step, apply events at their times (stopping exactly
// there) or at joint-angle crossings (located on the dense output), and sample
// the results at the output times. Each of these is a stage in a file of its
// own (integrator_switching, events, crossings, sampling, run_summary);
// simulate() only sequences them.
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "mbs-run/model/model.h"
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

  void append(const Sample& s);
  Sample row(std::size_t i) const;  // the row as it was taken
};

struct Results : RunSummary, History {};

struct RunOptions {
  bool quiet = false;
};

// Runs the scene, handing each output row to `sink` as it is taken. A
// termination signal recorded by common/termination (the executable installs
// it with Policy::Record) stops the loop at the next step with status
// "interrupted by SIGxxx"; a solver failure stops it with a status saying why;
// the sink's OutputError propagates.
RunSummary simulate(const Model& model, const RunOptions& options, SampleSink& sink);
// Runs the scene keeping every output row in memory.
Results simulate(const Model& model, const RunOptions& options = {});

}  // namespace fc::mbs
