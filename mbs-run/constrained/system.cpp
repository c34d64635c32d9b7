#include "mbs-run/constrained/system.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/rotations.h"
#include "mbs-run/mechanics/energy_sensitivity.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/mechanics/flexible/modal.h"
#include "mbs-run/mechanics/force_elements.h"
#include "mbs-run/mechanics/rigid_body.h"

namespace fc::mbs {

using Eigen::Vector3d;
using Eigen::VectorXd;

System::System(const Model& model) : model_(model) {
  joints_.resize(model.joints.size());
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    joints_[j].enabled = model.joints[j].enabled;
    joints_[j].locked = model.joints[j].locked;
  }
  force_on_.resize(model.forces.size());
  for (std::size_t f = 0; f < model.forces.size(); ++f) force_on_[f] = model.forces[f].enabled;
  // Force elements with a point at a stiffened body's interface (only these are
  // looked at per evaluation: nothing is computed when stiffening is off).
  stiffened_force_.assign(model.forces.size(), 0);
  for (std::size_t f = 0; f < model.forces.size(); ++f)
    stiffened_force_[f] = stiffenedInterface(model.forces[f].body_i, model.forces[f].interface_i) ||
                          stiffenedInterface(model.forces[f].body_j, model.forces[f].interface_j);
  joint_stiffening_.resize(model.joints.size());
  for (std::size_t j = 0; j < model.joints.size(); ++j)
    joint_stiffening_[j] = {stiffenedInterface(model.joints[j].body_i, model.joints[j].interface_i),
                            stiffenedInterface(model.joints[j].body_j, model.joints[j].interface_j)};
  solver_.setMethod(model.settings.linear_solver);
  // A modal mass block diagonal to rounding (fe-prep normalises the modes
  // with the body's own lumped mass, so it is the identity to ~1e-15) makes
  // the body's mass block an arrow block, factorised in O(modes): the
  // off-diagonal entries it drops are below kDiagonalTolerance of the
  // diagonal, i.e. rounding of the same order as the solve's own.
  constexpr double kDiagonalTolerance = 1e-12;
  // Otherwise (e.g. modes orthonormal only to the eigensolver's ~1e-10) the
  // block is still an arrow block, with the constant dense modal mass
  // factorised here once (ConstantBlock) instead of the whole (6 + nm)^2
  // block at every evaluation.
  modal_mass_.resize(model.bodies.size());
  modal_block_.resize(model.bodies.size());
  for (std::size_t k = 0; k < model.bodies.size(); ++k) {
    const Body& b = model.bodies[k];
    if (b.fixed || !b.flex || b.modes == 0) continue;
    const Eigen::MatrixXd Mff = b.flex->inertia.modalMass();
    const Eigen::VectorXd d = Mff.diagonal();
    Eigen::MatrixXd off = Mff;
    off.diagonal().setZero();
    if (d.minCoeff() > 0.0 && off.cwiseAbs().maxCoeff() <= kDiagonalTolerance * d.maxCoeff()) {
      modal_mass_[k] = d;
      continue;
    }
    // Only for modes orthonormal to the eigensolver's precision (off-diagonal
    // below kNearDiagonal of the diagonal): a general coupled modal mass (a
    // test set's consistent FE data) keeps the dense block's factorisation,
    // whose start and projections its published references were matched with.
    constexpr double kNearDiagonal = 1e-6;
    if (d.minCoeff() <= 0.0 || off.cwiseAbs().maxCoeff() > kNearDiagonal * d.maxCoeff()) continue;
    auto cb = std::make_shared<const ConstantBlock>(Mff);
    if (cb->ok()) modal_block_[k] = std::move(cb);  // else the dense block, whose factorisation reports it
  }
}

VectorXd System::initialState() const {
  VectorXd y = VectorXd::Zero(size());
  for (const Body& b : model_.bodies) {
    if (b.fixed) continue;
    y.segment<3>(b.pos_index) = b.position;
    y.segment<4>(b.pos_index + 3) = b.orientation.normalized();
    const Eigen::Matrix3d A = fc::rotationMatrix(b.orientation.normalized());
    y.segment<3>(model_.nq + b.dof_index) = b.velocity;
    y.segment<3>(model_.nq + b.dof_index + 3) = A.transpose() * b.angular_velocity;
    if (b.modes > 0 && b.modal_coordinates.size() == b.modes) {
      y.segment(b.pos_index + 7, b.modes) = b.modal_coordinates;
      y.segment(model_.nq + b.dof_index + 6, b.modes) = b.modal_velocities;
    }
  }
  return y;
}

void System::poses(const VectorXd& y, std::vector<BodyPose>& out) const {
  out.resize(model_.bodies.size());
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) bodyPose(static_cast<int>(k), y, out[k]);
}

void System::bodyPose(int k, const VectorXd& y, BodyPose& P) const {
  const Body& b = model_.bodies[static_cast<std::size_t>(k)];
  if (b.fixed) {
    P.r = b.position;
    P.p = b.orientation.normalized();
    P.rdot.setZero();
    P.w.setZero();
    P.free = false;
  } else {
    P.r = y.segment<3>(b.pos_index);
    P.p = y.segment<4>(b.pos_index + 3).normalized();
    P.rdot = y.segment<3>(model_.nq + b.dof_index);
    P.w = y.segment<3>(model_.nq + b.dof_index + 3);
    P.free = true;
  }
  if (b.modes > 0 && !b.fixed) {
    P.modal = y.segment(b.pos_index + 7, b.modes);
    P.modal_rate = y.segment(model_.nq + b.dof_index + 6, b.modes);
  } else {
    P.modal.resize(0);
    P.modal_rate.resize(0);
  }
  P.A = fc::rotationMatrix(P.p);
}

void System::initializeJoints(const VectorXd& y) {
  poses(y, P_);
  for (std::size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    JointRuntime& rt = joints_[j];
    const BodyPose &bi = P_[jt.body_i], &bj = P_[jt.body_j];
    if (jt.type == JointType::Fixed) captureFixed(jt, rt, bi, bj);
    if (jt.type == JointType::Prismatic || (jt.type == JointType::Revolute && rt.locked))
      captureLock(jt, rt, bi, bj);
    if (jt.type == JointType::Revolute) {
      rt.angle_offset = jt.initial_angle - rawRevoluteAngle(jt, bi, bj);
      rt.last_angle = jt.initial_angle;
    }
  }
}

double System::penalty() const {
  double m = 0.0;
  for (const Body& b : model_.bodies)
    if (!b.fixed) m = std::max(m, std::max(b.mass, b.inertia_com.diagonal().maxCoeff()));
  // Modal masses are 1 (mass-normalised modes), within that range.
  return model_.settings.penalty * std::max(m, 1e-12);
}

void System::assembleConstraints(double t, const std::vector<BodyPose>& P) {
  int m = 0;
  row_of_joint_.assign(model_.joints.size(), 0);
  for (std::size_t j = 0; j < model_.joints.size(); ++j) {
    row_of_joint_[j] = m;
    m += constraintCount(model_.joints[j], joints_[j]);
  }
  phi_.setZero(m);
  phit_.setZero(m);
  c_.setZero(m);
  // While the active joints and their row counts are unchanged, Phi_v's
  // pattern is too: its values are written straight into the slots found
  // when the pattern was built (rebuilding it every evaluation is measurable:
  // docs/mbs-run.md, "Cost").
  long sig = m;
  for (std::size_t j = 0; j < model_.joints.size(); ++j)
    sig = sig * 31 + (joints_[j].enabled ? constraintCount(model_.joints[j], joints_[j]) + 1 : 0);
  const bool same = sig == phi_signature_ && Phi_v_.nonZeros() > 0;
  phi_signature_ = sig;
  trip_.clear();
  std::size_t slot = 0;
  double* values = Phi_v_.valuePtr();
  auto emit = [&](int r, int c, double v) {
    if (same) values[phi_slots_[slot++]] = v;
    else trip_.emplace_back(r, c, v);
  };
  joint_rows_.resize(model_.joints.size());
  for (std::size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    ConstraintRows& rows = joint_rows_[j];
    if (!joints_[j].enabled) {
      rows.resize(0, 0, 0);
      continue;
    }
    jointConstraints(jt, joints_[j], P[jt.body_i], P[jt.body_j], t, rows);
    const int r0 = row_of_joint_[j];
    phi_.segment(r0, rows.size()) = rows.phi;
    phit_.segment(r0, rows.size()) = rows.phit;
    c_.segment(r0, rows.size()) = rows.c;
    const Body &bi = model_.bodies[jt.body_i], &bj = model_.bodies[jt.body_j];
    for (int r = 0; r < rows.size(); ++r) {
      if (!bi.fixed)
        for (int k = 0; k < bi.nv(); ++k) emit(r0 + r, bi.dof_index + k, rows.Ji(r, k));
      if (!bj.fixed)
        for (int k = 0; k < bj.nv(); ++k) emit(r0 + r, bj.dof_index + k, rows.Jj(r, k));
    }
  }
  if (same) return;
  // Entries are never summed: a joint's two bodies are distinct, and each
  // (row, column) is emitted once, so every triplet has a slot of its own.
  Phi_v_.resize(m, model_.nv);
  Phi_v_.setFromTriplets(trip_.begin(), trip_.end());
  Phi_v_.makeCompressed();
  phi_slots_.resize(trip_.size());
  for (std::size_t k = 0; k < trip_.size(); ++k)
    phi_slots_[k] = &Phi_v_.coeffRef(trip_[k].row(), trip_[k].col()) - Phi_v_.valuePtr();
}

void System::assembleMass(const std::vector<BodyPose>& P) {
  Qv_.setZero(model_.nv);
  mass_.size = model_.nv;
  mass_.offset.clear();
  std::size_t nb = 0;
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) {
    const Body& b = model_.bodies[k];
    if (b.fixed) continue;
    if (mass_.block.size() <= nb) {
      mass_.block.emplace_back();
      mass_.diagonal.emplace_back();
      mass_.constant.emplace_back();
    }
    mass_.offset.push_back(b.dof_index);
    mass_.constant[nb] = b.flex ? modal_block_[k] : nullptr;
    Eigen::MatrixXd& Mb = mass_.block[nb];
    Eigen::VectorXd& Db = mass_.diagonal[nb++];
    if (b.flex && (modal_mass_[k].size() > 0 || modal_block_[k])) {
      // Floating frame of reference: the arrow block (the six rigid rows and
      // the constant modal block, diagonal or factorised once), O(modes) to
      // assemble.
      FlexibleInertiaRows fi = flexibleInertiaRows(b.flex->inertia, P[k].A, P[k].modal, P[k].modal_rate, P[k].w,
                                                   b.flex->secondOrder());
      Mb.swap(fi.top);
      Db = modal_mass_[k];
      Qv_.segment(b.dof_index, b.nv()) = fi.Qv;
    } else if (b.flex) {
      // Floating frame of reference: inertia from the body file's invariants
      // (mbs-run/mechanics/flexible, shared conventions of the flexible-body kernel).
      const FlexibleInertia fi =
          flexibleInertia(b.flex->inertia, P[k].A, P[k].modal, P[k].modal_rate, P[k].w, b.flex->secondOrder());
      Mb = fi.M;
      Db.resize(0);
      Qv_.segment(b.dof_index, b.nv()) = fi.Qv;
    } else {
      Mb = rigidMassMatrix(b.mass, b.com, b.inertia_com, P[k].A);
      Db.resize(0);
      Qv_.segment<6>(b.dof_index) = rigidQuadraticVelocity(b.mass, b.com, b.inertia_com, P[k].A, P[k].w);
    }
  }
  mass_.block.resize(nb);
  mass_.diagonal.resize(nb);
  mass_.constant.resize(nb);
}

void System::factorize() {
  solver_.factorize(mass_, Phi_v_, penalty());
  if (!solver_.ok())
    throw std::runtime_error("the augmented matrix M + a Phi^T Phi could not be factorised "
                             "(a mass matrix not positive definite, or non-finite state)");
}

void System::appliedForces(const std::vector<BodyPose>& P, ForceSums& sums) const {
  sums.Q.setZero(model_.nv);
  sums.dissipation = 0.0;
  sums.applied_power = 0.0;
  for (std::size_t f = 0; f < model_.forces.size(); ++f)
    if (force_on_[f]) addForceElement(model_, model_.forces[f], P, joints_, ForceQuantity::ForcesAndPowers, sums);
}

const std::array<Eigen::MatrixXd, 6>* System::stiffenedInterface(int body, const std::string& name) const {
  if (body < 0 || name.empty()) return nullptr;
  const Body& b = model_.bodies[static_cast<std::size_t>(body)];
  if (b.fixed || b.modes == 0 || !b.flex->stiffening) return nullptr;
  const auto it = b.flex->stiffening->interfaces.find(name);
  return it == b.flex->stiffening->interfaces.end() ? nullptr : &it->second;
}

// The stages of f(t, y), each a function below: the configuration's
// constraints and mass, factorised; the generalised forces (applied, modal,
// geometric stiffening by the state); the accelerations from the augmented
// Lagrangian; when stiffening depends on accelerations or joint loads, those
// forces from the first solve and a second solve; the state derivative.
void System::derivative(double t, const VectorXd& y, VectorXd& ydot) {
  ++stats_.evaluations;
  poses(y, P_);
  assembleConstraints(t, P_);
  assembleMass(P_);
  factorize();
  ForceSums forces;
  appliedForces(P_, forces);
  forces.Q += Qv_;
  double stiffening_power = 0.0;
  const bool acceleration_stiffening = addModalForces(forces, stiffening_power);
  addInterfaceForceStiffening(forces.Q, stiffening_power);
  bool interface_stiffening = false;
  for (std::size_t j = 0; j < model_.joints.size(); ++j)
    if (joints_[j].enabled && (joint_stiffening_[j][0] || joint_stiffening_[j][1])) interface_stiffening = true;
  const Settings& s = model_.settings;
  const VectorXd v = y.segment(model_.nq, model_.nv);
  const VectorXd phidot = Phi_v_ * v + phit_;
  const VectorXd stab = c_ + 2.0 * s.xi * s.omega * phidot + s.omega * s.omega * phi_;
  AlResult r = solver_.accelerations(forces.Q, stab, 1e-10 * (1.0 + stab.lpNorm<Eigen::Infinity>()),
                                     s.multiplier_iterations);
  if (acceleration_stiffening || interface_stiffening) {
    // Geometric stiffening by the frame's acceleration and angular acceleration
    // and by the joints' loads: taken from this first solve, then solved once
    // more with them (their change of the accelerations is of second order in w).
    stats_.al_iterations += r.iterations;
    addAccelerationStiffening(r, forces.Q, stiffening_power);
    if (interface_stiffening) addJointLoadStiffening(r, forces.Q, stiffening_power);
    r = solver_.accelerations(forces.Q, stab, 1e-10 * (1.0 + stab.lpNorm<Eigen::Infinity>()), s.multiplier_iterations);
  }
  lambda_ = r.lambda;
  stats_.al_iterations += r.iterations;
  stats_.max_al_iterations = std::max(stats_.max_al_iterations, r.iterations);
  stateDerivative(y, r.vdot, forces.dissipation, forces.applied_power, stiffening_power, ydot);
}

// Modal stiffness and damping, - (Lambda w + D wdot) on the modal rows, and
// the geometric stiffening by the frame's angular velocity (velocity cases,
// flexible/geometric_stiffening.h; its work is booked with the applied loads',
// docs/mbs-run.md). True when a body also has acceleration cases.
bool System::addModalForces(ForceSums& forces, double& stiffening_power) const {
  bool acceleration_stiffening = false;
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) {
    const Body& b = model_.bodies[k];
    if (b.fixed || b.modes == 0) continue;
    forces.Q.segment(b.dof_index + 6, b.modes) -= elasticForces(b.flex->modal, P_[k].modal, P_[k].modal_rate);
    forces.dissipation += dissipatedPower(b.flex->modal, P_[k].modal_rate);
    if (b.flex->stiffening) {
      const StiffeningParameters p = stiffeningParameters(P_[k].w, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
      const VectorXd f = stiffeningMatrix(*b.flex->stiffening, p, true, false) * P_[k].modal;
      forces.Q.segment(b.dof_index + 6, b.modes) -= f;
      stiffening_power -= P_[k].modal_rate.dot(f);
      acceleration_stiffening = acceleration_stiffening || b.flex->stiffening->acceleration_cases;
    }
  }
  return acceleration_stiffening;
}

// Force elements acting at an interface of a stiffened body (springs,
// dampers, constant forces): their force there, body axes, weights the
// interface's unit-force cases. It depends on the state only, so it goes
// into the first solve.
void System::addInterfaceForceStiffening(VectorXd& Q, double& stiffening_power) {
  interface_forces_.clear();
  for (std::size_t f = 0; f < model_.forces.size(); ++f)
    if (force_on_[f] && stiffened_force_[f]) interfaceForces(model_, model_.forces[f], P_, interface_forces_);
  for (const InterfaceForce& l : interface_forces_) {
    const std::array<Eigen::MatrixXd, 6>* K = stiffenedInterface(l.body, *l.interface);
    if (!K) continue;
    const Body& b = model_.bodies[static_cast<std::size_t>(l.body)];
    const Vector3d F = P_[l.body].A.transpose() * l.force;
    const VectorXd f = (F(0) * (*K)[0] + F(1) * (*K)[1] + F(2) * (*K)[2]) * P_[l.body].modal;
    Q.segment(b.dof_index + 6, b.modes) -= f;
    stiffening_power -= P_[l.body].modal_rate.dot(f);
  }
}

// Stiffening by the frame's acceleration (gravity taken out: a body at rest
// in gravity is not stiffened by it) and angular acceleration, from the first
// solve's accelerations.
void System::addAccelerationStiffening(const AlResult& r, VectorXd& Q, double& stiffening_power) const {
  Vector3d g = Vector3d::Zero();
  for (std::size_t f = 0; f < model_.forces.size(); ++f)
    if (force_on_[f] && model_.forces[f].type == ForceType::Gravity) g += model_.forces[f].vector;
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) {
    const Body& b = model_.bodies[k];
    if (b.fixed || b.modes == 0 || !b.flex->stiffening || !b.flex->stiffening->acceleration_cases) continue;
    const Vector3d a0 = P_[k].A.transpose() * (r.vdot.segment<3>(b.dof_index) - g);
    const StiffeningParameters p = stiffeningParameters(Vector3d::Zero(), r.vdot.segment<3>(b.dof_index + 3), a0);
    const VectorXd f = stiffeningMatrix(*b.flex->stiffening, p, false, true) * P_[k].modal;
    Q.segment(b.dof_index + 6, b.modes) -= f;
    stiffening_power -= P_[k].modal_rate.dot(f);
  }
}

// Loads applied at interfaces: the force and moment a joint exerts on the
// body at its interface point, body axes, from the first solve's multipliers
// (the generalised force -J^T lambda: global force, then the moment about the
// frame origin in body axes, s x F + M).
void System::addJointLoadStiffening(const AlResult& r, VectorXd& Q, double& stiffening_power) const {
  for (std::size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    if (!joints_[j].enabled) continue;
    for (int side = 0; side < 2; ++side) {
      const int k = side ? jt.body_j : jt.body_i;
      const std::array<Eigen::MatrixXd, 6>* K = joint_stiffening_[j][static_cast<std::size_t>(side)];
      if (!K) continue;
      const ConstraintRows& rows = joint_rows_[j];
      const VectorXd Qj = -((side ? rows.Jj : rows.Ji).transpose() * r.lambda.segment(row_of_joint_[j], rows.size()));
      const Body& b = model_.bodies[static_cast<std::size_t>(k)];
      const Vector3d F = P_[k].A.transpose() * Qj.head<3>();
      const Vector3d at = (side ? jt.point_j : jt.point_i) + (side ? jt.shapes_j.psi : jt.shapes_i.psi) * P_[k].modal;
      const Vector3d M = Qj.segment<3>(3) - at.cross(F);
      VectorXd f = VectorXd::Zero(b.modes);
      for (int c = 0; c < 3; ++c) f += (F(c) * (*K)[c] + M(c) * (*K)[3 + c]) * P_[k].modal;
      Q.segment(b.dof_index + 6, b.modes) -= f;
      stiffening_power -= P_[k].modal_rate.dot(f);
    }
  }
}

// ydot from the accelerations: position rates (Euler parameters through L^T),
// vdot, and the two energy quadratures. Work of drives: the generalised force
// of the driven rows, -Phi_v^T lambda, does work at the rate -lambda . Phi_t on
// the system (Phi_v v = -Phi_t).
void System::stateDerivative(const VectorXd& y, const VectorXd& vdot, double dissipation, double applied_power,
                             double stiffening_power, VectorXd& ydot) const {
  const int nq = model_.nq, nv = model_.nv;
  ydot.setZero(size());
  double drive_power = 0.0;
  if (lambda_.size()) drive_power = lambda_.dot(phit_);
  for (const Body& b : model_.bodies) {
    if (b.fixed) continue;
    const Eigen::Vector4d p = y.segment<4>(b.pos_index + 3);
    ydot.segment<3>(b.pos_index) = y.segment<3>(nq + b.dof_index);
    ydot.segment<4>(b.pos_index + 3) = 0.5 * fc::Lmatrix(p).transpose() * y.segment<3>(nq + b.dof_index + 3);
    if (b.modes > 0) ydot.segment(b.pos_index + 7, b.modes) = y.segment(nq + b.dof_index + 6, b.modes);
  }
  ydot.segment(nq, nv) = vdot;
  ydot[nq + nv] = dissipation;
  ydot[nq + nv + 1] = applied_power + drive_power + stiffening_power;
}

StiffModalPart System::modalSplit(double t, const VectorXd& y) {
  StiffModalPart S;
  const int nq = model_.nq, nv = model_.nv;
  S.v_offset = nq;
  // Each flexible body's first column among the split's modes, for the force elements below.
  std::vector<int> first_col(model_.bodies.size(), -1);
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) {
    const Body& b = model_.bodies[k];
    if (b.fixed || b.modes == 0) continue;
    first_col[k] = int(S.q_index.size());
    for (int j = 0; j < b.modes; ++j) {
      S.q_index.push_back(b.pos_index + 7 + j);
      S.v_index.push_back(nq + b.dof_index + 6 + j);
    }
  }
  const int n = int(S.q_index.size());
  S.stiffness.resize(n);
  S.damping.resize(n);
  S.response.resize(nv, n);
  if (n == 0) return S;
  poses(y, P_);
  assembleConstraints(t, P_);
  assembleMass(P_);
  factorize();
  int col = 0;
  const VectorXd no_stabilisation = VectorXd::Zero(phi_.size());
  VectorXd Q = VectorXd::Zero(nv);
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) {
    const Body& b = model_.bodies[k];
    if (b.fixed || b.modes == 0) continue;
    const ModalProperties& mp = b.flex->modal;
    for (int j = 0; j < b.modes; ++j, ++col) {
      S.stiffness[col] = mp.stiffness[j];
      S.damping[col] = mp.damping[j];
      Q[b.dof_index + 6 + j] = 1.0;
      S.response.col(col) = solver_.accelerations(Q, no_stabilisation, 1e-12, model_.settings.multiplier_iterations).vdot;
      Q[b.dof_index + 6 + j] = 0.0;
    }
  }
  addForceElementSplit(first_col, S);
  return S;
}

// The linear force elements that act through modal coordinates
// (linearForce: -(k s + c s_dot) g along their coordinate s), each with the
// accelerations its unit force g causes: a damper at a flexible interface
// damps the body's modes as hard as their own stiffness is stiff (the SAR's
// 50 N m s at the crank's root against ~1 kHz modes), and left in the
// explicit part it holds the step at its stability bound. Elements without
// modal entries (between rigid frames) stay explicit as before.
void System::addForceElementSplit(const std::vector<int>& first_col, StiffModalPart& S) {
  const int n = S.modes(), nv = model_.nv;
  std::vector<VectorXd> g, gq;
  std::vector<double> c, kk;
  for (std::size_t f = 0; f < model_.forces.size(); ++f) {
    if (!force_on_[f]) continue;
    const ForceElement& fe = model_.forces[f];
    LinearForce lf;
    if (!linearForce(model_, fe, P_, joints_, lf) || (lf.stiffness == 0.0 && lf.damping == 0.0)) continue;
    const bool rotational = fe.type == ForceType::RotationalSpringDamper;
    const int bodies[2] = {rotational ? model_.joints[fe.joint].body_i : fe.body_i,
                           rotational ? model_.joints[fe.joint].body_j : fe.body_j};
    VectorXd ge = VectorXd::Zero(nv), gqe = VectorXd::Zero(n);
    for (int side = 0; side < 2; ++side) {
      const Body& b = model_.bodies[std::size_t(bodies[side])];
      if (b.fixed) continue;
      const Eigen::RowVectorXd& grad = side ? lf.grad_j : lf.grad_i;
      ge.segment(b.dof_index, b.nv()) += grad.transpose();
      if (first_col[std::size_t(bodies[side])] >= 0)
        gqe.segment(first_col[std::size_t(bodies[side])], b.modes) += grad.tail(b.modes).transpose();
    }
    if (gqe.squaredNorm() == 0.0) continue;
    g.push_back(ge);
    gq.push_back(gqe);
    c.push_back(lf.damping);
    kk.push_back(lf.stiffness);
  }
  const int ne = int(g.size());
  S.element_gradient.resize(nv, ne);
  S.element_modal_gradient.resize(n, ne);
  S.element_response.resize(nv, ne);
  S.element_damping.resize(ne);
  S.element_stiffness.resize(ne);
  const VectorXd no_stabilisation = VectorXd::Zero(phi_.size());
  for (int e = 0; e < ne; ++e) {
    S.element_gradient.col(e) = g[std::size_t(e)];
    S.element_modal_gradient.col(e) = gq[std::size_t(e)];
    S.element_damping[e] = c[std::size_t(e)];
    S.element_stiffness[e] = kk[std::size_t(e)];
    S.element_response.col(e) =
        solver_.accelerations(g[std::size_t(e)], no_stabilisation, 1e-12, model_.settings.multiplier_iterations).vdot;
  }
}

double System::constraintViolation(double t, const VectorXd& y) { return violations(t, y).position; }

System::Violations System::violations(double t, const VectorXd& y) {
  poses(y, P_);
  assembleConstraints(t, P_);
  Violations v;
  if (phi_.size() == 0) return v;
  Eigen::Index row = 0;
  v.position = phi_.cwiseAbs().maxCoeff(&row);
  v.velocity = (Phi_v_ * y.segment(model_.nq, model_.nv) + phit_).cwiseAbs().maxCoeff();
  for (std::size_t j = 0; j < model_.joints.size(); ++j)
    if (joints_[j].enabled && row_of_joint_[j] <= row) v.worst_joint = static_cast<int>(j);
  return v;
}

std::string System::nonFiniteCause(double t, const VectorXd& y) {
  auto finite = [](const auto& m) { return m.allFinite(); };
  for (const Body& b : model_.bodies) {
    if (b.fixed) continue;
    if (!finite(y.segment(b.pos_index, b.nq())) || !finite(y.segment(model_.nq + b.dof_index, b.nv())))
      return "the state of body " + b.name;
  }
  poses(y, P_);
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) {
    const Body& b = model_.bodies[k];
    if (b.fixed) continue;
    const BodyPose& P = P_[k];
    if (b.flex) {
      const FlexibleInertia fi = flexibleInertia(b.flex->inertia, P.A, P.modal, P.modal_rate, P.w, b.flex->secondOrder());
      if (!finite(fi.M) || !finite(fi.Qv)) return "the inertia of flexible body " + b.name + " (its body file)";
      if (b.modes > 0 && !finite(elasticForces(b.flex->modal, P.modal, P.modal_rate)))
        return "the modal stiffness of flexible body " + b.name + " (its body file)";
    } else if (!std::isfinite(b.mass) || !finite(b.com) || !finite(b.inertia_com) ||
               !finite(rigidMassMatrix(b.mass, b.com, b.inertia_com, P.A)) ||
               !finite(rigidQuadraticVelocity(b.mass, b.com, b.inertia_com, P.A, P.w))) {
      return "the mass or inertia of body " + b.name;
    }
  }
  for (std::size_t f = 0; f < model_.forces.size(); ++f) {
    if (!force_on_[f]) continue;
    ForceSums sums;
    sums.Q.setZero(model_.nv);
    addForceElement(model_, model_.forces[f], P_, joints_, ForceQuantity::ForcesAndPowers, sums);
    if (!finite(sums.Q) || !std::isfinite(sums.dissipation) || !std::isfinite(sums.applied_power))
      return "force element " + forceElementLabel(model_, static_cast<int>(f));
  }
  ConstraintRows rows;
  for (std::size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    if (!joints_[j].enabled) continue;
    jointConstraints(jt, joints_[j], P_[jt.body_i], P_[jt.body_j], t, rows);
    if (!finite(rows.Ji) || !finite(rows.Jj) || !finite(rows.phi) || !finite(rows.phit) || !finite(rows.c))
      return "joint " + jt.name;
  }
  return "";
}

double System::project(double t, VectorXd& y, bool hold_modes) {
  // Drift: the frames first, the modal coordinates held; all coordinates
  // only for what is left (a loop closed through a body's deflection). In
  // M's metric the correction also moves the modal coordinates, by O(drift)
  // through the frame-mode coupling: a move dq_k of a mode at omega_k sets it
  // ringing at omega_k dq_k, 1e3-1e4 tolerance units of a 14 kHz mode's rate
  // for a 1e-8 correction, which the error control then resolves
  // (docs/mbs-run.md, "Projections and stiff modes").
  // The velocities end with the full projection whatever the frames left:
  // rows only the modal rates can close (a weld or a drive on a deflection)
  // are then met to the solver's precision, and a pass over rates already
  // tangent moves the modes by rounding only, which rings no mode
  // (docs/mbs-run.md, "Projections and stiff modes").
  if (hold_modes) correctPositions(t, y, true, false, 10);
  const double viol = correctPositions(t, y, false, false, 10).violation;
  if (hold_modes) correctVelocities(t, y, true);
  correctVelocities(t, y, false);
  return viol;
}

System::Assembly System::assemble(double t, VectorXd& y) {
  const Assembly frames = correctPositions(t, y, true, true, kAssemblyPasses);
  Assembly all = correctPositions(t, y, false, true, kAssemblyPasses);
  correctVelocities(t, y, true);
  // Velocities the frames made tangent (to the projection's own tolerance)
  // stay: projecting them again would move the modal rates by rounding.
  const VectorXd v = y.segment(model_.nq, model_.nv);
  if (violations(t, y).velocity > 1e-13 * (1.0 + v.lpNorm<Eigen::Infinity>())) correctVelocities(t, y, false);
  all.passes += frames.passes;
  return all;
}

void System::applyIncrement(const VectorXd& dq, VectorXd& y) const {
  for (const Body& b : model_.bodies) {
    if (b.fixed) continue;
    y.segment<3>(b.pos_index) += dq.segment<3>(b.dof_index);
    // Rotation increments are in body axes: A_new = A exp(dtheta~).
    const Vector3d dth = dq.segment<3>(b.dof_index + 3);
    const double ang = dth.norm();
    Eigen::Vector4d dp(1, 0, 0, 0);
    if (ang > 0) dp = fc::eulerParametersFromAxisAngle(dth / ang, ang);
    y.segment<4>(b.pos_index + 3) = fc::quatProduct(y.segment<4>(b.pos_index + 3), dp).normalized();
    if (b.modes > 0) y.segment(b.pos_index + 7, b.modes) += dq.segment(b.dof_index + 6, b.modes);
  }
}

void System::holdModes() {
  std::size_t nb = 0;
  for (const Body& b : model_.bodies) {
    if (b.fixed) continue;
    Eigen::MatrixXd& Mb = mass_.block[nb++];
    if (b.modes == 0) continue;
    for (int c = b.dof_index + 6; c < b.dof_index + 6 + b.modes; ++c)
      for (SparseMatrixd::InnerIterator it(Phi_v_, c); it; ++it) it.valueRef() = 0.0;
    Mb.rightCols(b.modes).topRows(6).setZero();                // arrow block: its 6 rows only
    if (Mb.rows() > 6) Mb.bottomLeftCorner(b.modes, 6).setZero();  // dense block
  }
}

System::Assembly System::correctPositions(double t, VectorXd& y, bool frames_only, bool damped, int max_passes) {
  double scale = 1.0;
  for (const Body& b : model_.bodies) scale = std::max(scale, b.position.norm());
  const double tol = 1e-12 * scale;
  VectorXd accumulated = VectorXd::Zero(model_.nv);
  Assembly out;
  for (; out.passes < max_passes; ++out.passes) {
    poses(y, P_);
    assembleConstraints(t, P_);
    const double viol = phi_.size() ? phi_.cwiseAbs().maxCoeff() : 0.0;
    if (viol <= tol) break;
    assembleMass(P_);
    if (frames_only) holdModes();
    factorize();
    // The drift's projection returns to the nearest configuration of the
    // manifold in M's metric (the correction accumulated over the passes);
    // the assembly takes each pass's shortest step instead (Gauss-Newton,
    // quadratic): sliding back along a curved manifold toward a start far
    // from it converges only linearly (docs/mbs-run.md, "Consistent start").
    const VectorXd dq = solver_.positionCorrection(phi_, accumulated, 1e-3 * tol, 20);
    if (!damped) {
      accumulated += dq;
      applyIncrement(dq, y);
      continue;
    }
    // Backtracking on |Phi|_2 (Armijo's rule with c = 1e-4): the Newton step
    // of a gap of the body's size turns the body by a large linearised angle
    // and can land farther than it started.
    const double merit = phi_.norm();
    bool shortened = false;
    double s = 1.0;
    for (int k = 0; k < 30 && !shortened; ++k, s *= 0.5) {
      VectorXd trial = y;
      applyIncrement(s * dq, trial);
      poses(trial, P_);
      assembleConstraints(t, P_);
      if (phi_.norm() < (1.0 - 1e-4 * s) * merit) {
        y = trial;
        shortened = true;
      }
    }
    if (!shortened) {
      out.stalled = true;
      break;
    }
  }
  for (const Body& b : model_.bodies)
    if (!b.fixed) y.segment<4>(b.pos_index + 3).normalize();
  poses(y, P_);
  assembleConstraints(t, P_);
  out.violation = phi_.size() ? phi_.cwiseAbs().maxCoeff() : 0.0;
  return out;
}

void System::correctVelocities(double t, VectorXd& y, bool frames_only) {
  const int nq = model_.nq, nv = model_.nv;
  poses(y, P_);
  assembleConstraints(t, P_);
  if (phi_.size() == 0) return;
  assembleMass(P_);
  const VectorXd v0 = y.segment(nq, nv);
  VectorXd phit = phit_;
  if (frames_only) {
    // The held modal rates' share of the velocity constraints moves into
    // Phi_t before their columns leave Phi_v.
    VectorXd modal_rates = VectorXd::Zero(nv);
    for (const Body& b : model_.bodies)
      if (!b.fixed && b.modes > 0) modal_rates.segment(b.dof_index + 6, b.modes) = v0.segment(b.dof_index + 6, b.modes);
    phit += Phi_v_ * modal_rates;
    holdModes();
  }
  factorize();
  VectorXd v = solver_.projectVelocities(v0, phit, 1e-13 * (1.0 + v0.lpNorm<Eigen::Infinity>()), 20);
  if (frames_only)
    for (const Body& b : model_.bodies)
      if (!b.fixed && b.modes > 0) v.segment(b.dof_index + 6, b.modes) = v0.segment(b.dof_index + 6, b.modes);
  y.segment(nq, nv) = v;
}

VectorXd System::jointPointGap(int j, double t, const VectorXd& y) {
  const Joint& jt = model_.joints[j];
  const bool points = jt.type == JointType::Spherical || jt.type == JointType::Universal ||
                      (jt.type == JointType::Revolute && !jt.stop_only);
  if (!points) return VectorXd();
  poses(y, P_);
  ConstraintRows rows;
  JointRuntime rt = joints_[j];
  rt.enabled = true;
  jointConstraints(jt, rt, P_[jt.body_i], P_[jt.body_j], t, rows);
  return rows.phi.head(3);
}

Energies System::energies(double t, const VectorXd& y) const {
  std::vector<BodyPose> P;
  poses(y, P);
  Energies e;
  for (std::size_t k = 0; k < model_.bodies.size(); ++k) {
    const Body& b = model_.bodies[k];
    if (b.fixed) continue;
    if (b.flex) {
      Eigen::VectorXd v(b.nv());
      v << P[k].rdot, P[k].w, P[k].modal_rate;
      e.kinetic += kineticEnergy(b.flex->inertia, P[k].A, P[k].modal, v, b.flex->secondOrder());
      e.strain += strainEnergy(b.flex->modal, P[k].modal);
    } else {
      e.kinetic += rigidKineticEnergy(b.mass, b.com, b.inertia_com, P[k].A, P[k].rdot, P[k].w);
    }
  }
  ForceSums sums;
  for (std::size_t f = 0; f < model_.forces.size(); ++f)
    if (force_on_[f]) addForceElement(model_, model_.forces[f], P, joints_, ForceQuantity::Potential, sums);
  e.potential = sums.potential;
  e.dissipated = y[model_.nq + model_.nv];
  e.applied_work = y[model_.nq + model_.nv + 1];
  return e;
}

EnergySensitivity System::energySensitivity(double t, const VectorXd& y) const {
  (void)t;
  std::vector<BodyPose> P;
  poses(y, P);
  ForceSums sums;
  appliedForces(P, sums);
  return fc::mbs::energySensitivity(model_, P, sums.Q, y[model_.nq + model_.nv], y[model_.nq + model_.nv + 1]);
}

std::vector<JointReaction> System::reactions(double t, const VectorXd& y) {
  VectorXd ydot;
  derivative(t, y, ydot);  // leaves the multipliers of this state in lambda_
  std::vector<JointReaction> out(model_.joints.size());
  ConstraintRows rows;
  for (std::size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    if (!joints_[j].enabled) continue;
    jointConstraints(jt, joints_[j], P_[jt.body_i], P_[jt.body_j], t, rows);
    // Generalised constraint force on body i: -Ji^T lambda over its velocity
    // coordinates [rdot, omega', wdot]. Its first three entries are the global
    // force F; the next three, the moment about the body frame origin in body
    // axes (the virtual work of a frame rotation). The torque the joint
    // transmits is that moment taken about the joint's point on body i:
    // n = A n_O' - (x_P - r) x F.
    const VectorXd lam = lambda_.segment(row_of_joint_[j], rows.size());
    const VectorXd Q = -(rows.Ji.transpose() * lam);
    const BodyPose& bi = P_[jt.body_i];
    out[j].force = Q.head<3>();
    const Vector3d lever = attachedPoint(bi, jt.point_i, jt.shapes_i.psi).x - bi.r;
    out[j].torque = bi.A * Q.segment<3>(3) - lever.cross(out[j].force);
  }
  return out;
}

double System::jointAngle(int j, const VectorXd& y) const {
  // The joint's two bodies only: the stop and event scans call this per
  // joint and per scan point, and all the poses would make that O(N^2).
  const Joint& jt = model_.joints[j];
  BodyPose bi, bj;
  bodyPose(jt.body_i, y, bi);
  bodyPose(jt.body_j, y, bj);
  return revoluteAngle(jt, joints_[j], bi, bj);
}

void System::updateAngleReferences(const VectorXd& y) {
  poses(y, P_);
  for (std::size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    if (jt.type != JointType::Revolute) continue;
    joints_[j].last_angle = revoluteAngle(jt, joints_[j], P_[jt.body_i], P_[jt.body_j]);
  }
}

void System::setJointEnabled(int j, bool on, const VectorXd& y) {
  JointRuntime& rt = joints_[j];
  if (on && !rt.enabled) {
    poses(y, P_);
    const Joint& jt = model_.joints[j];
    if (jt.type == JointType::Fixed) captureFixed(jt, rt, P_[jt.body_i], P_[jt.body_j]);
    if (jt.type == JointType::Prismatic || (jt.type == JointType::Revolute && rt.locked))
      captureLock(jt, rt, P_[jt.body_i], P_[jt.body_j]);
  }
  rt.enabled = on;
}

void System::setJointLocked(int j, bool on, const VectorXd& y) {
  JointRuntime& rt = joints_[j];
  if (on && !rt.locked) {
    poses(y, P_);
    const Joint& jt = model_.joints[j];
    captureLock(jt, rt, P_[jt.body_i], P_[jt.body_j]);
  }
  rt.locked = on;
  rt.contact = 0;  // a lock holds the angle itself; a release leaves the joint free
}

void System::setLimitContact(int j, int side, const VectorXd& y) {
  JointRuntime& rt = joints_[j];
  if (side != 0 && !rt.locked) {
    poses(y, P_);
    const Joint& jt = model_.joints[j];
    captureLock(jt, rt, P_[jt.body_i], P_[jt.body_j]);
  }
  rt.contact = side;
}

double System::holdingTorque(int j) const {
  const Joint& jt = model_.joints[j];
  const JointRuntime& rt = joints_[j];
  if (jt.type != JointType::Revolute || !rt.enabled || !(rt.locked || rt.contact != 0 || jt.drive.active)) return 0.0;
  const int row = row_of_joint_[j] + (jt.stop_only ? 0 : 5);
  if (row >= lambda_.size()) return 0.0;
  // The row is sin(angle - held angle) (captureLock), whose gradient is the
  // angle's at the held angle, up to terms in the other rows of the joint;
  // its generalised force is -Phi_row^T lambda, so the torque about the
  // angle is -lambda.
  return -lambda_[row];
}

void System::assembleAt(double t, const VectorXd& y) {
  poses(y, P_);
  assembleConstraints(t, P_);
  assembleMass(P_);
}

}  // namespace fc::mbs
