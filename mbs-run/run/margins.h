#pragma once
// Margins a deployment engineer signs (outputs: {margins: ...}, docs/mbs-run.md
// "Margins"): per named beam its largest axial compression against its Euler
// load, per joint its peak reaction force and moment and when, per latch (an
// angle-crossing event with lock) its time and arrival rate. The contact
// monitor's smallest clearances are RunSummary::smallest_distance.
// Plain functions and a fold over the output rows; I/O is in results.cpp and
// main.cpp.
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "mbs-run/model/model.h"

namespace fc::mbs {

struct Sample;
class System;

// Effective-length factor K of the Euler load pi^2 EI / (K L)^2 for the end
// conditions a scene names: pinned-pinned 1, fixed-fixed 0.5, fixed-pinned
// 0.699 (Timoshenko & Gere, Theory of Elastic Stability, 2nd ed., sec. 2.5),
// fixed-free 2. Returns 0 for an unknown name.
double effectiveLengthFactor(const std::string& ends);

// Euler load [N] of a straight column: pi^2 EI / (K L)^2.
double eulerLoad(double EI, double length, double K);

// Axial compression [N] (positive compressive) of a two-ended member from the
// forces its two end joints apply to it (global) and the unit vector e from
// end a to end b: the mean of the two ends' pushes along the axis,
// (F_a . e - F_b . e) / 2 (they differ by the member's own inertia force).
double axialCompression(const Eigen::Vector3d& force_on_member_a, const Eigen::Vector3d& force_on_member_b,
                        const Eigen::Vector3d& e);

struct Margins {
  struct Beam {
    double compression = 0.0, compression_time = 0.0;  // largest compression [N] and when [s]
    double tension = 0.0, tension_time = 0.0;          // largest tension [N] and when
    std::vector<double> axial_compression;             // per output row [N], positive compressive
  };
  struct JointPeak {
    double force = 0.0, force_time = 0.0;    // |reaction force| [N]
    double moment = 0.0, moment_time = 0.0;  // |reaction moment| [N m] (revolute joints)
    // Revolute joints: the range of the angle over the output rows [rad].
    double angle_min = 0.0, angle_min_time = 0.0, angle_max = 0.0, angle_max_time = 0.0;
  };
  struct Latch {
    int joint = -1;
    double time = 0.0, angle = 0.0, rate = 0.0;  // [s], [rad], angle rate just before the lock [rad/s]
  };
  std::vector<Beam> beams;          // per Model::margin_beams
  std::vector<JointPeak> joints;    // per Model::joints
  std::vector<Latch> latches;       // in time order

  void observe(const Model& m, const Sample& s);
  // Largest compression / Euler load over the named beams (0 without beams), and which (-1 without).
  double largestBucklingRatio(const Model& m, int* beam = nullptr) const;
  // How far a revolute joint's angle went past its stops (limits: min, max)
  // and past the crossing angle of each latch on it, in the direction it
  // arrived [rad]; 0 when it never did, -1 for a joint with neither.
  double overshoot(const Model& m, int joint) const;
  // The largest overshoot over the joints that have stops or latches, and
  // which joint (-1 without any, or before any output row).
  double largestOvershoot(const Model& m, int* joint) const;

 private:
  long rows_ = 0;  // output rows observed
};

// The arrival of a latch at the crossing angle: the joint's angle rate in
// state y (velocities included), taken just before the event's lock acts.
Margins::Latch latchArrival(System& sys, const Model& m, int joint, double angle, double t, const Eigen::VectorXd& y);

}  // namespace fc::mbs
