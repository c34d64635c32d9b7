#include "mbs-run/simulation.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <ctime>
#include <sstream>

#include "common/progress.h"
#include "common/rotations.h"
#include "mbs-run/integrator.h"

namespace fc::mbs {

std::atomic<int> g_stop_signal{0};

namespace {

using Eigen::VectorXd;

void record(System& sys, double t, VectorXd y, Results& R) {
  const Model& m = sys.model();
  for (const Body& b : m.bodies)
    if (!b.fixed) y.segment<4>(b.pos_index + 3).normalize();
  std::vector<BodyPose> P;  // (modal coordinates come with the poses)
  sys.poses(y, P);
  R.time.push_back(t);
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    R.position[k].push_back(P[k].r);
    R.orientation[k].push_back(P[k].p);
    R.velocity[k].push_back(P[k].rdot);
    R.angular_velocity[k].push_back(P[k].A * P[k].w);
    R.modal[k].push_back(P[k].modal);
    R.modal_rate[k].push_back(P[k].modal_rate);
  }
  const std::vector<Eigen::Vector3d> reac = sys.reactions(t, y);
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    R.reaction[j].push_back(reac[j]);
    R.joint_angle[j].push_back(m.joints[j].type == JointType::Revolute ? sys.jointAngle(int(j), y) : 0.0);
  }
  const Energies e = sys.energies(t, y);
  R.kinetic.push_back(e.kinetic);
  R.potential.push_back(e.potential);
  R.strain.push_back(e.strain);
  R.dissipated.push_back(e.dissipated);
  R.applied_work.push_back(e.applied_work);
  const double v = sys.constraintViolation(t, y);
  R.violation.push_back(v);
  R.max_violation = std::max(R.max_violation, v);
  R.energy_scale = std::max({R.energy_scale, std::abs(e.kinetic), std::abs(e.potential), e.dissipated});
}

std::string timeLabel(double t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "t=%.10g:", t);
  return buf;
}

std::string describe(const Model& m, const Event& ev) {
  std::ostringstream s;
  auto names = [&](const char* what, const std::vector<int>& idx, bool joints) {
    if (idx.empty()) return;
    s << " " << what;
    for (int i : idx) s << " " << (joints ? m.joints[i].name : m.forces[i].name);
  };
  names("lock", ev.lock, true);
  names("release", ev.release, true);
  names("enable", ev.enable_joints, true);
  names("enable", ev.enable_forces, false);
  names("disable", ev.disable_joints, true);
  names("disable", ev.disable_forces, false);
  return s.str();
}

void applyEvent(System& sys, const Event& ev, const VectorXd& y) {
  for (int j : ev.enable_joints) sys.setJointEnabled(j, true, y);
  for (int j : ev.disable_joints) sys.setJointEnabled(j, false, y);
  for (int j : ev.lock) sys.setJointLocked(j, true, y);
  for (int j : ev.release) sys.setJointLocked(j, false, y);
  for (int f : ev.enable_forces) sys.setForceEnabled(f, true);
  for (int f : ev.disable_forces) sys.setForceEnabled(f, false);
}

}  // namespace

Results simulate(const Model& model, const RunOptions& options) {
  const std::clock_t cpu0 = std::clock();
  const Settings& st = model.settings;
  System sys(model);
  Results R;
  R.position.resize(model.bodies.size());
  R.orientation.resize(model.bodies.size());
  R.velocity.resize(model.bodies.size());
  R.angular_velocity.resize(model.bodies.size());
  R.modal.resize(model.bodies.size());
  R.modal_rate.resize(model.bodies.size());
  R.joint_angle.resize(model.joints.size());
  R.reaction.resize(model.joints.size());

  VectorXd y = sys.initialState();
  // Capture held poses, make the initial state consistent, then measure the
  // revolute angle offsets in the consistent configuration.
  sys.initializeJoints(y);
  sys.project(0.0, y);
  sys.initializeJoints(y);

  Tolerances tol;
  tol.rtol = st.rtol;
  tol.atol = st.atol > 0 ? st.atol : 1e-3 * st.rtol;
  // Default step limit: ten output intervals, so that a joint-angle event cannot
  // hide two crossings inside one long step of a slow motion.
  tol.max_step = st.max_step > 0 ? st.max_step : 10.0 * st.output_step;
  tol.mask = VectorXd::Ones(sys.size());
  tol.mask.tail(2).setZero();  // energy quadratures are diagnostics, not controlled
  Rhs f = [&sys](double t, const VectorXd& yy, VectorXd& yd) { sys.derivative(t, yy, yd); };
  // With `integrator: auto` a segment between events starts with
  // Dormand-Prince and moves to TR-BDF2 if a stiff eigenvalue (a fast mode
  // the joints do not clamp, such as the SAR crank's 1 kHz modes once R1 is
  // released) holds the explicit steps at the stability boundary; an event
  // changes the dynamics, so the next segment starts explicit again.
  std::unique_ptr<Integrator> explicit_method, implicit_method;
  Integrator* integ = nullptr;
  if (st.integrator == IntegratorKind::Bdf) {
    implicit_method = makeTrBdf2(f, tol);
    integ = implicit_method.get();
  } else {
    explicit_method = makeDormandPrince(f, tol);
    integ = explicit_method.get();
  }
  R.integrator = integ->name();
  auto useExplicitAgain = [&](double t_now, const VectorXd& y_now) {
    if (!st.switch_when_stiff || integ == explicit_method.get()) return false;
    integ = explicit_method.get();
    integ->reset(t_now, y_now);
    R.integrator_log.push_back(timeLabel(t_now) + " dopri5 (event)");
    return true;
  };
  const double projection_tol = 0.1 * tol.atol;
  integ->reset(0.0, y);

  // Events: time events in time order; angle events armed until they fire.
  std::vector<const Event*> timed, crossing;
  for (const Event& e : model.events) (e.joint >= 0 ? crossing : timed).push_back(&e);
  std::stable_sort(timed.begin(), timed.end(), [](const Event* a, const Event* b) { return a->time < b->time; });
  std::size_t next_timed = 0;
  std::vector<char> fired(crossing.size(), 0);

  const double t_end = st.t_end;
  long out_index = 0;
  auto nextOutputTime = [&]() { return out_index * st.output_step; };
  record(sys, 0.0, y, R);
  ++out_index;
  double e_ref = sys.energies(0.0, y).total();

  fc::Progress progress("mbs-run", t_end, options.quiet);
  double t = 0.0;
  // Any failure inside the step (a kernel throwing, a singular factorisation
  // reported as an exception) ends the run with what was computed so far and
  // a status saying why, as the contract asks of solver failures.
  try {
  while (t < t_end) {
    if (g_stop_signal.load()) {
      R.status = "interrupted by signal " + std::to_string(g_stop_signal.load());
      break;
    }
    while (next_timed < timed.size() && timed[next_timed]->time <= t) {
      // Events at or before the current time (e.g. time 0) apply now.
      applyEvent(sys, *timed[next_timed], y);
      R.event_log.push_back(timeLabel(t) + describe(model, *timed[next_timed]));
      ++next_timed;
      sys.project(t, y);
      if (!useExplicitAgain(t, y)) integ->reset(t, y);
      e_ref = sys.energies(t, y).total();
    }
    const double t_limit = next_timed < timed.size() ? std::min(t_end, timed[next_timed]->time) : t_end;
    if (!integ->step(t_limit)) {
      std::ostringstream s;
      // The usual cause at tight tolerances: the error test (or TR-BDF2's
      // Newton iteration) asks for more digits than f(y) carries (the
      // multiplier iteration stops at a 1e-10 residual), so say what to change.
      s << "solver failure: step size too small at t = " << t << " (" << integ->name() << ", rtol " << st.rtol
        << ", atol " << tol.atol << "): the error test cannot be met; at tight tolerances the right-hand side's"
        << " precision is the limit - loosen rtol or use dopri5";
      R.status = s.str();
      break;
    }
    double t_new = integ->t();
    VectorXd y_new = integ->y();
    // Joint-angle crossings: sign change of angle - value over the step, located
    // on the dense output by bisection to machine precision in time.
    const Event* hit = nullptr;
    for (std::size_t k = 0; k < crossing.size(); ++k) {
      if (fired[k]) continue;
      const Event& ev = *crossing[k];
      const double g0 = sys.jointAngle(ev.joint, y) - ev.angle;
      const double g1 = sys.jointAngle(ev.joint, y_new) - ev.angle;
      const bool cross = (g0 < 0 && g1 >= 0 && ev.direction >= 0) || (g0 > 0 && g1 <= 0 && ev.direction <= 0);
      if (!cross) continue;
      double a = t, b = t_new;
      for (int it = 0; it < 200 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++it) {
        const double mid = 0.5 * (a + b);
        const double gm = sys.jointAngle(ev.joint, integ->interpolate(mid)) - ev.angle;
        if ((gm < 0) == (g0 < 0) && gm != 0.0) a = mid; else b = mid;
      }
      if (!hit || b < t_new) {
        hit = &ev;
        t_new = b;
        fired[k] = 1;
      }
    }
    if (hit) y_new = integ->interpolate(t_new);
    while (out_index * st.output_step <= t_new + 1e-12 * std::max(1.0, t_new) && nextOutputTime() <= t_end + 1e-12) {
      const double to = std::min(nextOutputTime(), t_new);
      record(sys, to, integ->interpolate(to), R);
      ++out_index;
    }
    // Energy balance over the event-free segment (sampled at steps).
    const double e_now = sys.energies(t_new, y_new).total();
    R.energy_balance_error = std::max(R.energy_balance_error, std::abs(e_now - e_ref));
    t = t_new;
    y = y_new;
    sys.updateAngleReferences(y);
    // Project only a drift the error control could see: below a tenth of
    // atol (in m, rad, m/s, rad/s) the stabilised accelerations keep it
    // bounded, and every projection costs two or three factorisations and,
    // by changing y, the first stage the next step would reuse (FSAL).
    const System::Violations viol = sys.violations(t, y);
    const bool project = hit || viol.position > projection_tol || viol.velocity > projection_tol;
    if (project) {
      sys.project(t, y);
      ++R.projections;
    }
    if (hit) {
      applyEvent(sys, *hit, y);
      R.event_log.push_back(timeLabel(t) + " joint " + model.joints[hit->joint].name +
                            " crossed " + std::to_string(hit->angle) + ";" + describe(model, *hit));
      sys.project(t, y);
    }
    const bool at_time_event = next_timed < timed.size() && t >= timed[next_timed]->time;
    const double lambda = integ->stiffness();
    if (hit) {
      if (!useExplicitAgain(t, y)) integ->reset(t, y);
    } else if (st.switch_when_stiff && lambda > st.stiff_frequency && integ == explicit_method.get()) {
      if (!implicit_method) implicit_method = makeTrBdf2(f, tol);
      integ = implicit_method.get();
      integ->reset(t, y);
      char buf[96];
      std::snprintf(buf, sizeof buf, " trbdf2 (dopri5 held at its stability boundary by |lambda| ~ %.3g rad/s)",
                    lambda);
      R.integrator_log.push_back(timeLabel(t) + buf);
      R.integrator = "dopri5+trbdf2";
    } else if (project) {
      integ->restart(t, y);
    }
    if (hit || at_time_event) e_ref = sys.energies(t, y).total();
    progress.update(t, "steps " + std::to_string(integ->steps));
  }
  } catch (const std::exception& e) {
    std::ostringstream msg;
    msg << "solver failure at t = " << t << ": " << e.what();
    R.status = msg.str();
  }
  progress.finish();
  R.t_reached = t;
  for (const auto* m : {explicit_method.get(), implicit_method.get()})
    if (m) {
      R.steps += m->steps;
      R.rejected_steps += m->rejected;
    }
  R.evaluations = sys.stats().evaluations;
  R.max_al_iterations = sys.stats().max_al_iterations;
  R.cpu_seconds = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  return R;
}

}  // namespace fc::mbs
