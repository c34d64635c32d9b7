#include "mbs-run/run/tree_dynamics.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "mbs-run/mechanics/energy_sensitivity.h"
#include "mbs-run/mechanics/force_elements.h"
#include "mbs-run/mechanics/rigid_body.h"
#include "mbs-run/run/finite_guard.h"
#include "mbs-run/tree/kinematic_tree.h"

namespace fc::mbs {

using Eigen::VectorXd;

std::string treeFormulationDeclined(const Model& model) {
  if (model.settings.formulation == Formulation::Constrained) return "formulation: constrained";
  return treeUnsupported(model);
}

namespace {

// The first ingredient of the tree's equations at poses P that is not
// finite, as System::nonFiniteCause words it: a body's state, a body's mass
// or inertia, a force element ("" when all are).
std::string nonFiniteCauseAt(const Model& m, const std::vector<BodyPose>& P, const std::vector<JointRuntime>& rt) {
  for (std::size_t k = 0; k < m.bodies.size(); ++k) {
    const Body& b = m.bodies[k];
    if (b.fixed) continue;
    if (!P[k].r.allFinite() || !P[k].p.allFinite() || !P[k].rdot.allFinite() || !P[k].w.allFinite())
      return "the state of body " + b.name;
    if (!std::isfinite(b.mass) || !b.com.allFinite() || !b.inertia_com.allFinite() ||
        !rigidMassMatrix(b.mass, b.com, b.inertia_com, P[k].A).allFinite() ||
        !rigidQuadraticVelocity(b.mass, b.com, b.inertia_com, P[k].A, P[k].w).allFinite())
      return "the mass or inertia of body " + b.name;
  }
  for (std::size_t f = 0; f < m.forces.size(); ++f) {
    if (!m.forces[f].enabled) continue;
    ForceSums sums;
    sums.Q.setZero(m.nv);
    addForceElement(m, m.forces[f], P, rt, ForceQuantity::ForcesAndPowers, sums);
    if (!sums.Q.allFinite() || !std::isfinite(sums.dissipation) || !std::isfinite(sums.applied_power))
      return "force element " + forceElementLabel(m, static_cast<int>(f));
  }
  return "";
}

// The joint-coordinate right-hand side: state z = [q (N), qd (N),
// E_dissipated, W_applied] (the quadratures as in system.h).
class TreeRhs {
 public:
  TreeRhs(const Model& m, KinematicTree tree, std::vector<JointRuntime> runtimes)
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

  // Each joint's reaction at z (RNEA on the ABA's accelerations at z: the
  // derivative's own forces and accelerations).
  std::vector<JointReaction> reactions(const VectorXd& z) {
    VectorXd zd;
    derivative(z, zd);
    --evaluations;  // an output row, not an integration step's evaluation
    return treeReactions(m_, tree_, P_, z.segment(n(), n()), qdd_, sums_.Q);
  }

  // Every enabled element's generalised forces at z, for the run-quality
  // allowance (mechanics/energy_sensitivity.h), as the constrained rows report it.
  EnergySensitivity energySensitivity(const VectorXd& z) {
    poses(z);
    ForceSums sums;
    sums.Q.setZero(m_.nv);
    for (const ForceElement& fe : m_.forces)
      if (fe.enabled) addForceElement(m_, fe, P_, rt_, ForceQuantity::ForcesAndPowers, sums);
    return fc::mbs::energySensitivity(m_, P_, sums.Q, z[2 * n()], z[2 * n() + 1]);
  }

  // The largest |Phi| of the joints' constraint equations (constraints.h) at
  // the poses z implies: rounding, as the tree holds its joints exactly; the
  // same diagnostic the constrained formulation reports.
  double violation(const VectorXd& z) {
    poses(z);
    double v = 0.0;
    for (std::size_t j = 0; j < m_.joints.size(); ++j) {
      const Joint& jt = m_.joints[j];
      jointConstraints(jt, rt_[j], P_[jt.body_i], P_[jt.body_j], 0.0, rows_);
      if (rows_.size()) v = std::max(v, rows_.phi.cwiseAbs().maxCoeff());
    }
    return v;
  }

  // What is not finite at z ("" when everything is), named as the
  // constrained formulation names it (System::nonFiniteCause).
  std::string nonFiniteCause(const VectorXd& z) {
    if (!z.allFinite()) return "the joint coordinates";
    return nonFiniteCauseAt(m_, poses(z), rt_);
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
  ConstraintRows rows_;
};

class TreeDynamics : public Dynamics {
 public:
  explicit TreeDynamics(const Model& m) : m_(m) {
    // An open tree that reaches every moving body (treeUnsupported): one link,
    // one joint coordinate, per moving body.
    for (const Body& b : m.bodies) links_ += b.fixed ? 0 : 1;
  }

  std::string formulation() const override { return "tree"; }

  // The scene's placement (treeUnsupported: it holds every joint, where the
  // constrained start would leave it) is q = 0; the rates are the scene's
  // velocities projected onto the tree's motions in the kinetic-energy
  // metric, as the constrained start projects them onto its constraints:
  // z = [q (N), qd (N), E_dissipated, W_applied].
  VectorXd start(double, std::vector<std::string>&) override {
    const std::vector<BodyPose> P0 = placedPoses(m_);
    std::vector<JointRuntime> runtimes = treeJointRuntimes(m_, P0);
    if (const std::string cause = nonFiniteCauseAt(m_, P0, runtimes); !cause.empty())
      throw NonFiniteState("non-finite state: " + cause + " is not finite at t = 0 s");
    rhs_.emplace(m_, buildKinematicTree(m_, P0), std::move(runtimes));
    const int n = rhs_->n();
    if (n != links_) throw std::logic_error("the kinematic tree has " + std::to_string(n) + " links, not one per moving body");
    VectorXd z = VectorXd::Zero(2 * n + 2);
    z.segment(n, n) = treeProjectedRates(m_, rhs_->tree(), P0);
    return z;
  }
  // Error control on angles [rad] (or slides [m]) and their rates, as the
  // constrained formulation's on positions and velocities.
  int size() const override { return 2 * links_ + 2; }
  void derivative(double, const VectorXd& z, VectorXd& zd) override { rhs_->derivative(z, zd); }
  std::string nonFiniteCause(double, const VectorXd& z) override { return rhs_ ? rhs_->nonFiniteCause(z) : ""; }

  // The row from the tree's own state: the poses and velocities z implies,
  // the joints' reactions by the RNEA at the ABA's accelerations, the
  // unwrapped joint angles, the energies.
  Sample sample(double t, const VectorXd& z) override {
    const std::vector<JointReaction> reac = rhs_->reactions(z);
    Sample s = samplePoses(m_, t, rhs_->poses(z), force_on_);
    for (std::size_t j = 0; j < m_.joints.size(); ++j) {
      s.joints[j].reaction_force = reac[j].force;
      s.joints[j].reaction_torque = reac[j].torque;
      if (m_.joints[j].type == JointType::Revolute) s.joints[j].angle = rhs_->angle(int(j), z);
    }
    s.energy = rhs_->energies(z);
    s.energy_sensitivity = rhs_->energySensitivity(z);
    s.violation = rhs_->violation(z);
    return s;
  }
  double energy(double, const VectorXd& z) override { return rhs_->energies(z).total(); }

  // The unwrapping references of the rotational springs' angles; nothing to
  // project (joint coordinates hold the joints exactly).
  bool accept(double, VectorXd& z, bool) override {
    rhs_->accept(z);
    return false;
  }

  long evaluations() const override { return rhs_ ? rhs_->evaluations : 0; }

 private:
  const Model& m_;
  std::optional<TreeRhs> rhs_;
  int links_ = 0;
  // The tree has no events: each force element is on as the scene sets it.
  std::vector<char> force_on_ = [this] {
    std::vector<char> on;
    for (const ForceElement& fe : m_.forces) on.push_back(fe.enabled);
    return on;
  }();
};

}  // namespace

std::unique_ptr<Dynamics> makeTreeDynamics(const Model& model) { return std::make_unique<TreeDynamics>(model); }

}  // namespace fc::mbs
