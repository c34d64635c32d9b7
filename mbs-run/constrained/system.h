#pragma once
// The evolving side of a simulation (the "Data" of the Model/Data split): the
// run-time state of joints and force elements, the assembled matrices, and the
// kernels that turn a state vector into its time derivative, project it onto
// the constraints, and report energies and reactions.
//
// State vector y = [q (7 per free body: r, p), v (6 per free body: rdot,
// omega'), E_dissipated, W_applied]; the last two are quadratures of the power
// of dampers and of non-conservative applied loads (constant torques, drives),
// so that the energy balance T + V + E_dissipated - W_applied = const can be
// checked.
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mbs-run/constrained/augmented_lagrangian.h"
#include "mbs-run/mechanics/constraints.h"
#include "mbs-run/mechanics/energy_sensitivity.h"
#include "mbs-run/integrators/integrator.h"
#include "mbs-run/mechanics/force_elements.h"
#include "mbs-run/model/model.h"

namespace fc::mbs {

struct Energies {
  double kinetic = 0, potential = 0, strain = 0, dissipated = 0, applied_work = 0;
  double total() const { return kinetic + potential + strain + dissipated - applied_work; }
};

struct EvalStats {
  long evaluations = 0;
  long al_iterations = 0;
  int max_al_iterations = 0;
};

class System {
 public:
  explicit System(const Model& model);

  const Model& model() const { return model_; }
  int size() const { return model_.nq + model_.nv + 2; }
  // Initial state from the bodies' initial poses and velocities (not projected).
  Eigen::VectorXd initialState() const;
  // Captures fixed joints and locks, and sets the revolute angle offsets, in the
  // configuration y. Call once at t = 0, after projecting.
  void initializeJoints(const Eigen::VectorXd& y);

  void poses(const Eigen::VectorXd& y, std::vector<BodyPose>& out) const;
  // Body k's pose alone (as poses gives it).
  void bodyPose(int k, const Eigen::VectorXd& y, BodyPose& out) const;
  // ydot = f(t, y).
  void derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot);
  // Mass-orthogonal projection of positions then velocities; normalises the
  // Euler parameters. Returns the largest position violation after projecting.
  // For the drift of a step or the jump of an event (small): ten Newton
  // passes with full steps. hold_modes (the drift of a step): the frames
  // first with the modal coordinates and rates held, all coordinates only for
  // what is left; the default, M's metric on all, is an event's plastic
  // impact, whose impulse excites the modes as the real one does.
  double project(double t, Eigen::VectorXd& y, bool hold_modes = false);

  // The consistent start's projection, for a scene that may be placed far
  // from assembled (docs/mbs-run.md, "Consistent start"): first the bodies'
  // frames alone (modal coordinates and rates held at their given values),
  // then every coordinate for what the frames cannot close (joints that
  // need a deformation); each pass's step is halved until it shortens
  // |Phi|_2, so that a gap of the body's size converges instead of
  // overshooting. A gap the frames close leaves the modes as given.
  struct Assembly {
    double violation = 0.0;  // largest |Phi| after it
    // Stopped where no step along the correction shortens |Phi|: a
    // least-squares point of the joints (they pull against each other), not
    // the pass limit.
    bool stalled = false;
    int passes = 0;
  };
  Assembly assemble(double t, Eigen::VectorXd& y);
  // Passes of each of assemble()'s two stages at most.
  static constexpr int kAssemblyPasses = 50;
  // How far joint j is from holding at (t, y): the global vector from its
  // point on body i to its point on body j for the joints that make them
  // coincide (spherical, universal, revolute, except a revolute's stop-only
  // row); empty otherwise.
  Eigen::VectorXd jointPointGap(int j, double t, const Eigen::VectorXd& y);
  // Largest |Phi| over the active constraints.
  double constraintViolation(double t, const Eigen::VectorXd& y);
  // Largest |Phi| and largest |Phi_v v + Phi_t| (velocity level).
  struct Violations {
    double position = 0.0, velocity = 0.0;
    int worst_joint = -1;  // the joint of the largest position violation
  };
  Violations violations(double t, const Eigen::VectorXd& y);

  // What makes f(t, y) non-finite: "the state of body B", "the mass or
  // inertia of body B", "force element F", "joint J"...; "" when every
  // ingredient is finite (then the constraint solve itself failed).
  std::string nonFiniteCause(double t, const Eigen::VectorXd& y);

  Energies energies(double t, const Eigen::VectorXd& y) const;
  EnergySensitivity energySensitivity(double t, const Eigen::VectorXd& y) const;
  // Reaction force and torque (about the joint's point) on the first body of
  // each joint, global, from the multipliers; zero if disabled.
  std::vector<JointReaction> reactions(double t, const Eigen::VectorXd& y);
  // Unwrapped angle of revolute joint j in configuration y.
  double jointAngle(int j, const Eigen::VectorXd& y) const;
  // Records the current revolute angles as the unwrapping references
  // (after every accepted step, so unwrapping never skips a turn).
  void updateAngleReferences(const Eigen::VectorXd& y);

  // Event actions; each keeps the state consistent (captures poses as needed).
  void setJointEnabled(int j, bool on, const Eigen::VectorXd& y);
  void setJointLocked(int j, bool on, const Eigen::VectorXd& y);
  void setForceEnabled(int f, bool on) { force_on_[f] = on; }
  bool forceEnabled(int f) const { return force_on_[f]; }
  const JointRuntime& jointRuntime(int j) const { return joints_[j]; }

  // Stops (mbs-run/run/joint_limits.h). Rest on a stop (side -1 min, +1 max:
  // the angle is held where it is by the lock row) or leave it (side 0).
  void setLimitContact(int j, int side, const Eigen::VectorXd& y);
  // The torque the held angle row of a locked or resting revolute joint
  // applies about its axis (positive: it drives the angle up), from the
  // multipliers of the last derivative() or reactions() call.
  double holdingTorque(int j) const;
  // Assembles the mass matrix and the constraint Jacobian at (t, y), for the
  // impulse solves of impacts.
  void assembleAt(double t, const Eigen::VectorXd& y);
  const BlockDiagonal& massMatrix() const { return mass_; }
  const SparseMatrixd& constraintJacobian() const { return Phi_v_; }
  const Eigen::VectorXd& constraintTimeDerivative() const { return phit_; }

  const EvalStats& stats() const { return stats_; }

  // The stiff linear part of f (for the IMEX integrator, integrator.h): the
  // modal stiffness and damping forces -(Lambda w + D wdot) of every flexible
  // body, carried to the accelerations by the constrained inverse mass at y
  // (response: the accelerations a unit generalised force on each modal row
  // causes, with the joints' constraint forces).
  StiffModalPart modalSplit(double t, const Eigen::VectorXd& y);

 private:
  // Assembles Phi_v (sparse), Phi, Phi_t, c for the active joints at (t, poses).
  void assembleConstraints(double t, const std::vector<BodyPose>& P);
  void assembleMass(const std::vector<BodyPose>& P);
  // Generalised forces of the enabled force elements (without the
  // quadratic-velocity terms) and the powers of dampers and non-conservative
  // loads (force_elements.h).
  void appliedForces(const std::vector<BodyPose>& P, ForceSums& sums) const;
  // The stages of derivative() (system.cpp), on the poses P_.
  bool addModalForces(ForceSums& forces, double& stiffening_power) const;
  void addInterfaceForceStiffening(Eigen::VectorXd& Q, double& stiffening_power);
  void addAccelerationStiffening(const AlResult& r, Eigen::VectorXd& Q, double& stiffening_power) const;
  void addJointLoadStiffening(const AlResult& r, Eigen::VectorXd& Q, double& stiffening_power) const;
  void stateDerivative(const Eigen::VectorXd& y, const Eigen::VectorXd& vdot, double dissipation,
                       double applied_power, double stiffening_power, Eigen::VectorXd& ydot) const;
  void factorize();
  // modalSplit's force elements (StiffModalPart::element_*), at the poses
  // P_ with the mass and constraints factorised; first_col: each flexible
  // body's first column among S's modes (-1 for the others).
  void addForceElementSplit(const std::vector<int>& first_col, StiffModalPart& S);
  double penalty() const;
  // Newton passes on the positions (project(), assemble()): frames_only
  // holds the modal coordinates; damped (the assembly's) takes each pass's
  // shortest step, halved until it shortens |Phi|_2, where the drift's
  // passes return toward the start. Leaves the Euler parameters normalised.
  Assembly correctPositions(double t, Eigen::VectorXd& y, bool frames_only, bool damped, int max_passes);
  // Mass-orthogonal velocity projection; frames_only holds the modal rates.
  void correctVelocities(double t, Eigen::VectorXd& y, bool frames_only);
  // Takes the modal coordinates out of the assembled Phi_v (their columns
  // zeroed) and M (the frame-mode coupling zeroed), so that a correction
  // moves the frames only and is mass-orthogonal in the frames' own metric.
  void holdModes();
  // y advanced by the velocity-space increment dq (rotations in body axes).
  void applyIncrement(const Eigen::VectorXd& dq, Eigen::VectorXd& y) const;
  // The unit-load cases of interface `name` of a stiffened flexible body
  // (flexible/geometric_stiffening.h), or null when that point does not stiffen.
  const std::array<Eigen::MatrixXd, 6>* stiffenedInterface(int body, const std::string& name) const;

  const Model& model_;
  std::vector<JointRuntime> joints_;
  std::vector<char> force_on_;
  std::vector<char> stiffened_force_;              // acts at a stiffened body's interface
  std::vector<InterfaceForce> interface_forces_;   // scratch of derivative()
  // Per joint, its two sides' stiffenedInterface (constant: resolved once).
  std::vector<std::array<const std::array<Eigen::MatrixXd, 6>*, 2>> joint_stiffening_;
  std::vector<int> row_of_joint_;
  // Workspace.
  std::vector<BodyPose> P_;
  BlockDiagonal mass_;  // one block per free body (an arrow block for a flexible body, see modal_mass_)
  // Per body: the diagonal of its constant modal mass block when that block is
  // diagonal (mass-normalised modes), else empty (the body's block is dense).
  std::vector<Eigen::VectorXd> modal_mass_;
  // Per body: its constant modal mass block factorised once when that block
  // is not diagonal to rounding, else null.
  std::vector<std::shared_ptr<const ConstantBlock>> modal_block_;
  SparseMatrixd Phi_v_;
  std::vector<ConstraintRows> joint_rows_;  // rows of each joint, from the last assembly
  Eigen::VectorXd phi_, phit_, c_, lambda_, Qv_;
  std::vector<Eigen::Triplet<double>> trip_;
  long phi_signature_ = -1;
  std::vector<Eigen::Index> phi_slots_;  // value index in Phi_v_ of each emitted entry
  AlSolver solver_;
  EvalStats stats_;
};

}  // namespace fc::mbs
