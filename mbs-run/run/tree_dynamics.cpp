#include "mbs-run/run/tree_dynamics.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "mbs-run/constrained/consistent_start.h"
#include "mbs-run/constrained/system.h"
#include "mbs-run/tree/kinematic_tree.h"

namespace fc::mbs {

using Eigen::VectorXd;

std::string treeFormulationDeclined(const Model& model) {
  if (model.settings.formulation == Formulation::Constrained) return "formulation: constrained";
  return treeUnsupported(model);
}

namespace {

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

class TreeDynamics : public Dynamics {
 public:
  explicit TreeDynamics(const Model& m) : m_(m), sys_(m) {
    // An open tree that reaches every moving body (treeUnsupported): one link,
    // one joint coordinate, per moving body.
    for (const Body& b : m.bodies) links_ += b.fixed ? 0 : 1;
  }

  std::string formulation() const override { return "tree"; }

  // The constrained formulation's consistent start, then the tree's
  // coordinates there: z = [q (N), qd (N), E_dissipated, W_applied].
  VectorXd start(double atol, std::vector<std::string>&) override {
    const VectorXd y = consistentStart(sys_, atol);
    std::vector<BodyPose> P0;
    sys_.poses(y, P0);
    std::vector<JointRuntime> runtimes;
    for (std::size_t j = 0; j < m_.joints.size(); ++j) runtimes.push_back(sys_.jointRuntime(int(j)));
    rhs_.emplace(m_, buildKinematicTree(m_, P0), runtimes);
    const int n = rhs_->n();
    if (n != links_) throw std::logic_error("the kinematic tree has " + std::to_string(n) + " links, not one per moving body");
    VectorXd z = VectorXd::Zero(2 * n + 2);
    z.segment(n, n) = treeRates(rhs_->tree(), P0);
    return z;
  }
  // Error control on angles [rad] (or slides [m]) and their rates, as the
  // constrained formulation's on positions and velocities.
  int size() const override { return 2 * links_ + 2; }
  void derivative(double, const VectorXd& z, VectorXd& zd) override { rhs_->derivative(z, zd); }

  // The constrained sampling of the Cartesian state z implies (reactions from
  // its constraint solve there), with the tree's own energies and unwrapped
  // joint angles.
  Sample sample(double t, const VectorXd& z) override {
    const int n = rhs_->n();
    const Energies e = rhs_->energies(z);
    Sample s = takeSample(sys_, t, constrainedState(m_, rhs_->poses(z), z[2 * n], z[2 * n + 1]));
    s.energy = e;
    for (std::size_t j = 0; j < m_.joints.size(); ++j)
      if (m_.joints[j].type == JointType::Revolute) s.joints[j].angle = rhs_->angle(int(j), z);
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
  System sys_;  // the consistent start and the output rows' reactions
  std::optional<TreeRhs> rhs_;
  int links_ = 0;
};

}  // namespace

std::unique_ptr<Dynamics> makeTreeDynamics(const Model& model) { return std::make_unique<TreeDynamics>(model); }

}  // namespace fc::mbs
