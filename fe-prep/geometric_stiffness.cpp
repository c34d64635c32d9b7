#include "fe-prep/geometric_stiffness.h"

#include <stdexcept>

#include "fe-prep/elements/beam_element.h"
#include "fe-prep/elements/beam_geometric_stiffness.h"
#include "fe-prep/elements/shell_geometric_stiffness.h"
#include "fe-prep/static_response.h"

namespace fc::feprep {

Eigen::Matrix<double, 3, kInertialCases> inertialCaseAccelerations(const Eigen::Vector3d& s) {
  Eigen::Matrix<double, 3, kInertialCases> a = Eigen::Matrix<double, 3, kInertialCases>::Zero();
  a.leftCols<3>().setIdentity();  // a0
  // omega x (omega x s) = omega (omega . s) - s |omega|^2, split into its products.
  for (int i = 0; i < 3; ++i) {
    a.col(3 + i) = -s;
    a(i, 3 + i) += s(i);
  }
  a.col(6) << s.y(), s.x(), 0.0;  // w_x w_y
  a.col(7) << 0.0, s.z(), s.y();  // w_y w_z
  a.col(8) << s.z(), 0.0, s.x();  // w_z w_x
  // alpha x s
  for (int i = 0; i < 3; ++i) a.col(9 + i) = Eigen::Vector3d::Unit(i).cross(s);
  return a;
}

Eigen::MatrixXd inertialLoadCases(const Eigen::MatrixXd& nodes, const Eigen::VectorXd& lumped) {
  const long n = nodes.rows();
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(6 * n, kInertialCases);
  for (long k = 0; k < n; ++k) {
    const Eigen::Vector3d s = nodes.row(k).transpose();
    f.middleRows<3>(6 * k) = -(lumped.segment<3>(6 * k).asDiagonal() * inertialCaseAccelerations(s));
  }
  return f;
}

Eigen::MatrixXd beamAxialForces(const Mesh& mesh, const Eigen::Vector3d& section_x2, const Matrix6d& Ks,
                                const Eigen::MatrixXd& u) {
  const long ne = static_cast<long>(mesh.beams.size());
  Eigen::MatrixXd N(ne, u.cols());
  for (long e = 0; e < ne; ++e) {
    const auto& b = mesh.beams[static_cast<std::size_t>(e)];
    const Eigen::Vector3d xa = mesh.nodes.row(b[0]).transpose(), xb = mesh.nodes.row(b[1]).transpose();
    // The stiffness alone matters here; a unit section mass keeps the element's checks quiet.
    Matrix6d Ms = Matrix6d::Identity();
    const fe::Matrix12d K = fe::timoshenkoBeam(xa, xb, section_x2, Ks, Ms).K;
    for (long c = 0; c < u.cols(); ++c) {
      fe::Vector12d ue;
      ue << u.col(c).segment<6>(6 * b[0]), u.col(c).segment<6>(6 * b[1]);
      N(e, c) = fe::beamAxialForce(xa, xb, K, ue);
    }
  }
  return N;
}

std::vector<Eigen::MatrixXd> projectBeamGeometricStiffness(const Mesh& mesh, const Eigen::Vector3d& section_x2,
                                                           const Matrix6d& Ks, const Eigen::MatrixXd& axial,
                                                           const Eigen::MatrixXd& shapes) {
  const long nm = shapes.cols();
  std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(axial.cols()), Eigen::MatrixXd::Zero(nm, nm));
  Eigen::MatrixXd Pe(12, nm);
  for (std::size_t e = 0; e < mesh.beams.size(); ++e) {
    const auto& b = mesh.beams[e];
    const Eigen::Vector3d xa = mesh.nodes.row(b[0]).transpose(), xb = mesh.nodes.row(b[1]).transpose();
    Pe << shapes.middleRows(6 * b[0], 6), shapes.middleRows(6 * b[1], 6);
    // Linear in N: project the unit-force matrix once, scale per case.
    const Eigen::MatrixXd unit = Pe.transpose() * fe::beamGeometricStiffness(xa, xb, section_x2, Ks, 1.0) * Pe;
    for (long c = 0; c < axial.cols(); ++c) out[static_cast<std::size_t>(c)] += axial(static_cast<long>(e), c) * unit;
  }
  for (auto& k : out) k = 0.5 * (k + k.transpose()).eval();
  return out;
}

namespace {

Eigen::Matrix3d triangleCoordinates(const Mesh& mesh, std::size_t e) {
  Eigen::Matrix3d xyz;
  for (int i = 0; i < 3; ++i) xyz.row(i) = mesh.nodes.row(mesh.triangles[e][static_cast<std::size_t>(i)]);
  return xyz;
}

}  // namespace

Eigen::MatrixXd shellMembraneForces(const Mesh& mesh, const StressStiffnessModel& model, const Eigen::MatrixXd& u) {
  const long ne = static_cast<long>(mesh.triangles.size());
  Eigen::MatrixXd N(3 * ne, u.cols());
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
  for (long e = 0; e < ne; ++e) {
    const auto& t = mesh.triangles[static_cast<std::size_t>(e)];
    const Eigen::Matrix<double, 6, 18> G = fe::shellStrainOperator(triangleCoordinates(mesh, static_cast<std::size_t>(e)),
                                                                   *model.laminate, model.kind, model.material_x, centre);
    Eigen::Matrix<double, 3, 6> AB;
    AB << model.laminate->A, model.laminate->B;
    const Eigen::Matrix<double, 3, 18> NG = AB * G;  // shellMembraneForces, once for all cases
    for (long c = 0; c < u.cols(); ++c) {
      fe::Vector18d q;
      q << u.col(c).segment<6>(6 * t[0]), u.col(c).segment<6>(6 * t[1]), u.col(c).segment<6>(6 * t[2]);
      N.block<3, 1>(3 * e, c) = NG * q;
    }
  }
  return N;
}

std::vector<Eigen::MatrixXd> projectShellGeometricStiffness(const Mesh& mesh, const StressStiffnessModel& model,
                                                            const Eigen::MatrixXd& membrane,
                                                            const Eigen::MatrixXd& shapes) {
  const long nm = shapes.cols();
  std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(membrane.cols()), Eigen::MatrixXd::Zero(nm, nm));
  Eigen::MatrixXd Pe(18, nm);
  for (std::size_t e = 0; e < mesh.triangles.size(); ++e) {
    const auto& t = mesh.triangles[e];
    Pe << shapes.middleRows(6 * t[0], 6), shapes.middleRows(6 * t[1], 6), shapes.middleRows(6 * t[2], 6);
    // Linear in N: project the three unit matrices once, combine per case.
    const std::array<fe::Matrix18d, 3> units =
        fe::shellGeometricStiffnessUnits(triangleCoordinates(mesh, e), *model.laminate, model.kind, model.material_x);
    const long row = 3 * static_cast<long>(e);
    for (int j = 0; j < 3; ++j) {
      const Eigen::MatrixXd unit = Pe.transpose() * units[static_cast<std::size_t>(j)] * Pe;
      for (long c = 0; c < membrane.cols(); ++c) out[static_cast<std::size_t>(c)] += membrane(row + j, c) * unit;
    }
  }
  for (auto& k : out) k = 0.5 * (k + k.transpose()).eval();
  return out;
}

std::vector<Eigen::MatrixXd> loadCaseGeometricStiffness(Comm comm, const Mesh& mesh, const DofMap& map, SystemMatrix K,
                                                        const Eigen::MatrixXd& loads, const StressStiffnessModel& model,
                                                        const Eigen::MatrixXd& shapes) {
  return responseGeometricStiffness(mesh, solveStatic(comm, K, map, loads), model, shapes);
}

std::vector<Eigen::MatrixXd> responseGeometricStiffness(const Mesh& mesh, const Eigen::MatrixXd& u,
                                                        const StressStiffnessModel& model, const Eigen::MatrixXd& shapes) {
  const long nm = shapes.cols();
  std::vector<Eigen::MatrixXd> out(static_cast<std::size_t>(u.cols()), Eigen::MatrixXd::Zero(nm, nm));
  auto add = [&](const std::vector<Eigen::MatrixXd>& part) {
    for (std::size_t c = 0; c < out.size(); ++c) out[c] += part[c];
  };
  if (!mesh.beams.empty()) {
    if (!model.Ks) throw std::logic_error("geometric stiffness: beam elements without a section stiffness");
    add(projectBeamGeometricStiffness(mesh, model.section_x2, *model.Ks,
                                      beamAxialForces(mesh, model.section_x2, *model.Ks, u), shapes));
  }
  if (!mesh.triangles.empty()) {
    if (!model.laminate) throw std::logic_error("geometric stiffness: shell elements without a laminate");
    add(projectShellGeometricStiffness(mesh, model, shellMembraneForces(mesh, model, u), shapes));
  }
  return out;
}

std::vector<Eigen::MatrixXd> modalGeometricStiffness(Comm comm, const Mesh& mesh, const DofMap& map, SystemMatrix K,
                                                     const Eigen::VectorXd& lumped, const StressStiffnessModel& model,
                                                     const Eigen::MatrixXd& shapes) {
  return loadCaseGeometricStiffness(comm, mesh, map, K, inertialLoadCases(mesh.nodes, lumped), model, shapes);
}

std::vector<Eigen::MatrixXd> interfaceGeometricStiffness(Comm comm, const Mesh& mesh, const DofMap& map, SystemMatrix K,
                                                         const Eigen::MatrixXd& loads, const StressStiffnessModel& model,
                                                         const Eigen::MatrixXd& shapes) {
  return loadCaseGeometricStiffness(comm, mesh, map, K, loads, model, shapes);
}

}  // namespace fc::feprep
