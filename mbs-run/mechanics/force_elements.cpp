#include "mbs-run/mechanics/force_elements.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/mechanics/flexible/modal.h"

namespace fc::mbs {

using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

struct Context {
  const Model& model;
  const std::vector<BodyPose>& P;
  const std::vector<JointRuntime>& joints;
  bool forces;     // Q and the powers
  bool potential;  // potential energy
};

// Generalised forces J^T f of a global force at a point and J_w^T n of a
// global torque, J = [I, -A s~, A Psi], J_w = [0, A, A Theta].
void addForceAt(const Context& c, int body, const Vector3d& s0, const PointShapes& sh, const Vector3d& f,
                VectorXd& Q) {
  const Body& b = c.model.bodies[body];
  if (b.fixed) return;
  Q.segment(b.dof_index, b.nv()) += attachedPoint(c.P[body], s0, sh.psi).J.transpose() * f;
}

void addTorque(const Context& c, int body, const PointShapes& sh, const Vector3d& n, VectorXd& Q) {
  const Body& b = c.model.bodies[body];
  if (b.fixed) return;
  const Vector3d nb = c.P[body].A.transpose() * n;
  Q.segment<3>(b.dof_index + 3) += nb;
  if (b.modes > 0 && sh.theta.cols() == b.modes) Q.segment(b.dof_index + 6, b.modes) += sh.theta.transpose() * nb;
}

// The velocity coordinates [rdot, omega', wdot] of a pose (zero for fixed bodies).
VectorXd velocityOf(const BodyPose& b) {
  VectorXd v(b.nv());
  v << b.rdot, b.w, b.modal_rate;
  return v;
}

// Uniform gravity g on every free body: V = -m g . x_com (rigid), the
// flexible body's -g . (m r + A S(w)) (mbs-run/mechanics/flexible/modal.h).
void gravity(const Context& c, const ForceElement& fe, ForceSums& s) {
  const PointShapes frame_only;
  for (std::size_t k = 0; k < c.model.bodies.size(); ++k) {
    const Body& b = c.model.bodies[k];
    if (b.fixed) continue;
    const BodyPose& P = c.P[k];
    if (c.forces) {
      if (b.flex)
        s.Q.segment(b.dof_index, b.nv()) += gravityForces(b.flex->inertia, P.A, P.modal, fe.vector);
      else
        addForceAt(c, static_cast<int>(k), b.com, frame_only, b.mass * fe.vector, s.Q);
    }
    if (c.potential) {
      if (b.flex) s.potential += gravityPotential(b.flex->inertia, P.r, P.A, P.modal, fe.vector);
      else s.potential -= b.mass * fe.vector.dot(P.r + P.A * b.com);
    }
  }
}

// Torque M = f(angle) + c angle_dot about a revolute joint; V = int_0^angle f.
// Q = -M g^T with g = d(angle)/dv, the exact gradient of the angle the
// potential is a function of (constraints.h): the spring's power is exactly
// -dV/dt and the damper's exactly -c angle_dot^2, also with large modal
// rotations, where a torque M n through J_w = [0, A, A Theta] matched the
// angle only to first order in them. On rigid bodies with the joint assembled
// g^T is [0, -A_i^T n] and [0, A_j^T n]: the torques M n on i and -M n on j.
void rotationalSpringDamper(const Context& c, const ForceElement& fe, ForceSums& s) {
  const Joint& jt = c.model.joints[fe.joint];
  const BodyPose &bi = c.P[jt.body_i], &bj = c.P[jt.body_j];
  const double th = revoluteAngle(jt, c.joints[fe.joint], bi, bj);
  if (c.forces) {
    Eigen::RowVectorXd gi, gj;
    revoluteAngleJacobian(jt, bi, bj, gi, gj);
    const double thd = gi.dot(velocityOf(bi)) + gj.dot(velocityOf(bj));
    const double M = fe.torque.value(th) + fe.damping * thd;
    const Body &body_i = c.model.bodies[jt.body_i], &body_j = c.model.bodies[jt.body_j];
    if (!body_i.fixed) s.Q.segment(body_i.dof_index, body_i.nv()) -= M * gi.transpose();
    if (!body_j.fixed) s.Q.segment(body_j.dof_index, body_j.nv()) -= M * gj.transpose();
    s.dissipation += fe.damping * thd * thd;
  }
  if (c.potential) s.potential += fe.torque.integral(th);
}

// Force F = k (L - L0) + c L_dot along the line between two points, pulling
// them together when stretched; V = k (L - L0)^2 / 2.
struct SpringState {
  double L = 0.0, Ld = 0.0, F = 0.0;
  Vector3d e = Vector3d::Zero();  // from point i to point j
};

SpringState springState(const std::vector<BodyPose>& P, const ForceElement& fe) {
  const Attached ai = attachedPoint(P[fe.body_i], fe.point_i, fe.shapes_i.psi);
  const Attached aj = attachedPoint(P[fe.body_j], fe.point_j, fe.shapes_j.psi);
  const Vector3d d = aj.x - ai.x;
  SpringState s;
  s.L = d.norm();
  // At L = 0 the direction is undefined; the force is continuous only for L > 0.
  if (s.L > 0.0) {
    s.e = d / s.L;
    s.Ld = s.e.dot(aj.xdot - ai.xdot);
    s.F = fe.stiffness * (s.L - fe.free_length) + fe.damping * s.Ld;
  }
  return s;
}

void translationalSpringDamper(const Context& c, const ForceElement& fe, ForceSums& s) {
  const SpringState sp = springState(c.P, fe);
  if (c.forces && sp.L > 0.0) {
    addForceAt(c, fe.body_i, fe.point_i, fe.shapes_i, sp.F * sp.e, s.Q);
    addForceAt(c, fe.body_j, fe.point_j, fe.shapes_j, -sp.F * sp.e, s.Q);
    s.dissipation += fe.damping * sp.Ld * sp.Ld;
  }
  if (c.potential) {
    const double stretch = sp.L - fe.free_length;
    s.potential += 0.5 * fe.stiffness * stretch * stretch;
  }
}

// Constant global force at a body point: V = -f . x.
void constantForce(const Context& c, const ForceElement& fe, ForceSums& s) {
  if (c.forces) addForceAt(c, fe.body_i, fe.point_i, fe.shapes_i, fe.vector, s.Q);
  if (c.potential && !c.model.bodies[fe.body_i].fixed)
    s.potential -= fe.vector.dot(attachedPoint(c.P[fe.body_i], fe.point_i, fe.shapes_i.psi).x);
}

// Constant global torque on a body frame: not conservative for a body free to
// turn in 3-D, so no potential; its power n . omega is integrated instead.
void constantTorque(const Context& c, const ForceElement& fe, ForceSums& s) {
  if (!c.forces) return;
  const PointShapes frame_only;
  addTorque(c, fe.body_i, frame_only, fe.vector, s.Q);
  s.applied_power += fe.vector.dot(c.P[fe.body_i].A * c.P[fe.body_i].w);
}

void contact(const Context& c, const ForceElement& fe, ForceSums& s) {
  const ContactState cs = contactState(fe, c.P);
  if (!cs.touching) return;
  if (c.forces) {
    const Body &bi = c.model.bodies[fe.body_i], &bj = c.model.bodies[fe.body_j];
    if (!bi.fixed) s.Q.segment(bi.dof_index, bi.nv()) -= cs.force * cs.grad_i.transpose();
    if (!bj.fixed) s.Q.segment(bj.dof_index, bj.nv()) -= cs.force * cs.grad_j.transpose();
    s.dissipation += cs.dissipation;
  }
  if (c.potential) s.potential += cs.potential;
}

}  // namespace

namespace {

// Hunt-Crossley / Lankarani-Nikravesh at penetration d and rate d_dot (set
// in cs): F = max(0, k d^n (1 + alpha d_dot)) while touching, and the power
// and potential that go with it.
void applyLaw(const ForceElement& fe, ContactState& cs) {
  if (!cs.touching) return;
  cs.elastic = fe.stiffness * std::pow(cs.penetration, fe.exponent);
  // Never pulling: a fast separation (alpha d_dot < -1) leaves the hysteresis
  // term larger than the elastic one; the force is then 0, not negative.
  cs.force = std::max(0.0, cs.elastic * (1.0 + fe.hysteresis * cs.rate));
  cs.dissipation = (cs.force - cs.elastic) * cs.rate;
  cs.potential = cs.elastic * cs.penetration / (fe.exponent + 1.0);
}

// Point s_i (shapes sh_i) of body i against the plane of body j, the point
// standing `offset` off it (a panel edge's half thickness).
ContactState pointPlane(const ForceElement& fe, const std::vector<BodyPose>& P, const Vector3d& s_i,
                        const PointShapes& sh_i, double offset) {
  const BodyPose &a = P[fe.body_i], &b = P[fe.body_j];
  const Attached ap = attachedPoint(a, s_i, sh_i.psi);
  const Attached bq = attachedPoint(b, fe.point_j, fe.shapes_j.psi);
  const bool flex_j = b.modal.size() > 0 && fe.shapes_j.theta.cols() == b.modal.size();
  const Vector3d& n0 = fe.vector;
  const Vector3d n = flex_j ? Vector3d(n0 + Vector3d(fe.shapes_j.theta * b.modal).cross(n0)) : n0;  // body j axes
  ContactState cs;
  cs.normal = b.A * n;
  const Vector3d d = ap.x - bq.x, dj = b.A.transpose() * d;
  cs.penetration = offset - d.dot(cs.normal);
  // dd/dv_i = -n_g^T J_P; dd/dv_j = [n_g^T, ((u_Q + d_j) x n)^T, (Psi^T n + Theta^T (d_j x n0))^T]
  // with u_Q the body-axes position of Q (derivation in docs/mbs-run.md).
  cs.grad_i = -cs.normal.transpose() * ap.J;
  cs.grad_j.setZero(b.nv());
  cs.grad_j.head<3>() = cs.normal.transpose();
  const Vector3d uq = flex_j ? Vector3d(fe.point_j + fe.shapes_j.psi * b.modal) : fe.point_j;
  cs.grad_j.segment<3>(3) = (uq + dj).cross(n).transpose();
  if (flex_j)
    cs.grad_j.tail(b.modal.size()) =
        (fe.shapes_j.psi.transpose() * n + fe.shapes_j.theta.transpose() * dj.cross(n0)).transpose();
  cs.rate = cs.grad_i.dot(velocityOf(a)) + cs.grad_j.dot(velocityOf(b));
  bool inside = true;
  const Vector3d e = cs.normal.normalized();
  if (fe.patch_half_u > 0.0 || fe.patch_half_v > 0.0) {
    // The rectangle's axes turn with body j's frame (a rigid panel's plane).
    const Vector3d u0 = b.A * fe.patch_axis;
    const Vector3d u = (u0 - u0.dot(e) * e).normalized(), v = e.cross(u);
    const double du = std::abs(d.dot(u)) - fe.patch_half_u, dv = std::abs(d.dot(v)) - fe.patch_half_v;
    cs.outside = std::hypot(std::max(0.0, du), std::max(0.0, dv));
    inside = cs.outside == 0.0;
  } else if (fe.radius > 0.0) {
    const double in_plane = (d - d.dot(e) * e).norm();
    inside = in_plane <= fe.radius;
    cs.outside = std::max(0.0, in_plane - fe.radius);
  }
  cs.touching = cs.penetration > 0.0 && inside;
  applyLaw(fe, cs);
  return cs;
}

// Global position of a body point with shapes sh (no Jacobian).
Vector3d pointPosition(const BodyPose& b, const Vector3d& s0, const PointShapes& sh) {
  if (sh.psi.cols() > 0 && sh.psi.cols() == b.modal.size()) return b.r + b.A * (s0 + sh.psi * b.modal);
  return b.r + b.A * s0;
}

// The segment [x_a, x_b] of body i (radius r) against the edge polyline of
// body j (half thickness h): the pair of closest points over the edge's
// pieces, c_i = (1 - s) x_a + s x_b and c_j = (1 - t) x_k + t x_k+1,
// penetration d = r + h - |c_i - c_j|, normal n = (c_i - c_j) / |c_i - c_j|
// from the edge to the segment. As s and t minimise the distance, its
// gradient is the points' own (envelope theorem):
//   dd/dv_i = -n^T ((1 - s) J_a + s J_b),  dd/dv_j = n^T ((1 - t) J_k + t J_k+1),
// so F n acts at the segment's end points in the ratio (1 - s) : s and -F n
// at the edge's two nodes in the ratio (1 - t) : t, and the force is the
// exact gradient of the potential k d^(n+1) / (n+1) as for the plane.
ContactState segmentEdge(const ForceElement& fe, const std::vector<BodyPose>& P) {
  const BodyPose &a = P[fe.body_i], &b = P[fe.body_j];
  const Vector3d xa = pointPosition(a, fe.point_i, fe.shapes_i), xb = pointPosition(a, fe.point_i2, fe.shapes_i2);
  const std::size_t ne = fe.edge_points.size();
  std::vector<Vector3d> xe(ne);
  for (std::size_t k = 0; k < ne; ++k) xe[k] = pointPosition(b, fe.edge_points[k], fe.edge_shapes[k]);
  double best = std::numeric_limits<double>::infinity(), s = 0.0, t = 0.0;
  std::size_t kb = 0;
  for (std::size_t k = 0; k + 1 < ne; ++k) {
    double sk = 0.0, tk = 0.0;
    closestSegmentPoints(xa, xb, xe[k], xe[k + 1], sk, tk);
    const double dist = ((xa + sk * (xb - xa)) - (xe[k] + tk * (xe[k + 1] - xe[k]))).norm();
    if (dist < best) best = dist, s = sk, t = tk, kb = k;
  }
  ContactState cs;
  const Vector3d ci = xa + s * (xb - xa), cj = xe[kb] + t * (xe[kb + 1] - xe[kb]);
  Vector3d n = ci - cj;
  if (best > 0.0) {
    n /= best;
  } else {  // the axes meet: the normal of both (the distance's gradient is undefined there)
    n = (xb - xa).cross(xe[kb + 1] - xe[kb]);
    n = n.norm() > 0.0 ? Vector3d(n.normalized()) : Vector3d::UnitZ();
  }
  cs.normal = n;
  cs.penetration = fe.segment_radius + fe.edge_half_thickness - best;
  const Attached pa = attachedPoint(a, fe.point_i, fe.shapes_i.psi), pb = attachedPoint(a, fe.point_i2, fe.shapes_i2.psi);
  const Attached e0 = attachedPoint(b, fe.edge_points[kb], fe.edge_shapes[kb].psi);
  const Attached e1 = attachedPoint(b, fe.edge_points[kb + 1], fe.edge_shapes[kb + 1].psi);
  cs.grad_i = -n.transpose() * ((1.0 - s) * pa.J + s * pb.J);
  cs.grad_j = n.transpose() * ((1.0 - t) * e0.J + t * e1.J);
  cs.rate = cs.grad_i.dot(velocityOf(a)) + cs.grad_j.dot(velocityOf(b));
  cs.touching = cs.penetration > 0.0;
  applyLaw(fe, cs);
  return cs;
}

// The segment [x_a, x_b] of body i (radius r) against the shell triangles of
// body j (half thickness h), their nodes moving with their mode shapes: the
// closest points over the triangles, c_i = (1 - s) x_a + s x_b on the segment
// and c_j = sum_k lambda_k x_k on the nearest triangle (barycentric weights
// lambda), d = r + h - |c_i - c_j|, n from c_j to c_i. As in segmentEdge the
// points minimise the distance, so its gradient is theirs:
//   dd/dv_i = -n^T ((1 - s) J_a + s J_b),  dd/dv_j = n^T sum_k lambda_k J_k,
// F n at the segment's ends, -F n at the triangle's nodes in the weights
// lambda. A triangle whose box lies farther from the segment's box than the
// best distance so far cannot hold the minimum and is skipped.
ContactState segmentSurface(const ForceElement& fe, const std::vector<BodyPose>& P) {
  const BodyPose &a = P[fe.body_i], &b = P[fe.body_j];
  const Vector3d xa = pointPosition(a, fe.point_i, fe.shapes_i), xb = pointPosition(a, fe.point_i2, fe.shapes_i2);
  const std::size_t nn = fe.edge_points.size();
  std::vector<Vector3d> x(nn);
  for (std::size_t k = 0; k < nn; ++k) x[k] = pointPosition(b, fe.edge_points[k], fe.edge_shapes[k]);
  const Vector3d slo = xa.cwiseMin(xb), shi = xa.cwiseMax(xb);
  double best = std::numeric_limits<double>::infinity(), s = 0.0;
  Vector3d lambda(1, 0, 0);
  std::size_t tb = 0;
  for (std::size_t e = 0; e < fe.surface_triangles.size(); ++e) {
    const auto& t = fe.surface_triangles[e];
    const Vector3d &p0 = x[t[0]], &p1 = x[t[1]], &p2 = x[t[2]];
    const Vector3d lo = p0.cwiseMin(p1).cwiseMin(p2), hi = p0.cwiseMax(p1).cwiseMax(p2);
    const Vector3d gap = (lo - shi).cwiseMax(slo - hi).cwiseMax(0.0);
    if (gap.norm() > best) continue;
    double se = 0.0;
    Vector3d le;
    const double de = closestSegmentTrianglePoints(xa, xb, p0, p1, p2, se, le);
    if (de < best) best = de, s = se, lambda = le, tb = e;
  }
  ContactState cs;
  const auto& t = fe.surface_triangles[tb];
  const Vector3d ci = xa + s * (xb - xa), cj = lambda[0] * x[t[0]] + lambda[1] * x[t[1]] + lambda[2] * x[t[2]];
  Vector3d n = ci - cj;
  if (n.norm() > 0.0) {
    n.normalize();
  } else {  // through the triangle: its normal, towards the segment's farther end
    n = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).normalized();
    const Vector3d far = (xa - cj).norm() > (xb - cj).norm() ? xa : xb;
    if (n.dot(far - cj) < 0.0) n = -n;
  }
  cs.normal = n;
  cs.penetration = fe.segment_radius + fe.edge_half_thickness - best;
  const Attached pa = attachedPoint(a, fe.point_i, fe.shapes_i.psi), pb = attachedPoint(a, fe.point_i2, fe.shapes_i2.psi);
  cs.grad_i = -n.transpose() * ((1.0 - s) * pa.J + s * pb.J);
  cs.grad_j.setZero(b.nv());
  for (int k = 0; k < 3; ++k)
    if (lambda[k] != 0.0) cs.grad_j += lambda[k] * (n.transpose() * attachedPoint(b, fe.edge_points[t[k]], fe.edge_shapes[t[k]].psi).J);
  cs.rate = cs.grad_i.dot(velocityOf(a)) + cs.grad_j.dot(velocityOf(b));
  cs.touching = cs.penetration > 0.0;
  applyLaw(fe, cs);
  return cs;
}

// Every edge point of body i against the plane (patch) of body j, each with
// its own penetration and force: the sums of the forces, powers and
// potentials; the reported penetration, rate and normal are the deepest
// point's; grad_i, grad_j are the force-weighted mean gradients, so that
// -F grad is the sum of the points' generalised forces.
ContactState edgePlane(const ForceElement& fe, const std::vector<BodyPose>& P) {
  ContactState total;
  total.penetration = -std::numeric_limits<double>::infinity();
  total.grad_i.setZero(P[fe.body_i].nv());
  total.grad_j.setZero(P[fe.body_j].nv());
  for (std::size_t k = 0; k < fe.edge_points.size(); ++k) {
    const ContactState c = pointPlane(fe, P, fe.edge_points[k], fe.edge_shapes[k], fe.edge_half_thickness);
    const double reported = reportedPenetration(c);
    if (reported > total.penetration) {
      total.penetration = reported;
      total.rate = c.rate;
      total.normal = c.normal;
    }
    if (!c.touching) continue;
    total.touching = true;
    total.force += c.force;
    total.elastic += c.elastic;
    total.dissipation += c.dissipation;
    total.potential += c.potential;
    total.grad_i += c.force * c.grad_i;
    total.grad_j += c.force * c.grad_j;
  }
  if (total.force > 0.0) {
    total.grad_i /= total.force;
    total.grad_j /= total.force;
  }
  return total;
}

}  // namespace

void closestSegmentPoints(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2, const Vector3d& q2, double& s,
                          double& t) {
  const Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  s = t = 0.0;
  if (a == 0.0 && e == 0.0) return;
  if (a == 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double c = d1.dot(r);
  if (e == 0.0) {
    s = std::clamp(-c / a, 0.0, 1.0);
    return;
  }
  const double bb = d1.dot(d2), denom = a * e - bb * bb;
  // Parallel (to rounding): any s gives the lines' distance; start from s = 0.
  s = denom > 1e-14 * a * e ? std::clamp((bb * f - c * e) / denom, 0.0, 1.0) : 0.0;
  t = (bb * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((bb - c) / a, 0.0, 1.0);
  }
}

Vector3d closestTrianglePoint(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c,
                              Vector3d& bary) {
  // Ericson 5.1.5: Voronoi regions of the vertices, edges and face.
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    bary = Vector3d(1, 0, 0);
    return a;
  }
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) {
    bary = Vector3d(0, 1, 0);
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    bary = Vector3d(1 - v, v, 0);
    return a + v * ab;
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) {
    bary = Vector3d(0, 0, 1);
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    bary = Vector3d(1 - w, 0, w);
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    bary = Vector3d(0, 1 - w, w);
    return b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  bary = Vector3d(1 - v - w, v, w);
  return a + ab * v + ac * w;
}

double closestSegmentTrianglePoints(const Vector3d& p, const Vector3d& q, const Vector3d& a, const Vector3d& b,
                                    const Vector3d& c, double& s, Vector3d& bary) {
  // Crossing: the segment's ends on opposite sides of the plane and the
  // crossing point inside the triangle (signed areas of its sub-triangles).
  const Vector3d n = (b - a).cross(c - a);
  const double sp = n.dot(p - a), sq = n.dot(q - a);
  if (((sp <= 0 && sq >= 0) || (sp >= 0 && sq <= 0)) && sp != sq) {
    const double sx = sp / (sp - sq);
    const Vector3d x = p + sx * (q - p);
    const double u = n.dot((b - a).cross(x - a)), v = n.dot((c - b).cross(x - b)), w = n.dot((a - c).cross(x - c));
    if ((u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0)) {
      s = sx;
      const double sum = u + v + w;
      bary = sum != 0.0 ? Vector3d(v / sum, w / sum, u / sum) : Vector3d(1, 0, 0);
      return 0.0;
    }
  }
  // Otherwise the closest points lie on the segment's ends or on an edge.
  Vector3d bk;
  double best = (p - closestTrianglePoint(p, a, b, c, bk)).norm();
  s = 0.0;
  bary = bk;
  const double dq = (q - closestTrianglePoint(q, a, b, c, bk)).norm();
  if (dq < best) best = dq, s = 1.0, bary = bk;
  const Vector3d* v[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const Vector3d &e0 = *v[e], &e1 = *v[(e + 1) % 3];
    double se = 0.0, te = 0.0;
    closestSegmentPoints(p, q, e0, e1, se, te);
    const double de = ((p + se * (q - p)) - (e0 + te * (e1 - e0))).norm();
    if (de < best) {
      best = de, s = se;
      bary.setZero();
      bary[e] = 1.0 - te;
      bary[(e + 1) % 3] = te;
    }
  }
  return best;
}

ContactState contactState(const ForceElement& fe, const std::vector<BodyPose>& P) {
  switch (fe.contact_kind) {
    case ForceElement::ContactKind::SegmentEdge: return segmentEdge(fe, P);
    case ForceElement::ContactKind::EdgePlane: return edgePlane(fe, P);
    case ForceElement::ContactKind::SegmentSurface: return segmentSurface(fe, P);
    case ForceElement::ContactKind::PointPlane: break;
  }
  return pointPlane(fe, P, fe.point_i, fe.shapes_i, 0.0);
}

double reportedPenetration(const ContactState& cs) {
  return cs.outside > 0.0 ? -std::hypot(cs.outside, cs.penetration) : cs.penetration;
}

void addForceElement(const Model& model, const ForceElement& fe, const std::vector<BodyPose>& P,
                     const std::vector<JointRuntime>& joints, ForceQuantity what, ForceSums& sums) {
  const Context c{model, P, joints, what == ForceQuantity::ForcesAndPowers, what == ForceQuantity::Potential};
  switch (fe.type) {
    case ForceType::Gravity: gravity(c, fe, sums); break;
    case ForceType::RotationalSpringDamper: rotationalSpringDamper(c, fe, sums); break;
    case ForceType::TranslationalSpringDamper: translationalSpringDamper(c, fe, sums); break;
    case ForceType::ConstantForce: constantForce(c, fe, sums); break;
    case ForceType::ConstantTorque: constantTorque(c, fe, sums); break;
    case ForceType::Contact: contact(c, fe, sums); break;
  }
}

void interfaceForces(const Model& model, const ForceElement& fe, const std::vector<BodyPose>& P,
                     std::vector<InterfaceForce>& out) {
  (void)model;
  if (fe.type == ForceType::TranslationalSpringDamper && (!fe.interface_i.empty() || !fe.interface_j.empty())) {
    const SpringState sp = springState(P, fe);
    if (sp.L <= 0.0) return;
    if (!fe.interface_i.empty()) out.push_back({fe.body_i, &fe.interface_i, sp.F * sp.e});
    if (!fe.interface_j.empty()) out.push_back({fe.body_j, &fe.interface_j, -sp.F * sp.e});
  } else if (fe.type == ForceType::Contact && fe.contact_kind == ForceElement::ContactKind::PointPlane &&
             (!fe.interface_i.empty() || !fe.interface_j.empty())) {
    const ContactState cs = contactState(fe, P);
    if (!cs.touching) return;
    if (!fe.interface_i.empty()) out.push_back({fe.body_i, &fe.interface_i, cs.force * cs.normal});
    if (!fe.interface_j.empty()) out.push_back({fe.body_j, &fe.interface_j, -cs.force * cs.normal});
  } else if (fe.type == ForceType::ConstantForce && !fe.interface_i.empty()) {
    out.push_back({fe.body_i, &fe.interface_i, fe.vector});
  }
}

namespace {
// dF/dx of the piecewise-linear law at x: the slope of its segment, 0 beyond
// the ends (constant there).
double slope(const PiecewiseLinear& f, double at) {
  if (f.x.size() < 2 || at <= f.x.front() || at >= f.x.back()) return 0.0;
  std::size_t k = 1;
  while (f.x[k] < at) ++k;
  return (f.y[k] - f.y[k - 1]) / (f.x[k] - f.x[k - 1]);
}
}  // namespace

bool linearForce(const Model& model, const ForceElement& fe, const std::vector<BodyPose>& P,
                 const std::vector<JointRuntime>& joints, LinearForce& out) {
  if (fe.type == ForceType::RotationalSpringDamper) {
    const Joint& jt = model.joints[fe.joint];
    const BodyPose &bi = P[jt.body_i], &bj = P[jt.body_j];
    revoluteAngleJacobian(jt, bi, bj, out.grad_i, out.grad_j);
    out.stiffness = slope(fe.torque, revoluteAngle(jt, joints[fe.joint], bi, bj));
    out.damping = fe.damping;
    return true;
  }
  if (fe.type == ForceType::TranslationalSpringDamper) {
    const SpringState sp = springState(P, fe);
    if (sp.L <= 0.0) return false;
    // s_dot = e . (xdot_j - xdot_i), xdot = J v at each point.
    out.grad_i = -sp.e.transpose() * attachedPoint(P[fe.body_i], fe.point_i, fe.shapes_i.psi).J;
    out.grad_j = sp.e.transpose() * attachedPoint(P[fe.body_j], fe.point_j, fe.shapes_j.psi).J;
    out.stiffness = fe.stiffness;
    out.damping = fe.damping;
    return true;
  }
  return false;
}

std::string forceElementLabel(const Model& model, int index) {
  const ForceElement& fe = model.forces[index];
  const char* type = "";
  switch (fe.type) {
    case ForceType::Gravity: type = "gravity"; break;
    case ForceType::RotationalSpringDamper: type = "rotational_spring_damper"; break;
    case ForceType::TranslationalSpringDamper: type = "translational_spring_damper"; break;
    case ForceType::ConstantForce: type = "force"; break;
    case ForceType::ConstantTorque: type = "torque"; break;
    case ForceType::Contact: type = "contact"; break;
  }
  return (fe.name.empty() ? "#" + std::to_string(index + 1) : fe.name) + " (" + type + ")";
}

}  // namespace fc::mbs
