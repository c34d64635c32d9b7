#include "common/units.h"

#include <stdexcept>

namespace fc {

const std::vector<UnitSystem>& unitSystems() {
  // in-lbf-s: the mass unit is lbf s^2/in (the "slinch", 175.126836 kg) so that
  // force comes out in lbf: 0.0254 m and 4.4482216152605 N exactly by definition.
  static const std::vector<UnitSystem> systems = {
      {"m-kg-s", 1.0, 1.0, 1.0},
      {"mm-t-s", 1e-3, 1e3, 1.0},
      {"mm-kg-ms", 1e-3, 1.0, 1e-3},
      {"mm-g-ms", 1e-3, 1e-3, 1e-3},
      {"cm-g-s", 1e-2, 1e-3, 1.0},
      {"m-t-s", 1.0, 1e3, 1.0},
      {"in-lbf-s", 0.0254, 4.4482216152605 / 0.0254, 1.0},
  };
  return systems;
}

const UnitSystem& unitSystem(const std::string& name) {
  for (const auto& s : unitSystems())
    if (s.name == name) return s;
  std::string known;
  for (const auto& s : unitSystems()) known += (known.empty() ? "" : ", ") + s.name;
  throw std::invalid_argument("unknown unit system '" + name + "', expected one of " + known);
}

}  // namespace fc
