#pragma once
// The run loop: integrate with error control, project onto the constraints
// after every accepted step, apply events at their times (stopping exactly
// there) or at joint-angle crossings (located on the dense output), and sample
// the results at the output times.
#include <Eigen/Dense>

#include <atomic>
#include <string>
#include <vector>

#include "mbs-run/model.h"
#include "mbs-run/system.h"

namespace fc::mbs {

// Everything written to the results file, one row per output time.
struct Results {
  std::vector<double> time;
  // [body][row] -> 3 or 4 values (global frame).
  std::vector<std::vector<Eigen::Vector3d>> position, velocity, angular_velocity;
  std::vector<std::vector<Eigen::Vector4d>> orientation;
  std::vector<std::vector<Eigen::VectorXd>> modal, modal_rate; // [body][row] (flexible bodies)
  std::vector<std::vector<double>> joint_angle;                // [joint][row] (revolute only)
  std::vector<std::vector<Eigen::Vector3d>> reaction;          // [joint][row]
  std::vector<double> kinetic, potential, strain, dissipated, applied_work, violation;
  std::vector<std::string> event_log;                          // "t=...: what"
  std::vector<std::string> integrator_log;                     // "t=...: method (why)", automatic switches

  std::string status = "completed";
  std::string integrator;
  long steps = 0, rejected_steps = 0, evaluations = 0;
  long projections = 0;  // steps after which the drift exceeded atol/10 and was projected away
  double cpu_seconds = 0.0, t_reached = 0.0;
  double max_violation = 0.0;        // over the output samples
  double energy_balance_error = 0.0; // max |T + V + D - W - E_ref| per event-free segment
  double energy_scale = 0.0;         // max of |T|, |V|, D over the run, to make it relative
  int max_al_iterations = 0;
};

struct RunOptions {
  bool quiet = false;
};

// Set by the SIGINT/SIGTERM handler of the executable; the loop stops at the
// next step and the results so far are written with status "interrupted".
extern std::atomic<int> g_stop_signal;

Results simulate(const Model& model, const RunOptions& options = {});

}  // namespace fc::mbs
