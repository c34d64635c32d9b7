#include "mbs-run/mechanics/flexible/section_forces.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fc::mbs {

Eigen::VectorXd beamSectionForces(const Eigen::MatrixXd& resultants, const Eigen::VectorXd& q) {
  if (resultants.rows() % 6 != 0 || resultants.cols() != q.size())
    throw std::invalid_argument("beam section forces: resultants are (" + std::to_string(resultants.rows()) + ", " +
                                std::to_string(resultants.cols()) + "), expected (6 n_elements, " +
                                std::to_string(q.size()) + ")");
  return resultants * q;
}

SectionForcePeak largestSectionForces(const Eigen::VectorXd& s) {
  SectionForcePeak p;
  for (long e = 0; e < s.size() / 6; ++e) {
    const double m = std::hypot(s(6 * e + 4), s(6 * e + 5));
    if (m > p.bending) p.bending = m, p.bending_element = e;
    if (std::abs(s(6 * e)) > p.axial) p.axial = std::abs(s(6 * e)), p.axial_element = e;
    if (std::abs(s(6 * e + 3)) > p.torque) p.torque = std::abs(s(6 * e + 3)), p.torque_element = e;
  }
  return p;
}

}  // namespace fc::mbs
