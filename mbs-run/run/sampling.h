#pragma once
// Sampling: what one output row of the results holds, how it is taken from a
// state, and the output clock that says which rows fall inside a step.
// Rows go to a SampleSink as they are taken (kept in memory by Results, or
// streamed to the file by ResultsFileWriter), so the run loop keeps none.
#include <Eigen/Dense>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbs-run/model/model.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs {

struct BodySample {
  Eigen::Vector3d position, velocity, angular_velocity;  // global
  Eigen::Vector4d orientation;                           // Euler parameters
  Eigen::VectorXd modal, modal_rate;                     // flexible bodies, else empty
  // Bodies with stress recovery: one field per BodyStressRecovery::outputs
  // (ply stresses, failure indices), else empty.
  std::vector<Eigen::VectorXd> stress;
};

struct JointSample {
  double angle = 0.0;  // revolute joints, else 0
  Eigen::Vector3d reaction_force = Eigen::Vector3d::Zero();   // on the first body, global
  Eigen::Vector3d reaction_torque = Eigen::Vector3d::Zero();  // on the first body about the joint point, global
  // Joints with limits (joint_limits.h): 0 free, -1 / +1 resting on the
  // min / max stop, 2 locked; the held angle row's torque about the axis.
  int limit_state = 0;
  double limit_torque = 0.0;
};

struct Sample {
  double time = 0.0;
  std::vector<BodySample> bodies;
  std::vector<JointSample> joints;
  Energies energy;
  EnergySensitivity energy_sensitivity;  // for the run-quality allowance
  double violation = 0.0;  // largest position-level constraint violation
  std::vector<double> distances;  // contact monitor, per Model::distance_pairs [m]
  // Contact force elements (Model::contactElements order): force [N] (0 while
  // disabled) and penetration [m] (negative: apart along the plane normal).
  std::vector<double> contact_force, contact_penetration;
};

// The constrained formulation's output row at (t, y); y's Euler parameters
// are normalised first.
Sample takeSample(System& sys, double t, Eigen::VectorXd y);

// The part of a row that follows from the poses P alone, whatever the
// formulation: the bodies (with their stress recovery), the contact monitor's
// distances, the contact elements' forces (0 where force_on, per
// Model::forces, is 0) and penetrations; joints sized, left at zero.
Sample samplePoses(const Model& m, double t, const std::vector<BodyPose>& P, const std::vector<char>& force_on);

// A sink's failure to store a row (a full disk): it ends the run at once and
// is reported as an error, not as a status in a file that cannot be written.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SampleSink {
 public:
  virtual ~SampleSink() = default;
  virtual void write(const Sample& s) = 0;
};

// Warnings about what the output rows cannot show: an output step longer than
// half the period of the highest kept modal frequency (Nyquist) aliases the
// modal coordinates and every quantity they move.
std::vector<std::string> samplingWarnings(const Model& m);

// Output times: k * output_step up to t_end, and t_end.
class OutputClock {
 public:
  OutputClock(double output_step, double t_end) : step_(output_step), t_end_(t_end) {}
  // Multiples of output_step up to t_end, then t_end itself when it is not
  // one: a run always writes its final state (t_end 1 s with output_step
  // 0.3 s gives 0, 0.3, 0.6, 0.9, 1; output_step beyond t_end gives 0, t_end).
  double next() const {
    const double t = index_ * step_;
    return t > t_end_ + slack(t_end_) ? t_end_ : t;
  }
  // True while the next output time lies within a step ending at t_new.
  bool dueBy(double t_new) const { return !finished() && next() <= t_new + slack(t_new); }
  void advance() { ++index_; }

 private:
  static double slack(double t) { return 1e-12 * std::max(1.0, t); }
  // The last row written was t_end (or the multiple that coincides with it).
  bool finished() const { return index_ > 0 && (index_ - 1) * step_ >= t_end_ - slack(t_end_); }
  double step_, t_end_;
  long index_ = 0;
};

}  // namespace fc::mbs
