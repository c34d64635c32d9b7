#pragma once
// Unit systems of the input files (`units:` at the top of a section, body or scene
// file, and of a file named by `include:`). Every number is converted to SI when it is
// read (fc::InputNode::asDouble), so the physical-range checks of the parsers apply to
// SI values whatever the file's units. docs/units.md lists the systems and which keys
// carry which dimension.
#include <string>
#include <vector>

namespace fc {

// A consistent system: the sizes of its base units in SI (m, kg, s). Force, stress,
// density... follow (an in-lbf-s file's mass unit is the slinch, lbf s^2/in).
struct UnitSystem {
  std::string name;
  double length = 1.0;  // m
  double mass = 1.0;    // kg
  double time = 1.0;    // s
  bool isSI() const { return length == 1.0 && mass == 1.0 && time == 1.0; }
};

// The named systems, SI (m-kg-s) first.
const std::vector<UnitSystem>& unitSystems();

// A named system; nullptr when the name is unknown.
const UnitSystem* findUnitSystem(const std::string& name);

// Powers of length, mass and time of a quantity (stress: -1, 1, -2).
struct Dimension {
  double length = 0, mass = 0, time = 0;
  bool none() const { return length == 0 && mass == 0 && time == 0; }
};

// The SI value of one unit of `d` in system `u` (multiply a file's number by it).
double toSI(const UnitSystem& u, const Dimension& d);

// The dimension of the numbers under input key `key`. `parent_type` is the `type:`
// of the map holding the key ("" if none): a spring-damper's `damping` is N s/m or
// N m s/rad by its type. Returns false for keys the table does not name (their
// numbers take the dimension of the enclosing key, e.g. the interface names under
// `interfaces:` are lengths).
bool keyDimension(const std::string& key, const std::string& parent_type, Dimension& out);

}  // namespace fc
