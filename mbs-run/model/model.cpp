#include "mbs-run/model/model.h"

#include <cmath>

namespace fc::mbs {

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
}

namespace {
// Kane's spin-up law (model.h): angle, rate and acceleration added to the drive.
double spinAngle(double Os, double T, double t) {
  if (T <= 0) return 0.0;
  if (t >= T) return Os * (t - 0.5 * T);
  const double c = T / kTwoPi;
  return Os / T * (0.5 * t * t + c * c * (std::cos(kTwoPi * t / T) - 1.0));
}
double spinRate(double Os, double T, double t) {
  if (T <= 0) return 0.0;
  if (t >= T) return Os;
  return Os / T * (t - T / kTwoPi * std::sin(kTwoPi * t / T));
}
double spinAccel(double Os, double T, double t) {
  if (T <= 0 || t >= T) return 0.0;
  return Os / T * (1.0 - std::cos(kTwoPi * t / T));
}
}  // namespace

double Drive::angle(double t) const {
  return angle0 + speed * t + amplitude * std::sin(kTwoPi * frequency * t + phase) +
         spinAngle(spin_rate, spin_time, t);
}
double Drive::rate(double t) const {
  return speed + amplitude * kTwoPi * frequency * std::cos(kTwoPi * frequency * t + phase) +
         spinRate(spin_rate, spin_time, t);
}
double Drive::accel(double t) const {
  const double w = kTwoPi * frequency;
  return -amplitude * w * w * std::sin(w * t + phase) + spinAccel(spin_rate, spin_time, t);
}

double PiecewiseLinear::value(double at) const {
  if (x.empty()) return 0.0;
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  std::size_t k = 1;
  while (x[k] < at) ++k;
  const double s = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + s * (y[k] - y[k - 1]);
}

double PiecewiseLinear::integral(double at) const {
  // Exact integral of the piecewise-linear function (trapezoids between
  // breakpoints, rectangles beyond the ends), from 0 to at.
  auto primitive = [this](double b) {
    // Integral from x.front() (or b if below) to b; a common origin cancels out.
    double s = 0.0;
    if (x.empty()) return 0.0;
    if (b <= x.front()) return y.front() * (b - x.front());
    for (std::size_t k = 1; k < x.size(); ++k) {
      const double hi = std::min(b, x[k]);
      if (hi <= x[k - 1]) break;
      const double fa = y[k - 1], fb = value(hi);
      s += 0.5 * (fa + fb) * (hi - x[k - 1]);
    }
    if (b > x.back()) s += y.back() * (b - x.back());
    return s;
  };
  return primitive(at) - primitive(0.0);
}

void Model::finalize() {
  nq = nv = 0;
  for (Body& b : bodies) {
    if (b.fixed) {
      b.dof_index = b.pos_index = -1;
      continue;
    }
    b.pos_index = nq;
    b.dof_index = nv;
    nq += b.nq();
    nv += b.nv();
  }
}

int Model::bodyIndex(const std::string& name) const {
  for (std::size_t k = 0; k < bodies.size(); ++k)
    if (bodies[k].name == name) return static_cast<int>(k);
  return -1;
}
int Model::jointIndex(const std::string& name) const {
  for (std::size_t k = 0; k < joints.size(); ++k)
    if (joints[k].name == name) return static_cast<int>(k);
  return -1;
}
int Model::forceIndex(const std::string& name) const {
  for (std::size_t k = 0; k < forces.size(); ++k)
    if (forces[k].name == name) return static_cast<int>(k);
  return -1;
}

}  // namespace fc::mbs
