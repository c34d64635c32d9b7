#pragma once
// Minimal-coordinate dynamics of an open tree of rigid bodies on revolute and
// prismatic joints: one joint coordinate per moving body instead of
// the constrained path's 6 coordinates and 5 constraint rows, with
// Featherstone's Articulated-Body Algorithm (Featherstone, Rigid Body Dynamics
// Algorithms, Springer 2008, table 7.1), O(N) per evaluation.
//
// Everything is written in one frame, the ground frame, with spatial vectors
// at the world origin O (Featherstone ch. 2): a motion (omega, v_O), v_O the
// velocity of the body point at O; a force (n_O, f). For link i (the joint
// that moves body i relative to its parent p):
//   revolute   S_i = [n; x x n],  prismatic S_i = [0; n]
// with n the joint axis and x the joint point (global), both fixed in the
// parent and, for these joints, in the child, so dS_i/dt = v_i x S_i and
//   v_i = v_p + S_i qd_i,  a_i = a_p + S_i qdd_i + c_i,  c_i = v_i x S_i qd_i.
// The ABA's three passes: velocities and bias forces p_i = v_i x* I_i v_i -
// f_i (parents first); articulated inertias I^A and biases p^A (children
// first); accelerations (parents first), with gravity as the acceleration
// -g of the fixed bodies (exact for uniform gravity on rigid bodies).
// f_i: the other force elements, evaluated by force_elements.h at the poses
// the tree implies (the same functions as the constrained path, so force
// conventions cannot differ), carried from the body's velocity coordinates
// [rdot, omega'] to a spatial force at O.
//
// Joint reactions (treeReactions) by the recursive Newton-Euler backward
// pass (Featherstone ch. 5.3, table 5.1): with a_i the accelerations of the
// ABA (gravity in the base's -g), the force transmitted across joint i from
// its parent to body i is what the subtree of i needs beyond the external
// forces acting on it,
//   f_i = I_i a_i + v_i x* I_i v_i - f_i^ext + sum_{children c} f_c
// (a spatial force at O); S_i^T f_i = 0 for a free joint (its force along the
// joint's motion is the spring's or the torque's, in f^ext).
//
// Coordinates: q_i = 0 in the initial configuration (the scene's placement,
// which must hold every joint: treeUnsupported), where the tree records each
// child's orientation relative to its parent; q_i is the rotation about
// (revolute) or displacement along (prismatic) the parent's axis since then.
// The initial rates are the scene's body velocities projected onto the
// tree's motions in the kinetic-energy metric (treeProjectedRates), as the
// constrained start projects them onto its constraints.
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "mbs-run/mechanics/constraints.h"
#include "mbs-run/mechanics/kinematics.h"
#include "mbs-run/model/model.h"
#include "mbs-run/mechanics/rigid_body.h"

namespace fc::mbs {

struct TreeLink {
  int joint = -1;        // index into Model::joints
  int body = -1;         // the body this link moves (the child)
  int parent = -1;       // its parent body (Model::bodies)
  int parent_link = -1;  // the parent's link, -1 when the parent is fixed
  bool prismatic = false;
  Eigen::Vector3d s_parent, s_child;  // joint point in the parent's / child's body frame
  Eigen::Vector3d axis;               // unit, parent's body frame
  Eigen::Vector3d offset0;            // prismatic: x_child - x_parent at q = 0, parent's frame
  Eigen::Vector4d e0;                 // child's Euler parameters relative to the parent at q = 0
  // Joint angle reported for the joint: initial_angle + angle_sign q (the
  // joint measures body_j relative to body_i about axis_i; the link may run
  // the other way, about an axis_j of either sense).
  double angle_sign = 1.0;
};

struct KinematicTree {
  std::vector<TreeLink> links;    // parents before children
  std::vector<int> link_of_body;  // -1 for fixed bodies
  std::vector<BodyPose> fixed;    // poses of the fixed bodies (others unused)
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // summed enabled gravity elements
  std::vector<int> other_forces;  // enabled non-gravity force elements
  int size() const { return static_cast<int>(links.size()); }
};

// Why the scene is not an open tree of rigid bodies on free revolute and
// prismatic joints placed where its joints hold ("flexible body B", "joint J
// closes a loop", "joint J does not hold as placed ...", ...), or "" when it
// is. "Hold" is the constrained start's own test (System::assemble leaves a
// placement whose every constraint is within 1e-12 of the scene's size as
// it is, kPlacementTolerance): the tree starts where the constrained
// formulation would, and a placement that needs assembling runs constrained.
std::string treeUnsupported(const Model& m);
constexpr double kPlacementTolerance = 1e-12;

// The scene's placement: each body's pose and velocity as given (Euler
// parameters normalised), before any projection.
std::vector<BodyPose> placedPoses(const Model& m);

// The joints' run-time state in configuration P0 (System::initializeJoints
// for the tree's joints: the revolute angle offsets that make each angle its
// initial_angle there, the prismatic joints' reference vectors).
std::vector<JointRuntime> treeJointRuntimes(const Model& m, const std::vector<BodyPose>& P0);

// The tree of a qualifying scene (treeUnsupported(m) empty) from its
// consistent initial poses P0 (every joint satisfied).
KinematicTree buildKinematicTree(const Model& m, const std::vector<BodyPose>& P0);

// Joint rates of consistent poses and velocities P0 (q = 0 there).
Eigen::VectorXd treeRates(const KinematicTree& tree, const std::vector<BodyPose>& P0);

// Joint rates of the poses P0 (q = 0) whose body velocities need not be
// tree motions: the motion J qd nearest to them in the kinetic-energy metric,
// qd = (J^T M J)^-1 J^T M v0 (the constrained start's mass-orthogonal velocity
// projection, System::assemble, in joint coordinates). J^T M v0 is the joint
// space image of the bodies' momenta I_d v0_d, so qd is the rate an impulse
// of those momenta gives the tree at rest: the ABA (treeAccelerations) with
// zero velocities and gravity and the momenta as the applied forces, O(N).
Eigen::VectorXd treeProjectedRates(const Model& m, const KinematicTree& tree, const std::vector<BodyPose>& P0);

// Poses and velocities of every body at joint coordinates q and rates qd
// (P sized to the bodies; fixed bodies copied from the tree).
void treePoses(const KinematicTree& tree, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
               std::vector<BodyPose>& P);

// Scratch of treeAccelerations (sized on first use).
struct TreeWorkspace {
  std::vector<Vector6d> S, v, c, pA, U, a;
  std::vector<Matrix6d> IA;
  std::vector<double> D, u;
};

// qdd of the tree at poses P (treePoses) under the generalised forces Q on the
// bodies' velocity coordinates (Model::nv, [rdot, omega'] per free body; may be
// empty for none) and the tree's gravity. O(N).
void treeAccelerations(const Model& m, const KinematicTree& tree, const std::vector<BodyPose>& P,
                       const Eigen::VectorXd& qd, const Eigen::VectorXd& Q, TreeWorkspace& ws, Eigen::VectorXd& qdd);

// Each joint's reaction (Model::joints order) in the results' convention
// (JointReaction: on the joint's body_i, about its point on body_i, global)
// at poses P (treePoses of q, qd), joint accelerations qdd (treeAccelerations
// at the same state with the same Q) and generalised forces Q (as there):
// the RNEA backward pass above, O(N). The force transmitted to the child is
// the reaction on the child; a joint whose body_i is the parent gets its
// opposite.
std::vector<JointReaction> treeReactions(const Model& m, const KinematicTree& tree, const std::vector<BodyPose>& P,
                                         const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                         const Eigen::VectorXd& Q);

// The constrained path's state vector (system.h) of poses P, with the two
// energy quadratures (for tests and benchmarks that compare the two).
Eigen::VectorXd constrainedState(const Model& m, const std::vector<BodyPose>& P, double dissipated,
                                 double applied_work);

}  // namespace fc::mbs
