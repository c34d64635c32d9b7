#include "fe-prep/elements/beam_element.h"

#include <stdexcept>

#include "fe-prep/elements/beam_flexibility.h"

namespace fc::fe {
Eigen::Matrix3d beamSectionAxes(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, const Eigen::Vector3d& section_x2,
                                double& L) {
  const Eigen::Vector3d axis = xb - xa;
  L = axis.norm();
  if (!(L > 0.0)) throw std::invalid_argument("beam element: coincident end nodes");
  const Eigen::Vector3d e1 = axis / L;
  const Eigen::Vector3d p = section_x2 - section_x2.dot(e1) * e1;
  // Within ~0.1 degree of the axis the orthogonalised x2 is dominated by roundoff.
  if (p.norm() < 1e-3 * section_x2.norm() || !(section_x2.norm() > 0.0))
    throw std::invalid_argument("beam element: section_x2 is parallel to the beam axis");
  const Eigen::Vector3d e2 = p.normalized();
  const Eigen::Vector3d e3 = e1.cross(e2);
  Eigen::Matrix3d R;
  R.row(0) = e1.transpose();
  R.row(1) = e2.transpose();
  R.row(2) = e3.transpose();
  return R;
}

Matrix12d beamBlockRotation(const Eigen::Matrix3d& R) {
  Matrix12d T = Matrix12d::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  return T;
}

BeamMatrices timoshenkoBeam(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                            const Eigen::Vector3d& section_x2, const Matrix6d& Ks,
                            const Matrix6d& Ms) {
  double L = 0.0;
  const Eigen::Matrix3d R = beamSectionAxes(xa, xb, section_x2, L);  // v_local = R v_body
  const Matrix12d T = beamBlockRotation(R);

  const UniformBeam beam(Ks, L);
  BeamMatrices out;
  out.K = T.transpose() * beam.stiffness() * T;
  out.M = T.transpose() * beam.consistentMass(Ms) * T;

  // Lumped: half the element at each end; the section's rotary inertia per
  // length (lower-right block of Ms) times L/2, its diagonal in body axes.
  const double mu = Ms(0, 0);
  if (!(mu > 0.0)) throw std::invalid_argument("beam element: mass per length must be positive");
  const Eigen::Matrix3d J = R.transpose() * Ms.block<3, 3>(3, 3) * R;
  for (int n = 0; n < 2; ++n) {
    for (int d = 0; d < 3; ++d) {
      out.lumped(6 * n + d) = 0.5 * mu * L;
      out.lumped(6 * n + 3 + d) = 0.5 * L * J(d, d);
    }
  }
  return out;
}

Eigen::Matrix<double, 6, 12> beamMidpointResultants(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                                                    const Eigen::Vector3d& section_x2, const Matrix6d& Ks) {
  double L = 0.0;
  const Eigen::Matrix3d R = beamSectionAxes(xa, xb, section_x2, L);
  return UniformBeam(Ks, L).sectionForces(0.5 * L) * beamBlockRotation(R);
}

Eigen::MatrixXd beamModalResultants(const Eigen::MatrixXd& nodes, const std::vector<std::array<long, 2>>& beams,
                                    const Eigen::Vector3d& section_x2, const Matrix6d& Ks,
                                    const Eigen::MatrixXd& shapes) {
  const long ne = static_cast<long>(beams.size());
  Eigen::MatrixXd R(6 * ne, shapes.cols());
  Eigen::MatrixXd q(12, shapes.cols());
  for (long e = 0; e < ne; ++e) {
    const auto& b = beams[static_cast<std::size_t>(e)];
    q.topRows<6>() = shapes.middleRows<6>(6 * b[0]);
    q.bottomRows<6>() = shapes.middleRows<6>(6 * b[1]);
    R.middleRows<6>(6 * e) =
        beamMidpointResultants(nodes.row(b[0]).transpose(), nodes.row(b[1]).transpose(), section_x2, Ks) * q;
  }
  return R;
}

}  // namespace fc::fe
