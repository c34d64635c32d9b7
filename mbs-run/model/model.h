#pragma once
// The constant description of a multibody scene (Pinocchio's Model/Data split):
// bodies, joints, force elements, events and run settings, as parsed from the
// scene. Nothing here changes while integrating: the evolving state is the
// integrators' vector y (constrained/system.h, tree/kinematic_tree.h) and the
// run-time switches of the joints in JointRuntime (mechanics/constraints.h),
// those of the forces in System. It includes nothing of the engine: the
// layers above read it (docs/architecture.md).
#include <Eigen/Dense>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mbs-run/model/al_method.h"

namespace fc::mbs {

struct BodyGeometry;  // mbs-run/monitors/distance.h
struct FlexibleBodyData;  // mbs-run/mechanics/flexible/flexible_body.h
struct BodyStressRecovery;  // mbs-run/monitors/stress_recovery.h
struct BoundingTree;  // mbs-run/monitors/bounding_volume_tree.h

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::Vector4d;
using Eigen::VectorXd;

struct Body {
  std::string name;
  double mass = 1.0;
  Vector3d com = Vector3d::Zero();         // centre of mass, body frame
  Matrix3d inertia_com = Matrix3d::Identity();  // about the CoM, body axes
  bool fixed = false;
  // Initial state (global): frame origin, Euler parameters, velocity of the
  // origin, angular velocity.
  Vector3d position = Vector3d::Zero();
  Vector4d orientation = Vector4d(1, 0, 0, 0);
  Vector3d velocity = Vector3d::Zero();
  Vector3d angular_velocity = Vector3d::Zero();
  // Flexible bodies (floating frame of reference): modal data from the body
  // file; `modes` modal coordinates follow the rigid ones in q and v.
  std::shared_ptr<const FlexibleBodyData> flex;
  int modes = 0;
  // Initial modal coordinates and their rates (`modal_coordinates`,
  // `modal_velocities` in the scene, the names of the results datasets, so a
  // run can start from any row of another); zero unless given.
  Eigen::VectorXd modal_coordinates, modal_velocities;
  // Shape for the contact monitor (distance.h): a rod's axis, a plate's
  // mid-plane, a `geometry:` key, or a flexible body's mesh; null if none.
  std::shared_ptr<const BodyGeometry> geometry;
  // Its broad-phase tree (bounding_volume_tree.h), built for the bodies the monitor names.
  std::shared_ptr<const BoundingTree> geometry_tree;
  // Stress recovery (`outputs: {stresses: [...]}`, stress_recovery.h): set only
  // for the bodies named there; null costs nothing.
  std::shared_ptr<const BodyStressRecovery> stress;
  int dof_index = -1;  // first velocity coordinate (6 + modes per free body), -1 if fixed
  int pos_index = -1;  // first position coordinate (7 + modes per free body)
  int nv() const { return 6 + modes; }
  int nq() const { return 7 + modes; }
};

enum class JointType { Spherical, Revolute, Fixed, Universal, Cylindrical, Prismatic };

// Prescribed revolute angle: angle0 + speed t + amplitude sin(2 pi frequency t + phase)
// + spin-up(t). Smooth in time so that the driven accelerations stay finite.
// The spin-up is Kane, Ryan & Banerjee's (J. Guid. Control Dyn. 10 (1987) 139):
// rate (Os/T)(t - (T/2 pi) sin(2 pi t/T)) for t < T, then Os; its acceleration
// (Os/T)(1 - cos(2 pi t/T)) starts and ends at zero.
struct Drive {
  bool active = false;
  double angle0 = 0, speed = 0, amplitude = 0, frequency = 0, phase = 0;
  double spin_rate = 0, spin_time = 0;  // Os [rad/s], T [s]; spin_time 0: no spin-up
  double angle(double t) const;
  double rate(double t) const;
  double accel(double t) const;
};

// Mode shapes at an attachment point of a body with nm modes: translation Psi
// and rotation Theta, each (3, nm); zero for points that only move with the
// frame, empty (3, 0) for rigid bodies.
struct PointShapes {
  Eigen::MatrixXd psi = Eigen::MatrixXd::Zero(3, 0), theta = Eigen::MatrixXd::Zero(3, 0);
};

// One-sided stops on a revolute joint's angle (scene `limits: {min, max,
// restitution}`; docs/mbs-run.md "Stops"): the angle stays in [min, max]; an
// impact reverses the approach rate with Newton's coefficient, and a joint
// that cannot rebound above the tolerance rests on the stop while pushed.
struct JointLimits {
  bool has_min = false, has_max = false;
  double min = 0.0, max = 0.0;
  double restitution = 0.0;
  bool any() const { return has_min || has_max; }
};

struct Joint {
  std::string name;
  JointType type = JointType::Spherical;
  int body_i = -1, body_j = -1;               // indices into Model::bodies
  Vector3d point_i = Vector3d::Zero(), point_j = Vector3d::Zero();  // body frames
  // The flexible body's interface named as the point, empty for coordinates
  // (its reaction stiffens the body: flexible/geometric_stiffening.h).
  std::string interface_i, interface_j;
  // Axes and held directions of a body turn with the modal rotation at its point.
  PointShapes shapes_i, shapes_j;
  Vector3d axis_i = Vector3d::UnitZ(), axis_j = Vector3d::UnitZ();  // unit, body frames
  double initial_angle = 0.0;                 // revolute: angle in the initial configuration
  bool enabled = true;
  bool locked = false;                        // revolute: angle held
  Drive drive;                                // revolute: angle prescribed in time
  JointLimits limits;                         // revolute: stops on the angle
  // Revolute `stop_only: true`: the joint only measures the angle between
  // two bodies that other joints hold (a flexible hinge's two spherical
  // joints) and adds a row only while locked or resting on a stop.
  bool stop_only = false;
};

enum class ForceType { Gravity, RotationalSpringDamper, TranslationalSpringDamper, ConstantForce, ConstantTorque, Contact };

// f(x) piecewise linear through (x_k, y_k), constant beyond the ends.
struct PiecewiseLinear {
  std::vector<double> x, y;
  double value(double at) const;
  // Integral of f from 0 to `at` (the potential of a spring whose torque is f).
  double integral(double at) const;
};

struct ForceElement {
  std::string name;
  ForceType type = ForceType::Gravity;
  bool enabled = true;
  Vector3d vector = Vector3d::Zero();   // gravity g, constant force or torque (global)
  int joint = -1;                       // rotational spring-damper
  PiecewiseLinear torque;               // rotational: f(angle)
  double damping = 0.0;                 // rotational [N m s], translational [N s/m]
  int body_i = -1, body_j = -1;         // translational spring / constant force (body_i)
  Vector3d point_i = Vector3d::Zero(), point_j = Vector3d::Zero();
  PointShapes shapes_i, shapes_j;
  // The flexible body's interface named as the point, empty for coordinates
  // (its force there stiffens the body: flexible/geometric_stiffening.h).
  std::string interface_i, interface_j;
  double stiffness = 0.0, free_length = 0.0;  // translational spring; contact: k [N/m^exponent]
  // One-sided contact (force_elements.h, contactState): point i (on body_i)
  // against the plane through point j of body_j with normal `vector` (body_j
  // axes, unit); F = k d^n (1 + hysteresis d_dot) >= 0 for a penetration d > 0.
  double exponent = 1.0;    // n: 1 linear, 1.5 Hertz
  double hysteresis = 0.0;  // Lankarani-Nikravesh 3 (1 - e^2) / (4 v0) [s/m]
  double radius = 0.0;      // in-plane extent of the plane patch about point j; 0: unbounded
  // The plane patch as a rectangle instead (a panel's mid-plane): half-widths
  // along `patch_axis` (body j axes, in the plane) and along n x patch_axis;
  // both 0: the circular `radius` (or unbounded).
  Vector3d patch_axis = Vector3d::UnitX();
  double patch_half_u = 0.0, patch_half_v = 0.0;
  // Which contact (force_elements.h): point i against the plane of j; the
  // segment from point_i to point_i2 of body i (a rod's axis, `segment_radius`
  // its radius) against the edge polyline `edge_points` of body j; or each
  // edge point of body i against the plane of j; or the segment of body i
  // against the shell triangles `surface_triangles` of body j's mesh (indices
  // into `edge_points`, which then hold all its nodes). The edge's points are
  // interfaces or mesh nodes with their shapes, `edge_half_thickness` the
  // panel's half thickness about them.
  enum class ContactKind { PointPlane, SegmentEdge, EdgePlane, SegmentSurface };
  ContactKind contact_kind = ContactKind::PointPlane;
  Vector3d point_i2 = Vector3d::Zero();
  PointShapes shapes_i2;
  double segment_radius = 0.0;
  std::vector<Vector3d> edge_points;
  std::vector<PointShapes> edge_shapes;
  double edge_half_thickness = 0.0;
  std::vector<std::array<int, 3>> surface_triangles;
};

struct Event {
  // Either a time, or a joint-angle crossing: the first time after the start at
  // which the joint's angle passes `angle` (in `direction`: +1 rising, -1 falling, 0 any).
  double time = -1.0;
  int joint = -1;
  double angle = 0.0;
  int direction = 0;
  std::vector<int> lock, release;               // revolute joints
  std::vector<int> enable_joints, disable_joints;
  std::vector<int> enable_forces, disable_forces;
  std::string label;
};

enum class IntegratorKind { Auto, DormandPrince, TrBdf2, Imex };

// `formulation:` auto runs an open tree of rigid bodies on revolute and
// prismatic joints in joint coordinates (kinematic_tree.h) and everything
// else constrained; tree asks for joint coordinates (a warning and the
// constrained path when the scene has what they do not support);
// constrained forces the Cartesian coordinates with constraints.
enum class Formulation { Auto, Tree, Constrained };

struct Settings {
  double t_end = 1.0;
  double output_step = 0.01;
  double rtol = 1e-6;
  double atol = -1.0;            // < 0: rtol * 1e-3 (positions in m, angles in rad, ~1)
  // As asked: Auto stays Auto here; what it means for the run, and the
  // tolerances' defaults, are decided once by runPolicy (run/run_policy.h).
  IntegratorKind integrator = IntegratorKind::Auto;
  double max_step = -1.0;        // < 0: 10 output steps
  // Augmented Lagrangian (Bayo & Ledesma 1996): penalty scale relative to the
  // largest free-body mass or inertia (1e6: see docs/mbs-run.md, larger values
  // make the singular SAR toggle bounce instead of pass), and the Baumgarte-like
  // frequency and damping ratio (Bayo & Ledesma: omega = 10, xi = 1).
  double penalty = 1.0e6;
  double omega = 10.0, xi = 1.0;
  // Most multiplier updates per acceleration solve. Far from singularities
  // two reach rounding level (penalty 1e6); a small fixed cap keeps the
  // nearly dependent rows of a singular configuration penalty-regularised in
  // a way that is smooth in the state: a converged solve (or a state-dependent
  // stopping rule) let the SAR knee be captured at its toggle or stall the
  // step control there (docs/mbs-run.md).
  int multiplier_iterations = 3;
  // How (M + a Phi^T Phi)^-1 is applied (augmented_lagrangian.h): block Schur
  // complement with a dense joint-space matrix up to
  // AlSolver::kMaxDenseSchurRows constraint rows, with a sparse one above.
  AlMethod linear_solver = AlMethod::Automatic;
  Formulation formulation = Formulation::Auto;
};

// `outputs: {margins: {beams: [...]}}`: a member whose axial compression is
// checked against its Euler load (run/margins.h).
struct BeamMarginSpec {
  int body = -1;
  int joint_a = -1, joint_b = -1;  // the joints at its two ends
  double EI = 0.0;                 // bending stiffness of the weaker axis [N m^2], as stated in the scene
  double length = 0.0;             // between the two joints' points [m]
  std::string ends;                // end conditions: pinned, fixed, fixed_pinned, fixed_free
  double K = 1.0;                  // effective-length factor of `ends`
  double euler_load = 0.0;         // pi^2 EI / (K L)^2 [N]
};

struct Model {
  std::vector<Body> bodies;
  std::vector<Joint> joints;
  std::vector<ForceElement> forces;
  std::vector<Event> events;
  // Indices into `forces` of the contact elements, in order: the rows of the
  // results' contacts/ group.
  std::vector<int> contactElements() const {
    std::vector<int> k;
    for (std::size_t f = 0; f < forces.size(); ++f)
      if (forces[f].type == ForceType::Contact) k.push_back(static_cast<int>(f));
    return k;
  }
  // Contact monitor (`outputs: {distances: [[A, B], ...]}`): body index pairs.
  std::vector<std::array<int, 2>> distance_pairs;
  // `outputs: {stress_every: K}`: the full stress fields get every K-th output
  // row (and the last) with their own /stress_time; 0 when the key is absent
  // (every row, no /stress_time). The envelope takes every row either way.
  int stress_every = 0;
  // `outputs: {margins: ...}`: beams checked against buckling, and the joints
  // whose peak reactions the summary prints (every joint's are written).
  std::vector<BeamMarginSpec> margin_beams;
  std::vector<int> margin_joints;
  Settings settings;
  int nq = 0, nv = 0;  // 7 + modes and 6 + modes per free body
  std::string source;  // scene file, for messages

  // Assigns dof_index/pos_index and nq/nv; call after the bodies are final.
  void finalize();
  int bodyIndex(const std::string& name) const;
  int jointIndex(const std::string& name) const;
  int forceIndex(const std::string& name) const;
};

}  // namespace fc::mbs
