#pragma once
// Force elements (contracts.md `forces:`): gravity, rotational and
// translational spring-dampers, constant forces and torques. Each type is
// defined once, in one function giving its generalised forces, the powers the
// energy balance integrates (dampers, non-conservative loads) and its
// potential energy, so that force and potential cannot drift apart.
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "mbs-run/mechanics/constraints.h"
#include "mbs-run/mechanics/kinematics.h"
#include "mbs-run/model/model.h"

namespace fc::mbs {

// Sums over the force elements, accumulated in element order.
struct ForceSums {
  Eigen::VectorXd Q;           // generalised forces on the velocity coordinates (nv)
  double dissipation = 0.0;    // power dissipated by dampers (>= 0)
  double applied_power = 0.0;  // power of non-conservative loads (constant torques)
  double potential = 0.0;      // potential energy of the conservative parts
};

// What to evaluate: the rates the derivative needs (Q and the powers), or the
// potential energy only (energy reports).
enum class ForceQuantity { ForcesAndPowers, Potential };

// Adds the contribution of element `fe` at poses P (joint runtimes for the
// revolute angle of rotational springs) to `sums`; sums.Q must have size nv
// when forces are asked for.
void addForceElement(const Model& model, const ForceElement& fe, const std::vector<BodyPose>& P,
                     const std::vector<JointRuntime>& joints, ForceQuantity what, ForceSums& sums);

// A force a point element exerts on a body at one of its interfaces (global
// axes): what stiffens that body (flexible/geometric_stiffening.h).
struct InterfaceForce {
  int body = -1;
  const std::string* interface = nullptr;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

// The forces element `fe` applies at named interfaces at poses P: a
// translational spring-damper's F e and -F e at its two points, a constant
// force at its point; none for gravity (an inertial case of its own) and the
// torques (a pure moment at a point: not among the stiffening loads). Appends
// to `out`.
void interfaceForces(const Model& model, const ForceElement& fe, const std::vector<BodyPose>& P,
                     std::vector<InterfaceForce>& out);

// One-sided contact of a point P on body i with the plane through a point Q
// of body j, normal n (body j axes; the plane turns with the interface
// rotation Theta w when Q is an interface of a flexible body j):
//   penetration d = -(x_P - x_Q) . n_g,  n_g = A_j (n + (Theta_Q w_j) x n),
//   force F = max(0, k d^n (1 + alpha d_dot)) for d > 0 (and P within `radius`
//   of Q in the plane when a radius is given), else 0,
// the Hunt-Crossley law with Lankarani and Nikravesh's hysteresis factor
// alpha = 3 (1 - e^2) / (4 v0) (J. Mech. Des. 112:369, 1990). F pushes P
// along +n_g and body j along -n_g; the generalised forces are -F dd/dq, the
// exact gradient of the d the potential k d^(n+1) / (n+1) is a function of,
// so the elastic part's power is exactly -dV/dt and the rest, (F - k d^n)
// d_dot >= 0, is dissipated.
struct ContactState {
  double penetration = 0.0;  // d [m] (negative: separated along the normal)
  double rate = 0.0;         // d_dot [m/s]
  double force = 0.0;        // F [N] >= 0
  double elastic = 0.0;      // k d^n while in contact, else 0 [N]
  bool touching = false;     // d > 0 and inside the patch
  double outside = 0.0;      // in-plane distance of P beyond the patch's edge [m] (0 inside or unbounded)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // n_g, global
  Eigen::RowVectorXd grad_i, grad_j;                 // dd/dv of the two bodies
  double dissipation = 0.0;  // (F - k d^n) d_dot >= 0 [W], summed over the contact's points
  double potential = 0.0;    // k d^(n+1) / (n+1) [J], summed
};
// The other kinds (ForceElement::ContactKind) use the same law:
// - segment against edge: a rod's axis [x_a, x_b] on body i (radius r)
//   against a polyline of body j's points (a panel's hinge edge, half
//   thickness h): d = r + h minus the distance of the closest points, F n at
//   the segment's ends and -F n at the edge's two nearest nodes in the
//   closest points' ratios (force_elements.cpp, segmentEdge);
// - edge against plane: each of body i's edge points (half thickness h off
//   it) against body j's plane patch, summed (edgePlane): grad_i, grad_j are
//   then the force-weighted means, so that -F grad is the sum's generalised
//   force; the reported d, d_dot and normal are the deepest point's.
ContactState contactState(const ForceElement& fe, const std::vector<BodyPose>& P);

// The closest points p1 + s (q1 - p1) and p2 + t (q2 - p2), s, t in [0, 1],
// of two segments (Ericson, Real-Time Collision Detection, 2005, 5.1.9).
void closestSegmentPoints(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                          const Eigen::Vector3d& q2, double& s, double& t);

// The point of triangle (a, b, c) closest to p (Ericson 5.1.5, Voronoi regions
// of the vertices, edges and face), and its barycentric weights: the point is
// bary(0) a + bary(1) b + bary(2) c.
Eigen::Vector3d closestTrianglePoint(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c, Eigen::Vector3d& bary);

// The closest points of the segment [p, q] and the triangle (a, b, c): the
// segment's point p + s (q - p) and the triangle's with barycentric weights
// `bary`; returns their distance (0 where the segment passes through the
// triangle, s and bary then the crossing point's). The smallest of the
// segment's ends against the triangle and the segment against its three
// edges, after the crossing test (Ericson 5.1.9, 5.1.5, 5.3.6).
double closestSegmentTrianglePoints(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c, double& s,
                                    Eigen::Vector3d& bary);

// What the results report as the contact's penetration: d inside the patch,
// and outside it minus P's distance to the patch disk, -hypot(outside, d)
// (negative: apart), so that a point far off the patch does not show a
// penetration the element never acts on.
double reportedPenetration(const ContactState& cs);

// The linear part of a force element along its own coordinate s (a
// revolute angle, a spring's length): the element applies
// Q = -F(s, s_dot) [grad_i, grad_j]^T with s_dot = grad_i v_i + grad_j v_j,
// and dF/ds = stiffness, dF/ds_dot = damping at poses P, so its stiffness and
// damping on the velocity coordinates are stiffness g g^T (the part through
// s only; the curvature of s is left out) and damping g g^T. A damper acting
// at a flexible body's interface puts damping g_f g_f^T on that body's modal
// rates, g_f the modal tail of its gradient: as stiff as the modes it damps
// (System::modalSplit hands it to the IMEX integrator's implicit part).
// False, and nothing set, for elements without such a coordinate (gravity,
// constant loads) or when the element is inactive (a contact not touching,
// a spring at zero length).
struct LinearForce {
  double stiffness = 0.0, damping = 0.0;
  Eigen::RowVectorXd grad_i, grad_j;
};
bool linearForce(const Model& model, const ForceElement& fe, const std::vector<BodyPose>& P,
                 const std::vector<JointRuntime>& joints, LinearForce& out);

// "NAME (type)", or "#k (type)" for an unnamed element, for messages.
std::string forceElementLabel(const Model& model, int index);

}  // namespace fc::mbs
