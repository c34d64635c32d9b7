#pragma once
// Hashin's ply failure criteria (Z. Hashin, "Failure criteria for
// unidirectional fiber composites", J. Appl. Mech. 47 (1980) 329-334, the 3D
// forms of his eqs. (21)-(26), as VABS's recovery uses them), shared by
// section-prep's recovery and mbs-run's shell and beam ply outputs. Theory,
// the transverse shear strength used and how this differs from VABS:
// docs/stresses.md, "Hashin".
#include <Eigen/Dense>

#include "common/materials.h"

namespace fc {

// The four Hashin mode indices of one stress state: each the left-hand side of
// Hashin's quadratic criterion (failure of that mode at 1), 0 for the mode the
// sign of the stress does not select (fibre: sign of s11; matrix: of s22 + s33).
struct HashinIndices {
  double fibre_tension = 0, fibre_compression = 0, matrix_tension = 0, matrix_compression = 0;
  double max() const;
};

// The transverse shear strength S_T (Hashin's tau_T, the strength for s23)
// that the criteria use: Yc / 2, because the project's materials carry the
// five in-plane strengths only (contracts.md). With it the matrix compression
// criterion's linear term [(Yc / 2 S_T)^2 - 1] (s22 + s33) / Yc vanishes; a
// uniaxial s22 = -Yc still fails exactly at 1 whatever S_T is.
double hashinTransverseShear(const PlyStrength& st);

// Hashin's 3D criteria from the stresses in material axes, Voigt order
// [s11, s22, s33, s23, s13, s12] (1 the fibre), with the axial shear strength
// S_A = S12 for both s12 and s13 (transverse isotropy about the fibre):
//   fibre tension     (s11 >= 0): (s11/Xt)^2 + (s12^2 + s13^2)/S_A^2
//   fibre compression (s11 < 0):  (s11/Xc)^2
//   matrix tension    (s22 + s33 >= 0): (s22 + s33)^2/Yt^2 + (s23^2 - s22 s33)/S_T^2 + (s12^2 + s13^2)/S_A^2
//   matrix compression (s22 + s33 < 0): [(Yc/(2 S_T))^2 - 1](s22 + s33)/Yc + (s22 + s33)^2/(4 S_T^2)
//                                       + (s23^2 - s22 s33)/S_T^2 + (s12^2 + s13^2)/S_A^2
HashinIndices hashinIndices(const PlyStrength& st, const Eigen::Matrix<double, 6, 1>& s);

// The plane-stress form (s33 = s23 = s13 = 0) from [s11, s22, t12], as the
// shells' ply stresses and the beams' ply outputs carry them.
HashinIndices hashinIndices(const PlyStrength& st, const Eigen::Vector3d& s);

}  // namespace fc
