#pragma once
// Reader for VABS input files (format of the public VABS manual, versions 3-4):
//   format_flag nlayer | Timoshenko_flag damping_flag thermal_flag |
//   curve_flag oblique_flag trapeze_flag Vlasov_flag | [k1 k2 k3] | [cos cos] |
//   nnode nelem nmate | nodes: id x2 x3 | elements: id n1..n9 |
//   new format (format_flag 1): elem layer theta1, then layers: id material theta3;
//   old format (format_flag 0): elem material theta3 theta1(1..9), theta1(2) = 540
//     meaning "theta1(1) for the whole element", else nodal values;
//   materials: id orth, then E nu (orth 0) | E1 E2 E3 G12 G13 G23 nu12 nu13 nu23
//     (orth 1) | the 21 upper-triangle stiffnesses (orth 2), then the density.
// '!' starts a comment; Fortran exponents (1.0d0) are accepted.
#include <string>

#include "section-prep/section_mesh.h"

namespace fc::section {

struct VabsModel {
  SectionMesh mesh;
  bool timoshenko = true;  // the file's Timoshenko_flag
};

// Bad input raises fc::InputError naming the file, the line and the item.
VabsModel readVabsFile(const std::string& path);
VabsModel parseVabs(const std::string& text, const std::string& name);

// Orthotropic stiffness from engineering constants, without the admissibility
// checks of fc::makeOrthotropic (VABS files carry placeholder materials such as
// E = 10 Pa fillers, which VABS accepts).
Matrix6d orthotropicStiffness(double E1, double E2, double E3, double G12, double G13,
                              double G23, double nu12, double nu13, double nu23);

}  // namespace fc::section
