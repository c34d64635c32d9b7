// Constraint kernels against finite differences: for every joint type, with
// random poses and velocities,
//   Phi_v v + Phi_t = d Phi / dt        (central difference along the motion)
//   Phi_v vdot + c  = d^2 Phi / dt^2    (central difference of Phi_dot)
// where the motion integrates r' = rdot, A' = A omega'~ exactly for constant
// velocities and accelerations over the tiny difference step.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include <Eigen/Geometry>

#include "common/rotations.h"
#include "mbs-run/mechanics/constraints.h"

namespace fc::mbs {
namespace {

using Eigen::Vector3d;

struct Motion {
  Vector3d r0, rd, rdd, w0, wd;
  Eigen::Vector4d p0;
  // Pose at time t for constant rdd and omega' = w0 + wd t (second-order
  // accurate attitude via the midpoint rotation of the exponential map).
  BodyPose at(double t) const {
    BodyPose b;
    b.free = true;
    b.r = r0 + rd * t + 0.5 * rdd * t * t;
    b.rdot = rd + rdd * t;
    b.w = w0 + wd * t;
    // Rotation vector of the body-frame increment, to third order in t.
    const Vector3d phi = w0 * t + 0.5 * wd * t * t + (1.0 / 12.0) * w0.cross(wd) * t * t * t;
    b.A = fc::rotationMatrix(p0) * fc::expRotation(phi);
    b.p = fc::eulerParametersFromMatrix(b.A);
    return b;
  }
};

Motion randomMotion(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  auto v = [&] { return Vector3d(u(rng), u(rng), u(rng)); };
  Motion m{v(), v(), v(), v(), v(), Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()};
  return m;
}

Joint makeJoint(JointType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Joint j;
  j.type = type;
  j.point_i = Vector3d(u(rng), u(rng), u(rng));
  j.point_j = Vector3d(u(rng), u(rng), u(rng));
  j.axis_i = Vector3d(u(rng), u(rng), u(rng)).normalized();
  j.axis_j = Vector3d(u(rng), u(rng), u(rng)).normalized();
  return j;
}

// Modal coordinates w(t) = w0 + wd t + wdd t^2 / 2 of a flexible body (empty: rigid).
struct ModalMotion {
  Eigen::VectorXd w0, wd, wdd;
  void apply(BodyPose& b, double t) const {
    b.modal = w0 + wd * t + 0.5 * wdd * t * t;
    b.modal_rate = wd + wdd * t;
  }
};

// nm > 0: both bodies flexible with nm modes, random shapes at the joint's
// points and modal rotations |Theta w| ~ 0.5 rad.
void checkJoint(Joint jt, bool locked, bool driven, unsigned seed, int nm = 0) {
  std::mt19937 rng(seed);
  const Motion mi = randomMotion(rng), mj = randomMotion(rng);
  std::uniform_real_distribution<double> u(-1, 1);
  auto randomMatrix = [&](int rows, int cols, double scale) {
    Eigen::MatrixXd m(rows, cols);
    for (int k = 0; k < m.size(); ++k) m.data()[k] = scale * u(rng);
    return m;
  };
  ModalMotion wi{randomMatrix(nm, 1, 0.3), randomMatrix(nm, 1, 1.0), randomMatrix(nm, 1, 1.0)};
  ModalMotion wj{randomMatrix(nm, 1, 0.3), randomMatrix(nm, 1, 1.0), randomMatrix(nm, 1, 1.0)};
  if (nm > 0) {
    jt.shapes_i.psi = randomMatrix(3, nm, 1.0);
    jt.shapes_i.theta = randomMatrix(3, nm, 1.0);
    jt.shapes_j.psi = randomMatrix(3, nm, 1.0);
    jt.shapes_j.theta = randomMatrix(3, nm, 1.0);
  }
  auto poseI = [&](double t) {
    BodyPose b = mi.at(t);
    if (nm > 0) wi.apply(b, t);
    return b;
  };
  auto poseJ = [&](double t) {
    BodyPose b = mj.at(t);
    if (nm > 0) wj.apply(b, t);
    return b;
  };
  JointRuntime rt;
  rt.locked = locked;
  if (driven) {
    jt.drive.active = true;
    jt.drive.angle0 = 0.3;
    jt.drive.speed = 0.7;
    jt.drive.amplitude = 0.2;
    jt.drive.frequency = 1.3;
  }
  // Held poses captured at a different time than checked, so they are generic.
  const BodyPose ci = poseI(-0.3), cj = poseJ(-0.3);
  captureFixed(jt, rt, ci, cj);
  captureLock(jt, rt, ci, cj);
  rt.angle_offset = 0.1;
  const double t0 = 0.2, h = 1e-4;
  ConstraintRows r0, rp, rm;
  jointConstraints(jt, rt, poseI(0), poseJ(0), t0, r0);
  jointConstraints(jt, rt, poseI(h), poseJ(h), t0 + h, rp);
  jointConstraints(jt, rt, poseI(-h), poseJ(-h), t0 - h, rm);
  ASSERT_GT(r0.size(), 0);
  Eigen::VectorXd vi(6 + nm), vj(6 + nm), ai(6 + nm), aj(6 + nm);
  vi << mi.rd, mi.w0, wi.wd;
  vj << mj.rd, mj.w0, wj.wd;
  ai << mi.rdd, mi.wd, wi.wdd;
  aj << mj.rdd, mj.wd, wj.wdd;
  const Eigen::VectorXd phidot = r0.Ji * vi + r0.Jj * vj + r0.phit;
  const Eigen::VectorXd phidot_fd = (rp.phi - rm.phi) / (2 * h);
  const Eigen::VectorXd phiddot = r0.Ji * ai + r0.Jj * aj + r0.c;
  const Eigen::VectorXd phiddot_fd = (rp.phi - 2 * r0.phi + rm.phi) / (h * h);
  // Central differences: truncation h^2 ~ 1e-8 times third derivatives of
  // order 1, rounding eps/h ~ 1e-12 (first) and eps/h^2 ~ 2e-8 (second).
  EXPECT_LT((phidot - phidot_fd).lpNorm<Eigen::Infinity>(), 1e-7);
  EXPECT_LT((phiddot - phiddot_fd).lpNorm<Eigen::Infinity>(), 1e-5);
}

TEST(Constraints, SphericalMatchesFiniteDifferences) {
  std::mt19937 rng(1);
  for (unsigned s = 0; s < 5; ++s) checkJoint(makeJoint(JointType::Spherical, rng), false, false, 10 + s);
}
TEST(Constraints, RevoluteFreeLockedDrivenMatchFiniteDifferences) {
  std::mt19937 rng(2);
  for (unsigned s = 0; s < 5; ++s) {
    const Joint j = makeJoint(JointType::Revolute, rng);
    checkJoint(j, false, false, 20 + s);
    checkJoint(j, true, false, 30 + s);
    checkJoint(j, false, true, 40 + s);
  }
}
TEST(Constraints, FixedUniversalCylindricalPrismaticMatchFiniteDifferences) {
  std::mt19937 rng(3);
  for (JointType t : {JointType::Fixed, JointType::Universal, JointType::Cylindrical, JointType::Prismatic})
    for (unsigned s = 0; s < 3; ++s) checkJoint(makeJoint(t, rng), false, false, 50 + s);
}

// The same on flexible bodies with large modal rotations: the attached
// points and vectors (kinematics.h), and the fixed joint's offset turning
// with the modal rotation at point i.
TEST(Constraints, EveryJointOnFlexibleBodiesMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  for (JointType t : {JointType::Spherical, JointType::Fixed, JointType::Universal, JointType::Cylindrical,
                      JointType::Prismatic})
    for (unsigned s = 0; s < 3; ++s) checkJoint(makeJoint(t, rng), false, false, 60 + s, 3);
  for (unsigned s = 0; s < 3; ++s) {
    const Joint j = makeJoint(JointType::Revolute, rng);
    checkJoint(j, false, false, 70 + s, 3);
    checkJoint(j, true, false, 80 + s, 3);
    checkJoint(j, false, true, 90 + s, 3);
  }
}

// A weld captured on deformed flexible bodies holds exactly the captured
// pose: the offset is stored in body i's joint frame F_i = A_i (I + (Theta w)~)
// and the rotation as F_i^-1 F_j^-T, the dual basis of j's joint frame (F is
// orthonormal only to first order; R = F_i^-1 F_j left rows of the order of
// |Theta w|^2, 2e-3 to 7e-2 here). Moving body i's modes then moves the weld point
// with the modal rotation: x_j = x_i + F_i o.
TEST(Constraints, FixedJointOnFlexibleBodiesHoldsTheCapturedPose) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  const int nm = 3;
  auto randomMatrix = [&](int rows, int cols, double scale) {
    Eigen::MatrixXd m(rows, cols);
    for (int k = 0; k < m.size(); ++k) m.data()[k] = scale * u(rng);
    return m;
  };
  for (unsigned trial = 0; trial < 5; ++trial) {
    Joint jt = makeJoint(JointType::Fixed, rng);
    jt.shapes_i.psi = randomMatrix(3, nm, 1.0);
    jt.shapes_i.theta = randomMatrix(3, nm, 1.0);
    jt.shapes_j.psi = randomMatrix(3, nm, 1.0);
    jt.shapes_j.theta = randomMatrix(3, nm, 1.0);
    BodyPose bi = randomMotion(rng).at(0.0), bj = randomMotion(rng).at(0.0);
    bi.modal = randomMatrix(nm, 1, 0.3);
    bj.modal = randomMatrix(nm, 1, 0.3);
    bi.modal_rate = bj.modal_rate = Eigen::VectorXd::Zero(nm);
    JointRuntime rt;
    captureFixed(jt, rt, bi, bj);
    ConstraintRows r;
    jointConstraints(jt, rt, bi, bj, 0.0, r);
    ASSERT_EQ(r.size(), 6);
    EXPECT_LT(r.phi.cwiseAbs().maxCoeff(), 1e-14) << trial;
    // The former capture R = F_i^-1 F_j: rows of order |Theta w|^2.
    JointRuntime old = rt;
    auto frame = [](const BodyPose& b, const Eigen::MatrixXd& th) {
      return Eigen::Matrix3d(b.A * (Eigen::Matrix3d::Identity() + fc::skew(th * b.modal)));
    };
    old.fixed_rotation = frame(bi, jt.shapes_i.theta).inverse() * frame(bj, jt.shapes_j.theta);
    ConstraintRows ro;
    jointConstraints(jt, old, bi, bj, 0.0, ro);
    std::printf("[   info   ] weld captured on deformed bodies: rows %.1e (former capture %.1e)\n",
                r.phi.cwiseAbs().maxCoeff(), ro.phi.tail<3>().cwiseAbs().maxCoeff());
    // Deform body i further: the weld point moves with the modal rotation at
    // point i, x_j = x_i + F_i o (it followed A_i only, x_i + A_i o, before).
    bi.modal += randomMatrix(nm, 1, 0.1);
    jointConstraints(jt, rt, bi, bj, 0.0, r);
    const Eigen::Matrix3d Fi = frame(bi, jt.shapes_i.theta);
    const Vector3d xi = bi.r + bi.A * (jt.point_i + jt.shapes_i.psi * bi.modal);
    const Vector3d xj = bj.r + bj.A * (jt.point_j + jt.shapes_j.psi * bj.modal);
    EXPECT_LT((r.phi.head<3>() - (xj - xi - Fi * rt.fixed_offset)).norm(), 1e-14) << trial;
    EXPECT_GT((Fi * rt.fixed_offset - bi.A * rt.fixed_offset).norm(), 1e-3) << trial;  // the test can tell
  }
}

TEST(Constraints, CapturedJointsHoldTheCapturedPose) {
  std::mt19937 rng(4);
  const Motion mi = randomMotion(rng), mj = randomMotion(rng);
  for (JointType t : {JointType::Fixed, JointType::Prismatic, JointType::Revolute}) {
    Joint jt = makeJoint(t, rng);
    if (t != JointType::Fixed) jt.point_j = jt.point_i;  // a consistent joint for the point rows
    JointRuntime rt;
    rt.locked = t == JointType::Revolute;
    const BodyPose bi = mi.at(0.4), bj = mj.at(0.4);
    captureFixed(jt, rt, bi, bj);
    captureLock(jt, rt, bi, bj);
    ConstraintRows r;
    jointConstraints(jt, rt, bi, bj, 0.4, r);
    // The rotational rows (and for the fixed joint, all rows) vanish at capture.
    const int from = t == JointType::Fixed ? 0 : r.size() - 1;
    EXPECT_LT(r.phi.tail(r.size() - from).cwiseAbs().maxCoeff(), 1e-14) << int(t);
  }
}

TEST(Constraints, RevoluteAngleIsTheRelativeRotationAboutTheAxis) {
  Joint jt;
  jt.type = JointType::Revolute;
  jt.axis_i = jt.axis_j = Vector3d(0.3, -0.5, 0.8).normalized();
  BodyPose bi, bj;
  bi.A = fc::expRotation(Vector3d(0.2, 0.1, -0.4));
  for (double angle : {-3.0, -1.0, 0.0, 0.5, 2.5}) {
    bj.A = bi.A * fc::expRotation(angle * jt.axis_i);
    JointRuntime rt;
    rt.last_angle = angle;  // unwrapping reference near the answer
    rt.angle_offset = 0.0;
    const double raw0 = rawRevoluteAngle(jt, bi, bi);  // 0 for the same pose
    EXPECT_NEAR(raw0, 0.0, 1e-14);
    EXPECT_NEAR(revoluteAngle(jt, rt, bi, bj), angle, 1e-12);
  }
  // Unwrapping: 3 full turns plus 0.5 rad reads continuously from a reference near it.
  JointRuntime rt;
  rt.last_angle = 6 * M_PI + 0.4;
  bj.A = bi.A * fc::expRotation(0.5 * jt.axis_i);
  EXPECT_NEAR(revoluteAngle(jt, rt, bi, bj), 6 * M_PI + 0.5, 1e-12);
}

// The gradient of the revolute angle that the rotational spring applies its
// torque through (Q = -M g^T): on flexible bodies with large modal rotations
// (|Theta w| ~ 0.5 rad, where the first-order modal rotation I + (Theta w)~ is
// far from orthonormal) g v equals the central difference of the angle
// along the motion, and revoluteRate is the same number.
TEST(Constraints, RevoluteAngleJacobianMatchesFiniteDifferencesOnFlexibleBodies) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const int nm = 3;
  auto randomShapes = [&] {
    Eigen::MatrixXd m(3, nm);
    for (int k = 0; k < m.size(); ++k) m.data()[k] = u(rng);
    return m;
  };
  for (unsigned trial = 0; trial < 6; ++trial) {
    Joint jt = makeJoint(JointType::Revolute, rng);
    jt.shapes_i.psi = randomShapes();
    jt.shapes_i.theta = randomShapes();
    jt.shapes_j.psi = randomShapes();
    jt.shapes_j.theta = randomShapes();
    const Motion mi = randomMotion(rng), mj = randomMotion(rng);
    Eigen::VectorXd wi0(nm), wj0(nm), wid(nm), wjd(nm);
    for (int k = 0; k < nm; ++k) {
      wi0(k) = 0.3 * u(rng);
      wj0(k) = 0.3 * u(rng);
      wid(k) = u(rng);
      wjd(k) = u(rng);
    }
    auto at = [&](const Motion& m, const Eigen::VectorXd& w0, const Eigen::VectorXd& wd, double t) {
      BodyPose b = m.at(t);
      b.modal = w0 + wd * t;
      b.modal_rate = wd;
      return b;
    };
    const BodyPose bi = at(mi, wi0, wid, 0.0), bj = at(mj, wj0, wjd, 0.0);
    Eigen::RowVectorXd gi, gj;
    revoluteAngleJacobian(jt, bi, bj, gi, gj);
    ASSERT_EQ(gi.size(), 6 + nm);
    ASSERT_EQ(gj.size(), 6 + nm);
    Eigen::VectorXd vi(6 + nm), vj(6 + nm);
    vi << mi.rd, mi.w0, wid;
    vj << mj.rd, mj.w0, wjd;
    const double h = 1e-5;
    const double fd = (rawRevoluteAngle(jt, at(mi, wi0, wid, h), at(mj, wj0, wjd, h)) -
                       rawRevoluteAngle(jt, at(mi, wi0, wid, -h), at(mj, wj0, wjd, -h))) /
                      (2 * h);
    const double g = gi.dot(vi) + gj.dot(vj);
    // Central difference: h^2 = 1e-10 times O(1) third derivatives, rounding
    // eps / h ~ 2e-11.
    EXPECT_NEAR(g, fd, 1e-8) << trial;
    EXPECT_NEAR(revoluteRate(jt, bi, bj), g, 1e-13) << trial;
    // Each block separately (only one body moving), so no error cancels.
    const double fd_i = (rawRevoluteAngle(jt, at(mi, wi0, wid, h), bj) -
                         rawRevoluteAngle(jt, at(mi, wi0, wid, -h), bj)) / (2 * h);
    EXPECT_NEAR(gi.dot(vi), fd_i, 1e-8) << trial;
  }
}

// Rigid bodies with the revolute joint assembled: the gradient is the torque
// pair of before, [0, -A_i^T n] on i and [0, A_j^T n] on j.
TEST(Constraints, RevoluteAngleJacobianOnRigidBodiesIsTheAxisTorque) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1, 1);
  for (unsigned trial = 0; trial < 5; ++trial) {
    Joint jt = makeJoint(JointType::Revolute, rng);
    const Motion mi = randomMotion(rng);
    const BodyPose bi = mi.at(0.0);
    // Body j turned so that its axis lies on body i's, then about it.
    BodyPose bj = randomMotion(rng).at(0.0);
    const Vector3d n = bi.A * jt.axis_i;
    const Eigen::Quaterniond align = Eigen::Quaterniond::FromTwoVectors(bj.A * jt.axis_j, n);
    bj.A = fc::expRotation(u(rng) * 3.0 * n) * align.toRotationMatrix() * bj.A;
    ASSERT_LT((bj.A * jt.axis_j - n).norm(), 1e-14);
    Eigen::RowVectorXd gi, gj;
    revoluteAngleJacobian(jt, bi, bj, gi, gj);
    Eigen::Matrix<double, 1, 6> ei = Eigen::Matrix<double, 1, 6>::Zero(), ej = ei;
    ei.tail<3>() = -(bi.A.transpose() * n).transpose();
    ej.tail<3>() = (bj.A.transpose() * n).transpose();
    EXPECT_LT((gi - ei).lpNorm<Eigen::Infinity>(), 1e-14) << trial;
    EXPECT_LT((gj - ej).lpNorm<Eigen::Infinity>(), 1e-14) << trial;
  }
}

}  // namespace
}  // namespace fc::mbs
