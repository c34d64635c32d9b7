#include "fe-prep/body_inertia.h"

namespace fc::feprep {

RigidProperties& RigidProperties::operator+=(const RigidProperties& o) {
  mass += o.mass;
  first_moment += o.first_moment;
  second_moment += o.second_moment;
  return *this;
}

namespace {

void addTriangle(RigidProperties& p, const Mesh& mesh, const std::array<long, 3>& t, const LaminateStiffness& lam) {
  {
    const Eigen::Vector3d x0 = mesh.nodes.row(t[0]), x1 = mesh.nodes.row(t[1]), x2 = mesh.nodes.row(t[2]);
    const Eigen::Vector3d cr = (x1 - x0).cross(x2 - x0);
    const double A = 0.5 * cr.norm();
    const Eigen::Vector3d n = cr.normalized();
    const Eigen::Vector3d c = (x0 + x1 + x2) / 3.0;
    const Eigen::Matrix3d XX = A / 12.0 * (x0 * x0.transpose() + x1 * x1.transpose() + x2 * x2.transpose() +
                                           9.0 * c * c.transpose());
    // p = x + z n: int rho p p^T = rho_A int x x^T + f (int x n^T + n int x^T) + r A n n^T
    p.mass += lam.mass_per_area * A;
    p.first_moment += lam.mass_per_area * A * c + lam.first_moment * A * n;
    p.second_moment += lam.mass_per_area * XX +
                       lam.first_moment * A * (c * n.transpose() + n * c.transpose()) +
                       lam.rotary_per_area * A * n * n.transpose();
  }
}

void addBeam(RigidProperties& p, const Mesh& mesh, const std::array<long, 2>& b, const Eigen::Matrix<double, 6, 6>& Ms,
             const Eigen::Vector3d& section_x2) {
  const double mu = Ms(0, 0);
  const double x3c = Ms(0, 4) / mu, x2c = -Ms(0, 5) / mu;
  const double i22 = Ms(4, 4), i33 = Ms(5, 5), i23 = -Ms(4, 5);
  {
    const Eigen::Vector3d a = mesh.nodes.row(b[0]), c = mesh.nodes.row(b[1]);
    const double L = (c - a).norm();
    const Eigen::Vector3d e1 = (c - a) / L;
    const Eigen::Vector3d e2 = (section_x2 - section_x2.dot(e1) * e1).normalized();
    const Eigen::Vector3d e3 = e1.cross(e2);
    const Eigen::Vector3d d = x2c * e2 + x3c * e3;  // mass centre offset in the section
    const Eigen::Vector3d m = 0.5 * (a + c);
    // Along the axis r(s) is linear: int r r^T ds = L (m m^T + (c - a)(c - a)^T / 12).
    const Eigen::Matrix3d RR = L * (m * m.transpose() + (c - a) * (c - a).transpose() / 12.0);
    const Eigen::Matrix3d Q = i33 * e2 * e2.transpose() + i22 * e3 * e3.transpose() +
                              i23 * (e2 * e3.transpose() + e3 * e2.transpose());
    p.mass += mu * L;
    p.first_moment += mu * L * (m + d);
    p.second_moment += mu * RR + mu * L * (m * d.transpose() + d * m.transpose()) + L * Q;
  }
}

}  // namespace

RigidProperties shellProperties(const Mesh& mesh, const LaminateStiffness& lam) {
  RigidProperties p;
  for (const auto& t : mesh.triangles) addTriangle(p, mesh, t, lam);
  return p;
}

RigidProperties beamProperties(const Mesh& mesh, const Eigen::Matrix<double, 6, 6>& Ms,
                               const Eigen::Vector3d& section_x2) {
  RigidProperties p;
  for (const auto& b : mesh.beams) addBeam(p, mesh, b, Ms, section_x2);
  return p;
}

RigidProperties meshProperties(const Mesh& mesh, bool reference_surface_only) {
  RigidProperties shells, beams, points;
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
    LaminateStiffness lam = mesh.shellProperty(static_cast<long>(e)).laminate;
    if (reference_surface_only) {
      lam.first_moment = 0.0;  // through-thickness terms belong to the rotary inertias
      lam.rotary_per_area = 0.0;
    }
    addTriangle(shells, mesh, mesh.triangles[e], lam);
  }
  for (std::size_t e = 0; e < mesh.beams.size(); ++e) {
    const Eigen::Matrix<double, 6, 6>& Ms = mesh.beamProperty(static_cast<long>(e)).Ms;
    Eigen::Matrix<double, 6, 6> axis = Eigen::Matrix<double, 6, 6>::Zero();
    axis(0, 0) = Ms(0, 0);
    addBeam(beams, mesh, mesh.beams[e], reference_surface_only ? axis : Ms, mesh.beam_x2[e]);
  }
  for (const auto& m : mesh.point_masses) {
    // At its point (not its node): E = m p p^T + (tr(J)/2 I - J), J about the point.
    const Eigen::Vector3d x = reference_surface_only ? Eigen::Vector3d(mesh.nodes.row(m.node).transpose()) : m.point;
    points.mass += m.mass;
    points.first_moment += m.mass * x;
    points.second_moment += m.mass * x * x.transpose();
    if (!reference_surface_only)
      points.second_moment += 0.5 * m.inertia.trace() * Eigen::Matrix3d::Identity() - m.inertia;
  }
  RigidProperties p;
  if (!mesh.triangles.empty()) p = shells;
  if (!mesh.beams.empty()) p += beams;
  if (!mesh.point_masses.empty()) p += points;
  return p;
}

}  // namespace fc::feprep
