#include "mbs-run/run/margins.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "mbs-run/constrained/system.h"
#include "mbs-run/mechanics/constraints.h"
#include "mbs-run/run/sampling.h"

namespace fc::mbs {

double effectiveLengthFactor(const std::string& ends) {
  if (ends == "pinned") return 1.0;
  if (ends == "fixed") return 0.5;
  if (ends == "fixed_pinned") return 0.699;
  if (ends == "fixed_free") return 2.0;
  return 0.0;
}

double eulerLoad(double EI, double length, double K) {
  const double le = K * length;
  return M_PI * M_PI * EI / (le * le);
}

double axialCompression(const Eigen::Vector3d& fa, const Eigen::Vector3d& fb, const Eigen::Vector3d& e) {
  return 0.5 * (fa.dot(e) - fb.dot(e));
}

namespace {
// The force joint j applies to body b (global): the sample's reaction acts on
// the joint's first body, the second gets its opposite.
Eigen::Vector3d forceOn(const Model& m, const Sample& s, int j, int b) {
  const Eigen::Vector3d& f = s.joints[static_cast<std::size_t>(j)].reaction_force;
  return m.joints[static_cast<std::size_t>(j)].body_i == b ? Eigen::Vector3d(f) : Eigen::Vector3d(-f);
}
Eigen::Vector3d pointOn(const Joint& jt, int b) { return jt.body_i == b ? jt.point_i : jt.point_j; }
}  // namespace

void Margins::observe(const Model& m, const Sample& s) {
  if (joints.size() != m.joints.size()) joints.assign(m.joints.size(), JointPeak());
  if (beams.size() != m.margin_beams.size()) beams.assign(m.margin_beams.size(), Beam());
  const bool first_row = rows_++ == 0;
  for (std::size_t j = 0; j < m.joints.size() && j < s.joints.size(); ++j) {
    JointPeak& p = joints[j];
    const double f = s.joints[j].reaction_force.norm(), t = s.joints[j].reaction_torque.norm();
    if (f > p.force) p.force = f, p.force_time = s.time;
    if (m.joints[j].type != JointType::Spherical && t > p.moment) p.moment = t, p.moment_time = s.time;
    const double a = s.joints[j].angle;
    if (first_row || a < p.angle_min) p.angle_min = a, p.angle_min_time = s.time;
    if (first_row || a > p.angle_max) p.angle_max = a, p.angle_max_time = s.time;
  }
  for (std::size_t k = 0; k < m.margin_beams.size(); ++k) {
    const BeamMarginSpec& spec = m.margin_beams[k];
    const auto b = static_cast<std::size_t>(spec.body);
    const Joint& ja = m.joints[static_cast<std::size_t>(spec.joint_a)];
    const Joint& jb = m.joints[static_cast<std::size_t>(spec.joint_b)];
    const Eigen::Vector4d& q = s.bodies[b].orientation;  // Euler parameters (e0, e1, e2, e3)
    const Eigen::Matrix3d R = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).toRotationMatrix();
    const Eigen::Vector3d e = (R * (pointOn(jb, spec.body) - pointOn(ja, spec.body))).normalized();
    const double c = axialCompression(forceOn(m, s, spec.joint_a, spec.body), forceOn(m, s, spec.joint_b, spec.body), e);
    Beam& out = beams[k];
    out.axial_compression.push_back(c);
    if (c > out.compression) out.compression = c, out.compression_time = s.time;
    if (-c > out.tension) out.tension = -c, out.tension_time = s.time;
  }
}

double Margins::largestBucklingRatio(const Model& m, int* beam) const {
  double worst = 0.0;
  for (std::size_t k = 0; k < beams.size() && k < m.margin_beams.size(); ++k) {
    const double ratio = beams[k].compression / m.margin_beams[k].euler_load;
    if (k == 0 || ratio > worst) {
      worst = ratio;
      if (beam) *beam = static_cast<int>(k);
    }
  }
  return worst;
}

double Margins::overshoot(const Model& m, int joint) const {
  const auto j = static_cast<std::size_t>(joint);
  if (j >= joints.size() || m.joints[j].type != JointType::Revolute) return -1.0;
  const JointPeak& p = joints[j];
  const JointLimits& lim = m.joints[j].limits;
  double past = -1.0;
  if (lim.has_max) past = std::max(past, std::max(0.0, p.angle_max - lim.max));
  if (lim.has_min) past = std::max(past, std::max(0.0, lim.min - p.angle_min));
  // A latch holds the angle it crossed: past it in the direction of arrival.
  for (const Latch& l : latches)
    if (l.joint == joint)
      past = std::max(past, std::max(0.0, l.rate >= 0.0 ? p.angle_max - l.angle : l.angle - p.angle_min));
  return past;
}

double Margins::largestOvershoot(const Model& m, int* joint) const {
  double largest = -1.0;
  *joint = -1;
  if (rows_ == 0) return largest;
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const double past = overshoot(m, static_cast<int>(j));
    if (past > largest) largest = past, *joint = static_cast<int>(j);
  }
  return largest;
}

Margins::Latch latchArrival(System& sys, const Model& m, int joint, double angle, double t, const Eigen::VectorXd& y) {
  std::vector<BodyPose> P;
  sys.poses(y, P);
  const Joint& jt = m.joints[static_cast<std::size_t>(joint)];
  Margins::Latch l;
  l.joint = joint;
  l.time = t;
  l.angle = angle;
  l.rate = revoluteRate(jt, P[static_cast<std::size_t>(jt.body_i)], P[static_cast<std::size_t>(jt.body_j)]);
  return l;
}

}  // namespace fc::mbs
