#include "mbs-run/run/joint_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "mbs-run/mechanics/constraints.h"

namespace fc::mbs {

using Eigen::MatrixXd;
using Eigen::VectorXd;

ImpactSolution constrainedImpact(const MatrixXd& M, const MatrixXd& Phi, const VectorXd& phit,
                                 const Eigen::RowVectorXd& g, const VectorXd& v_minus, double target) {
  const Eigen::Index n = M.rows(), m = Phi.rows();
  MatrixXd C(m + 1, n);
  C.topRows(m) = Phi;
  C.row(m) = g;
  VectorXd r(m + 1);  // what the jump must supply: C dv = b - C v-
  r.head(m) = -phit - Phi * v_minus;
  r[m] = target - g.dot(v_minus);
  const Eigen::LLT<MatrixXd> llt(M);
  const MatrixXd W = llt.matrixL().solve(C.transpose());  // L^-1 C^T
  const MatrixXd S = W.transpose() * W;                     // C M^-1 C^T
  // Redundant rows make S singular; the pseudo-inverse gives the consistent
  // least-norm multipliers, the rank decided relative to S's largest pivot.
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(S);
  cod.setThreshold(1e-12);
  const VectorXd mu = cod.solve(r);
  ImpactSolution out;
  out.v_plus = v_minus + llt.solve(C.transpose() * mu);
  out.impulse = mu[m];
  return out;
}

double zenoRemainder(double restitution, double rebound_rate, double accel_into_stop) {
  if (restitution <= 0.0) return 0.0;
  if (!(accel_into_stop > 0.0) || restitution >= 1.0) return std::numeric_limits<double>::infinity();
  return 2.0 * rebound_rate / ((1.0 - restitution) * accel_into_stop);
}

bool shouldRest(double restitution, double rebound_rate, double accel_into_stop, double angle_tol, double step) {
  if (restitution <= 0.0) return true;       // plastic: nothing to rebound (a pull releases it at once)
  if (!(accel_into_stop > 0.0)) return false;  // pulled away or neutral: it leaves
  // The remainder is shorter than one step: the integrator cannot resolve it
  // (and, on a flexible body, a mode excited by the impacts would interrupt
  // the sequence long before its apex fell below angle_tol, the bounces then
  // re-excited every mode period: the SAR's chatter, docs/mbs-run.md).
  if (restitution < 1.0 && zenoRemainder(restitution, rebound_rate, accel_into_stop) <= step) return true;
  return rebound_rate * rebound_rate < 2.0 * accel_into_stop * angle_tol;
}

StopMonitor::StopMonitor(const Model& model, double angle_tol)
    : model_(model), angle_tol_(angle_tol), impacts_(model.joints.size()), release_tol_(model.joints.size(), 0.0) {
  for (std::size_t j = 0; j < model.joints.size(); ++j)
    if (model.joints[j].type == JointType::Revolute && model.joints[j].limits.any()) joints_.push_back(int(j));
}

double StopMonitor::angleRate(System& sys, int j, const VectorXd& y) const {
  const Joint& jt = model_.joints[j];
  BodyPose bi, bj;
  sys.bodyPose(jt.body_i, y, bi);
  sys.bodyPose(jt.body_j, y, bj);
  return revoluteRate(jt, bi, bj);
}

double StopMonitor::angleAccel(System& sys, int j, double t, const VectorXd& y) const {
  // d/dt of the exact rate along the flow, central difference: h = 1e-6 s
  // keeps the truncation (h^2 times the third derivative) and the rounding
  // (1e-16 |rate| / h) near 1e-10 of the rates involved.
  VectorXd yd;
  sys.derivative(t, y, yd);
  const double h = 1e-6;
  return (angleRate(sys, j, y + h * yd) - angleRate(sys, j, y - h * yd)) / (2.0 * h);
}

double StopMonitor::push(System& sys, int j, double t, const VectorXd& y) const {
  VectorXd yd;
  sys.derivative(t, y, yd);
  return -sys.jointRuntime(j).contact * sys.holdingTorque(j);
}

bool StopMonitor::restIfPushed(System& sys, int j, int side, double t, VectorXd& y, double step, double& lost,
                               double& accumulation) {
  const double e = model_.joints[j].limits.restitution;
  const double rebound = std::max(0.0, -side * angleRate(sys, j, y));  // away from the stop
  const double accel = side * angleAccel(sys, j, t, y);                 // > 0: back into the stop
  if (!shouldRest(e, rebound, accel, angle_tol_, step)) return false;
  accumulation = t + zenoRemainder(e, rebound, accel);
  const double T0 = sys.energies(t, y).kinetic;
  sys.setLimitContact(j, side, y);
  sys.project(t, y);  // the held angle row takes the unresolvable rebound
  const double T1 = sys.energies(t, y).kinetic;
  lost += std::max(0.0, T0 - T1);
  y[model_.nq + model_.nv] += std::max(0.0, T0 - T1);
  const double p = push(sys, j, t, y);
  // Hysteresis of the release test: a relative 1e-8 of the holding torque
  // (at least 1e-8 N m), far above the multipliers' rounding, far below any
  // load that matters.
  release_tol_[j] = 1e-8 * std::max(1.0, std::abs(p));
  if (p < -release_tol_[j]) {  // pulled: it leaves at once (a plastic stop under a pull)
    sys.setLimitContact(j, 0, y);
    return false;
  }
  return true;
}

void StopMonitor::start(System& sys, double t, VectorXd& y, std::vector<std::string>& log) {
  for (int j : joints_) {
    const Joint& jt = model_.joints[j];
    if (sys.jointRuntime(j).locked || !sys.jointRuntime(j).enabled) continue;
    const double th = sys.jointAngle(j, y);
    int side = 0;
    if (jt.limits.has_min && th <= jt.limits.min + angle_tol_) side = -1;
    if (jt.limits.has_max && th >= jt.limits.max - angle_tol_) side = 1;
    if (side == 0) continue;
    StopEvent ev;
    ev.kind = StopEvent::Impact;
    ev.joint = j;
    ev.side = side;
    ev.time = t;
    log.push_back(apply(sys, ev, t, y, 0.0));
  }
}

std::optional<StopEvent> StopMonitor::locate(System& sys, const Dense& dense, double t0, const VectorXd& y0, double t1,
                                             const VectorXd& y1) {
  std::optional<StopEvent> best;
  // Points at which a free joint's angle is checked inside a step.
  constexpr int kScanPoints = 8;
  auto consider = [&](StopEvent ev) {
    if (!best || ev.time < best->time) best = ev;
  };
  auto bisect = [&](auto&& inside) {  // inside(t0) false, inside(t1) true: last time outside
    double a = t0, b = t1;
    for (int it = 0; it < 200 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++it) {
      const double mid = 0.5 * (a + b);
      (inside(mid) ? b : a) = mid;
    }
    return std::make_pair(a, b);
  };
  // The scan points' states, interpolated once for all joints (per joint
  // they would cost O(N) each: O(N^2) per step on a chain of N).
  constexpr int kScan = kScanPoints;
  std::vector<VectorXd> scan(kScan);
  auto scanState = [&](int k) -> const VectorXd& {
    if (scan[k].size() == 0) scan[k] = dense(t0 + (t1 - t0) * k / kScan);
    return scan[k];
  };
  for (int j : joints_) {
    const JointRuntime& rt = sys.jointRuntime(j);
    if (rt.locked || !rt.enabled) continue;
    const JointLimits& lim = model_.joints[j].limits;
    if (rt.contact == 0) {
      for (int side : {-1, 1}) {
        if ((side < 0 && !lim.has_min) || (side > 0 && !lim.has_max)) continue;
        const double bound = side < 0 ? lim.min : lim.max;
        // Penetration (> 0 beyond the stop).
        auto pen = [&](const VectorXd& y) { return side * (sys.jointAngle(j, y) - bound); };
        StopEvent ev;
        ev.kind = StopEvent::Impact;
        ev.joint = j;
        ev.side = side;
        double ta = t0, pa = pen(y0);
        if (pa > 0.0) {
          // Beyond the stop at t0 by rounding (a located impact leaves it on
          // the admissible side, a projection may not): an impact now if
          // moving in, else it is leaving and the scan starts once it is out.
          // (A rate below atol is a joint just released at rest, not an impact.)
          if (side * angleRate(sys, j, y0) > angle_tol_) {
            ev.time = t0;
            consider(ev);
            continue;
          }
        }
        // Scan the step on the dense output (a flexible hinge's angle can dip
        // in and out within one step: its ends alone would miss it, or, just
        // after a rebound, see only the second contact): the first interval
        // from admissible to penetrated is bisected.
        const int n = kScanPoints;
        bool found = false;
        for (int k = 1; k <= n && !found; ++k) {
          const double tb = k == n ? t1 : t0 + (t1 - t0) * k / n;
          const double pb = k == n ? pen(y1) : pen(scanState(k));
          if (pa <= 0.0 && pb > 0.0) {
            const double t_lo = ta, t_hi = tb;
            double a = t_lo, b = t_hi;
            for (int it = 0; it < 200 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++it) {
              const double mid = 0.5 * (a + b);
              (pen(dense(mid)) > 0.0 ? b : a) = mid;
            }
            ev.time = a;
            found = true;
          }
          ta = tb;
          pa = pb;
        }
        if (found) consider(ev);
      }
    } else {
      const double tol = release_tol_[j];
      auto pulls = [&](double t, const VectorXd& y) { return push(sys, j, t, y) < -tol; };
      if (!pulls(t1, y1)) continue;
      StopEvent ev;
      ev.kind = StopEvent::Release;
      ev.joint = j;
      ev.side = rt.contact;
      ev.time = pulls(t0, y0) ? t0 : bisect([&](double t) { return pulls(t, dense(t)); }).second;
      consider(ev);
    }
  }
  return best;
}

std::string StopMonitor::apply(System& sys, const StopEvent& ev, double t, VectorXd& y, double step) {
  const Joint& jt = model_.joints[ev.joint];
  const int j = ev.joint;
  char buf[384];
  if (ev.kind == StopEvent::Release) {
    sys.setLimitContact(j, 0, y);
    std::snprintf(buf, sizeof buf, "t=%.10g: joint %s leaves its %s stop (pulled)", t, jt.name.c_str(),
                  ev.side < 0 ? "min" : "max");
    return buf;
  }
  sys.setLimitContact(j, 0, y);
  const double rate_minus = angleRate(sys, j, y);
  double rate_plus = rate_minus, impulse = 0.0, lost = 0.0;
  const double approach = ev.side * rate_minus;  // > 0: moving into the stop
  if (approach > 0.0) {
    sys.assembleAt(t, y);
    const MatrixXd M = MatrixXd(sys.massMatrix().toSparse());
    const MatrixXd Phi = MatrixXd(sys.constraintJacobian());
    const int nq = model_.nq, nv = model_.nv;
    std::vector<BodyPose> P;
    sys.poses(y, P);
    Eigen::RowVectorXd gi, gj, g = Eigen::RowVectorXd::Zero(nv);
    revoluteAngleJacobian(jt, P[jt.body_i], P[jt.body_j], gi, gj);
    const Body &bi = model_.bodies[jt.body_i], &bj = model_.bodies[jt.body_j];
    if (!bi.fixed) g.segment(bi.dof_index, bi.nv()) += gi;
    if (!bj.fixed) g.segment(bj.dof_index, bj.nv()) += gj;
    const double T0 = sys.energies(t, y).kinetic;
    const ImpactSolution s = constrainedImpact(M, Phi, sys.constraintTimeDerivative(), g, y.segment(nq, nv),
                                               -jt.limits.restitution * g.dot(y.segment(nq, nv)));
    y.segment(nq, nv) = s.v_plus;
    impulse = s.impulse;
    rate_plus = angleRate(sys, j, y);
    lost = std::max(0.0, T0 - sys.energies(t, y).kinetic);
    y[nq + nv] += lost;
  }
  double accumulation = t;
  const bool rests = restIfPushed(sys, j, ev.side, t, y, step, lost, accumulation);
  if (approach > 0.0) impacts_[j].push_back({t, rate_minus, rate_plus, impulse, lost});
  char rest[96] = "";
  if (rests && accumulation > t)
    std::snprintf(rest, sizeof rest, "; rests on it (its bounces would have ended at t=%.10g)", accumulation);
  else if (rests)
    std::snprintf(rest, sizeof rest, "; rests on it");
  std::snprintf(buf, sizeof buf, "t=%.10g: joint %s hits its %s stop at %.6g rad/s, leaves at %.6g rad/s "
                "(impulse %.6g N m s, %.6g J dissipated)%s", t, jt.name.c_str(), ev.side < 0 ? "min" : "max",
                rate_minus, rests ? 0.0 : rate_plus, impulse, lost, rest);
  return buf;
}

}  // namespace fc::mbs
