#pragma once
// Consistent unit systems of input files (an FE model's units), converted to SI
// at read time. A system is named length-mass-time, e.g. "mm-t-s" (millimetre,
// tonne, second: force in N, stress in MPa, density in t/mm^3), the usual
// choice of CalculiX and Abaqus models of metal parts. Each factor is the SI
// value of one file unit; derived quantities follow from the three.
#include <string>
#include <vector>

namespace fc {

struct UnitSystem {
  std::string name;
  double length = 1.0;  // [m] per file length unit
  double mass = 1.0;    // [kg] per file mass unit
  double time = 1.0;    // [s] per file time unit
  double force() const { return mass * length / (time * time); }    // [N] per file force unit
  double energy() const { return force() * length; }                 // [J] per file energy unit
};

// The systems fc::unitSystem knows, SI first.
const std::vector<UnitSystem>& unitSystems();

// The system named `name` (m-kg-s, mm-t-s, mm-kg-ms, mm-g-ms, cm-g-s, m-t-s, in-lbf-s).
// Throws std::invalid_argument listing the known names otherwise.
const UnitSystem& unitSystem(const std::string& name);

}  // namespace fc
