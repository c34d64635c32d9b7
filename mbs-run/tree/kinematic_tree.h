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
// Coordinates: q_i = 0 in the consistent initial configuration (the one the
// constrained path projects the scene's poses onto), where the tree records
// each child's orientation relative to its parent; q_i is the rotation about
// (revolute) or displacement along (prismatic) the parent's axis since then.
#include <Eigen/Dense>

#include <string>
#include <vector>

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
// prismatic joints ("flexible body B", "joint J closes a loop", ...), or ""
// when it is.
std::string treeUnsupported(const Model& m);

// The tree of a qualifying scene (treeUnsupported(m) empty) from its
// consistent initial poses P0 (every joint satisfied).
KinematicTree buildKinematicTree(const Model& m, const std::vector<BodyPose>& P0);

// Joint rates of consistent poses and velocities P0 (q = 0 there).
Eigen::VectorXd treeRates(const KinematicTree& tree, const std::vector<BodyPose>& P0);

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

// The constrained path's state vector (system.h) of poses P, with the two
// energy quadratures: for the sampling and reaction kernels.
Eigen::VectorXd constrainedState(const Model& m, const std::vector<BodyPose>& P, double dissipated,
                                 double applied_work);

}  // namespace fc::mbs
