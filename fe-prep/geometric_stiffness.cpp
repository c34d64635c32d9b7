#include "fe-prep/geometric_stiffness.h"

#include "fe-prep/elements/beam_element.h"
#include "fe-prep/elements/beam_geometric_stiffness.h"
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

std::vector<Eigen::MatrixXd> modalGeometricStiffness(MPI_Comm comm, const Mesh& mesh, const DofMap& map, Mat K,
                                                     const Eigen::VectorXd& lumped, const Eigen::Vector3d& section_x2,
                                                     const Matrix6d& Ks, const Eigen::MatrixXd& shapes) {
  const Eigen::MatrixXd u = solveStatic(comm, K, map, inertialLoadCases(mesh.nodes, lumped));
  return projectBeamGeometricStiffness(mesh, section_x2, Ks, beamAxialForces(mesh, section_x2, Ks, u), shapes);
}

std::vector<Eigen::MatrixXd> interfaceGeometricStiffness(MPI_Comm comm, const Mesh& mesh, const DofMap& map, Mat K,
                                                         const Eigen::MatrixXd& loads, const Eigen::Vector3d& section_x2,
                                                         const Matrix6d& Ks, const Eigen::MatrixXd& shapes) {
  const Eigen::MatrixXd u = solveStatic(comm, K, map, loads);
  return projectBeamGeometricStiffness(mesh, section_x2, Ks, beamAxialForces(mesh, section_x2, Ks, u), shapes);
}

}  // namespace fc::feprep
