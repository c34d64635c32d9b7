#include "common/units.h"

namespace fc {
namespace {

// Consistent systems in common use by FE codes (force and stress follow).
const UnitSystem kSystems[] = {
    {"m-kg-s", 1.0, 1.0, 1.0},       // N, Pa, kg/m^3
    {"mm-t-s", 1e-3, 1e3, 1.0},      // N, MPa, t/mm^3 (Nastran and Abaqus aerospace decks)
    {"mm-kg-ms", 1e-3, 1.0, 1e-3},   // kN, GPa, kg/mm^3
    {"mm-g-ms", 1e-3, 1e-3, 1e-3},   // N, MPa, g/mm^3
    {"m-t-s", 1.0, 1e3, 1.0},        // kN, kPa, t/m^3
    {"cm-g-s", 1e-2, 1e-3, 1.0},     // dyn, dyn/cm^2, g/cm^3
};

}  // namespace

std::optional<UnitSystem> unitSystem(const std::string& name) {
  for (const auto& u : kSystems)
    if (u.name == name) return u;
  return std::nullopt;
}

std::vector<std::string> unitSystemNames() {
  std::vector<std::string> n;
  for (const auto& u : kSystems) n.push_back(u.name);
  return n;
}

}  // namespace fc
