#pragma once
// Unit systems of the input files. `units:` at the top of a section, body or scene
// file (and of a file named by `include:`) says which units the file's numbers are in:
// every number is converted to SI when it is read (fc::InputNode::asDouble), so the
// physical-range checks of the parsers apply to SI values whatever the file's units.
// `body.units` names the units of the files a body is built from (a mesh file, a
// Nastran deck, imported matrices). docs/units.md lists the systems and which keys
// carry which dimension.
#include <string>
#include <vector>

namespace fc {

// A consistent system: the sizes of its base units in SI (m, kg, s). Force, stress,
// density... follow (an in-lbf-s file's mass unit is the slinch, lbf s^2/in).
struct UnitSystem {
  std::string name;
  double length = 1.0;  // [m] per file length unit
  double mass = 1.0;    // [kg] per file mass unit
  double time = 1.0;    // [s] per file time unit
  bool isSI() const { return length == 1.0 && mass == 1.0 && time == 1.0; }
  double force() const { return mass * length / (time * time); }         // [N] per file force unit
  double energy() const { return force() * length; }                      // [J]
  double stress() const { return force() / (length * length); }          // [Pa], also moduli
  double density() const { return mass / (length * length * length); }  // [kg/m^3]
  double area() const { return length * length; }                        // [m^2]
  double inertiaMoment() const { return mass * length * length; }        // [kg m^2]
};

// The named systems, SI (m-kg-s) first.
const std::vector<UnitSystem>& unitSystems();
std::vector<std::string> unitSystemNames();

// A named system; nullptr when the name is unknown.
const UnitSystem* findUnitSystem(const std::string& name);

// A named system; throws std::invalid_argument listing the known names otherwise.
const UnitSystem& unitSystem(const std::string& name);

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
