#pragma once
// Section forces of a reduced flexible beam from its modal coordinates (issue
// 14; theory in docs/mbs-run.md, "Beam section forces"). fe-prep writes, per
// mode j and element e, the section resultants R_ej = [N, V2, V3, T, M2, M3] at
// the element midpoint in its section axes (/stress/section_resultants,
// fc::fe::beamMidpointResultants). The elastic deformation of the body is
// u = sum_j Phi_j q_j, and the resultants are linear in it, so
//   s_e(t) = sum_j R_ej q_j(t)
// (the mode-displacement method: the section forces the retained modes'
// deformation implies; a load the modes cannot represent statically is missed,
// which a Craig-Bampton basis with the loaded points as interfaces avoids).
#include <Eigen/Dense>

namespace fc::mbs {

// resultants: (6 n_elements, n_modes), row 6e + c is component c of element e
// per unit modal coordinate; q: (n_modes). Returns the (6 n_elements) vector
// s, element-major (C order of (n_elements, 6)).
Eigen::VectorXd beamSectionForces(const Eigen::MatrixXd& resultants, const Eigen::VectorXd& q);

// The largest bending moment |(M2, M3)| over the elements of one section-force
// vector (as beamSectionForces returns), and where; and the largest |N| and |T|.
struct SectionForcePeak {
  double bending = 0.0;   // [N m]
  long bending_element = -1;
  double axial = 0.0;     // |N| [N]
  long axial_element = -1;
  double torque = 0.0;    // |T| [N m]
  long torque_element = -1;
};
SectionForcePeak largestSectionForces(const Eigen::VectorXd& forces);

}  // namespace fc::mbs
