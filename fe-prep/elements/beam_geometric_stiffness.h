#pragma once
// Geometric (stress) stiffness of the two-node Timoshenko beam under a constant
// axial force N (tension positive): the second-order work of N through the
// element's transverse displacements, 1/2 N int (v'^2 + w'^2) dx, with the
// element's cubic transverse interpolation including shear deformation
// (Przemieniecki, Theory of Matrix Structural Analysis, McGraw-Hill 1968,
// sec. 15.2, eq. 15.12 with the shear parameter phi; the phi = 0 form is the
// Euler-Bernoulli consistent matrix N/(30 L) [36 3L -36 3L; 3L 4L^2 -3L -L^2; ...]).
// Per bending plane, DOF (v_a, th_a, v_b, th_b) with th = dv/dx:
//   K_G = N / (L (1+phi)^2) [ a  L/10  -a  L/10; L/10  b L^2  -L/10  -c L^2; ... ]
//   a = 6/5 + 2 phi + phi^2,  b = 2/15 + phi/6 + phi^2/12,  c = 1/30 + phi/6 + phi^2/12,
//   phi = 12 EI / (kGA L^2) from the section compliance (its diagonal entries:
//   a coupled section's bending and shear flexibilities).
// The torsional term N (I_p/A) th1'^2 (Wagner) is left out: it needs the polar
// radius of gyration of the section and stiffens only torsion.
#include <Eigen/Dense>

#include "common/materials.h"
#include "fe-prep/elements/beam_element.h"

namespace fc::fe {

// In the BODY frame, DOF as timoshenkoBeam's ([u1 u2 u3 th1 th2 th3] per node);
// xa, xb, section_x2, Ks as timoshenkoBeam (Ks gives phi per plane).
Matrix12d beamGeometricStiffness(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb,
                                 const Eigen::Vector3d& section_x2, const Matrix6d& Ks, double N);

// The element's axial force (tension positive) from its nodal displacements
// (body frame, 12): the axial component at node b of the end forces K u.
double beamAxialForce(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, const Matrix12d& K,
                      const Vector12d& u);

}  // namespace fc::fe
