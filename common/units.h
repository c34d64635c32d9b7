#pragma once
// Consistent unit systems of input files (the `units:` key of a body): each
// base unit's size in SI, and the derived ones a structural model needs. A
// file's value times the factor is the SI value.
#include <optional>
#include <string>
#include <vector>

namespace fc {

struct UnitSystem {
  std::string name;
  double length = 1.0, mass = 1.0, time = 1.0;  // metres, kilograms, seconds per unit
  double force() const { return mass * length / (time * time); }
  double stress() const { return force() / (length * length); }  // also moduli
  double density() const { return mass / (length * length * length); }
  double area() const { return length * length; }
  double inertiaMoment() const { return mass * length * length; }  // kg m^2
};

// m-kg-s, mm-t-s (N, MPa, t/mm^3), mm-kg-ms (kN, GPa), mm-g-ms (N, MPa), m-t-s (kN, kPa) ...;
// nullopt for other names.
std::optional<UnitSystem> unitSystem(const std::string& name);
std::vector<std::string> unitSystemNames();

}  // namespace fc
