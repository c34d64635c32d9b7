#include "mbs-run/tree/tree_simulation.h"

#include <cmath>
#include <ctime>
#include <sstream>

#include "common/progress.h"
#include "common/termination.h"
#include "mbs-run/constrained/consistent_start.h"
#include "mbs-run/run/finite_guard.h"
#include "mbs-run/run/integrator_switching.h"
#include "mbs-run/tree/kinematic_tree.h"
#include "mbs-run/run/run_quality.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs {

using Eigen::VectorXd;

std::string treeFormulationDeclined(const Model& model) {
  if (model.settings.formulation == Formulation::Constrained) return "formulation: constrained";
  return treeUnsupported(model);
}

namespace {

// The joint-coordinate right-hand side: state z = [q (N), qd (N),
// E_dissipated, W_applied] (the quadratures as in system.h).
class TreeDynamics {
 public:
  TreeDynamics(const Model& m, KinematicTree tree, std::vector<JointRuntime> runtimes)
      : m_(m), tree_(std::move(tree)), rt_(std::move(runtimes)), link_of_joint_(m.joints.size(), -1) {
    for (int k = 0; k < tree_.size(); ++k) link_of_joint_[tree_.links[k].joint] = k;
  }
  int n() const { return tree_.size(); }
  const KinematicTree& tree() const { return tree_; }

  void derivative(const VectorXd& z, VectorXd& zd) {
    ++evaluations;
    const int n = tree_.size();
    treePoses(tree_, z.head(n), z.segment(n, n), P_);
    sums_.dissipation = sums_.applied_power = 0.0;
    if (tree_.other_forces.empty()) {
      sums_.Q.resize(0);
    } else {
      sums_.Q.setZero(m_.nv);
      for (int f : tree_.other_forces)
        addForceElement(m_, m_.forces[f], P_, rt_, ForceQuantity::ForcesAndPowers, sums_);
    }
    treeAccelerations(m_, tree_, P_, z.segment(n, n), sums_.Q, ws_, qdd_);
    zd.resize(2 * n + 2);
    zd.head(n) = z.segment(n, n);
    zd.segment(n, n) = qdd_;
    zd[2 * n] = sums_.dissipation;
    zd[2 * n + 1] = sums_.applied_power;
  }

  // The poses z implies (kept for the next calls).
  const std::vector<BodyPose>& poses(const VectorXd& z) {
    treePoses(tree_, z.head(n()), z.segment(n(), n()), P_);
    return P_;
  }

  // As System::energies, on the poses z implies.
  Energies energies(const VectorXd& z) {
    poses(z);
    Energies e;
    for (std::size_t k = 0; k < m_.bodies.size(); ++k) {
      const Body& b = m_.bodies[k];
      if (!b.fixed) e.kinetic += rigidKineticEnergy(b.mass, b.com, b.inertia_com, P_[k].A, P_[k].rdot, P_[k].w);
    }
    ForceSums sums;
    for (const ForceElement& fe : m_.forces)
      if (fe.enabled) addForceElement(m_, fe, P_, rt_, ForceQuantity::Potential, sums);
    e.potential = sums.potential;
    e.dissipated = z[2 * n()];
    e.applied_work = z[2 * n() + 1];
    return e;
  }

  // The revolute angle of joint j: its initial angle plus the link's turn.
  double angle(int j, const VectorXd& z) const {
    const int k = link_of_joint_[j];
    return m_.joints[j].initial_angle + tree_.links[k].angle_sign * z[k];
  }

  // After an accepted step: the unwrapping references of the rotational
  // springs' angles (constraints.h revoluteAngle), as System does.
  void accept(const VectorXd& z) {
    for (int k = 0; k < n(); ++k) {
      const int j = tree_.links[k].joint;
      if (!tree_.links[k].prismatic) rt_[j].last_angle = angle(j, z);
    }
  }

  long evaluations = 0;

 private:
  const Model& m_;
  KinematicTree tree_;
  std::vector<JointRuntime> rt_;
  std::vector<int> link_of_joint_;
  std::vector<BodyPose> P_;
  ForceSums sums_;
  TreeWorkspace ws_;
  VectorXd qdd_;
};

// The output row at z: the constrained path's sampling of the Cartesian
// state z implies (reactions from its constraint solve there), with the
// tree's own energies and unwrapped joint angles.
Sample treeSample(System& sys, TreeDynamics& dyn, double t, const VectorXd& z) {
  const Model& m = sys.model();
  const int n = dyn.n();
  const Energies e = dyn.energies(z);
  Sample s = takeSample(sys, t, constrainedState(m, dyn.poses(z), z[2 * n], z[2 * n + 1]));
  s.energy = e;
  for (std::size_t j = 0; j < m.joints.size(); ++j)
    if (m.joints[j].type == JointType::Revolute) s.joints[j].angle = dyn.angle(int(j), z);
  return s;
}

}  // namespace

RunSummary simulateTree(const Model& model, const RunOptions& options, SampleSink& output) {
  const std::clock_t cpu0 = std::clock();
  const Settings& st = model.settings;
  System sys(model);
  RunSummary R;
  R.warnings = samplingWarnings(model);
  R.formulation = "tree";
  auto write = [&](const Sample& s) {
    FiniteGuard::checkSample(model, s);
    R.observe(model, s);
    output.write(s);
  };
  fc::Progress progress("mbs-run", st.t_end, options.quiet);
  double t = 0.0;
  long evaluations = 0;
  std::unique_ptr<IntegratorSwitching> methods;
  try {
    // The constrained path's consistent start (simulation.cpp), then the
    // tree's coordinates there.
    VectorXd y = consistentStart(sys, absoluteTolerance(st));
    std::vector<BodyPose> P0;
    sys.poses(y, P0);
    std::vector<JointRuntime> runtimes;
    for (std::size_t j = 0; j < model.joints.size(); ++j) runtimes.push_back(sys.jointRuntime(int(j)));
    TreeDynamics dyn(model, buildKinematicTree(model, P0), runtimes);
    const int n = dyn.n();
    VectorXd z = VectorXd::Zero(2 * n + 2);
    z.segment(n, n) = treeRates(dyn.tree(), P0);

    // Error control on angles [rad] (or slides [m]) and their rates, as the
    // constrained path's on positions and velocities.
    const Tolerances tol = tolerances(st, 2 * n + 2);
    int non_finite = 0;
    bool watch_signals = false;  // from the initial row on, as FiniteGuard::watchSignals
    const Rhs rhs = [&](double, const VectorXd& zz, VectorXd& zd) {
      if (watch_signals) fc::throwIfTerminated();
      dyn.derivative(zz, zd);
      non_finite = zd.allFinite() ? 0 : non_finite + 1;
      if (non_finite >= FiniteGuard::kMaxNonFinite)
        throw NonFiniteState("non-finite state: the joint accelerations stayed non-finite over " +
                             std::to_string(non_finite) + " evaluations with smaller steps");
    };
    methods = std::make_unique<IntegratorSwitching>(st, rhs, StiffPart(), tol);
    R.integrator = methods->label();
    OutputClock clock(st.output_step, st.t_end);
    StallMonitor stall(st.t_end);
    EnergyBalance balance;
    methods->current().reset(0.0, z);
    write(treeSample(sys, dyn, 0.0, z));
    clock.advance();
    balance.startSegment(dyn.energies(z).total());
    watch_signals = true;
    while (t < st.t_end) {
      if (const int sig = fc::terminationSignal()) throw fc::Terminated(sig);
      Integrator& integ = methods->current();
      if (!integ.step(st.t_end)) {
        R.status = stepFailure(t, integ.name(), st.rtol, tol.atol);
        break;
      }
      const double t_new = integ.t();
      for (; clock.dueBy(t_new); clock.advance()) {
        const double to = std::min(clock.next(), t_new);
        write(treeSample(sys, dyn, to, integ.interpolate(to)));
      }
      z = integ.y();
      t = t_new;
      balance.check(dyn.energies(z).total(), R);
      dyn.accept(z);
      if (methods->switchIfStiff(t, z, R.integrator_log)) R.integrator = methods->label();
      evaluations = dyn.evaluations;
      progress.update(t, "steps " + std::to_string(methods->current().steps));
      if (std::string stalled = stall.check(t, methods->current().name()); !stalled.empty()) {
        R.status = std::move(stalled);
        break;
      }
    }
  } catch (const OutputError&) {
    throw;
  } catch (const fc::Terminated& e) {
    R.status = "interrupted by " + fc::signalName(e.signal());
  } catch (const NonFiniteState& e) {
    R.status = e.what();
  } catch (const UnsatisfiableConstraints& e) {
    R.status = e.what();
  } catch (const std::exception& e) {
    std::ostringstream msg;
    msg << "solver failure at t = " << t << ": " << e.what();
    R.status = msg.str();
  }
  progress.finish();
  R.t_reached = t;
  if (methods) {
    R.steps = methods->steps();
    R.rejected_steps = methods->rejected();
  }
  R.evaluations = evaluations;
  R.cpu_seconds = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  if (R.status == "completed") R.status = qualityStatus(R, st.rtol, st.atol > 0 ? st.atol : 1e-3 * st.rtol);
  return R;
}

}  // namespace fc::mbs
