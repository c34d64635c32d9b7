#include "common/units.h"

#include <cmath>
#include <map>
#include <stdexcept>

namespace fc {

namespace {
// lbf = 4.4482216152605 N (exact by definition: 0.45359237 kg x 9.80665 m/s^2).
constexpr double kInch = 0.0254, kFoot = 0.3048, kLbf = 4.4482216152605;
}  // namespace

const std::vector<UnitSystem>& unitSystems() {
  static const std::vector<UnitSystem> systems = {
      {"m-kg-s", 1.0, 1.0, 1.0},
      {"mm-t-s", 1e-3, 1e3, 1.0},      // N, MPa, t/mm^3: the usual FE system in mm
      {"mm-kg-ms", 1e-3, 1.0, 1e-3},   // kN, GPa: crash and impact codes
      {"mm-kg-s", 1e-3, 1.0, 1.0},     // mN, kPa
      {"mm-g-ms", 1e-3, 1e-3, 1e-3},   // N, MPa, g/mm^3
      {"cm-g-s", 1e-2, 1e-3, 1.0},     // dyn
      {"m-t-s", 1.0, 1e3, 1.0},        // kN, kPa, t/m^3
      {"in-lbf-s", kInch, kLbf / kInch, 1.0},  // lbf, psi; mass in slinch (lbf s^2/in), as VABS users
      {"in-lb-s", kInch, kLbf / kInch, 1.0},   // the same, as often written
      {"ft-slug-s", kFoot, kLbf / kFoot, 1.0}, // lbf; mass in slug (lbf s^2/ft)
  };
  return systems;
}

const UnitSystem* findUnitSystem(const std::string& name) {
  for (const UnitSystem& u : unitSystems())
    if (u.name == name) return &u;
  return nullptr;
}

std::vector<std::string> unitSystemNames() {
  std::vector<std::string> n;
  for (const UnitSystem& u : unitSystems()) n.push_back(u.name);
  return n;
}

const UnitSystem& unitSystem(const std::string& name) {
  if (const UnitSystem* u = findUnitSystem(name)) return *u;
  std::string known;
  for (const auto& s : unitSystems()) known += (known.empty() ? "" : ", ") + s.name;
  throw std::invalid_argument("unknown unit system '" + name + "', expected one of " + known);
}

double toSI(const UnitSystem& u, const Dimension& d) {
  return std::pow(u.length, d.length) * std::pow(u.mass, d.mass) * std::pow(u.time, d.time);
}

bool keyDimension(const std::string& key, const std::string& parent_type, Dimension& out) {
  // {length, mass, time} powers.
  static const Dimension kNone{0, 0, 0}, kLength{1, 0, 0}, kMass{0, 1, 0}, kTime{0, 0, 1}, kRate{0, 0, -1},
      kStress{-1, 1, -2}, kDensity{-3, 1, 0}, kInertia{2, 1, 0}, kVelocity{1, 0, -1}, kAcceleration{1, 0, -2},
      kForce{1, 1, -2}, kTorque{2, 1, -2}, kLinearStiffness{0, 1, -2}, kArealMass{-2, 1, 0},
      kModal{1, 0.5, 0}, kModalRate{1, 0.5, -1};
  static const std::map<std::string, Dimension> table = {
      // materials
      {"E", kStress}, {"E1", kStress}, {"E2", kStress}, {"E3", kStress}, {"G12", kStress}, {"G13", kStress},
      {"G23", kStress}, {"C", kStress}, {"Xt", kStress}, {"Xc", kStress}, {"Yt", kStress}, {"Yc", kStress},
      {"S12", kStress}, {"rho", kDensity}, {"density", kDensity},
      {"nu", kNone}, {"nu12", kNone}, {"nu13", kNone}, {"nu23", kNone},
      // lengths: plies, sections, shells, beams, interfaces, geometry
      {"thickness", kLength}, {"diameter", kLength}, {"outer_diameter", kLength}, {"width", kLength},
      {"height", kLength}, {"length", kLength}, {"mesh_size", kLength}, {"size", kLength},
      {"graded_from", kLength}, {"interfaces", kLength}, {"point", kLength}, {"points", kLength},
      {"within", kLength}, {"box", kLength}, {"at", kLength}, {"origin", kLength}, {"position", kLength},
      {"center_of_mass", kLength}, {"free_length", kLength}, {"radius", kLength}, {"geometry", kLength}, {"segment", kLength},
      {"rectangle", kLength},
      // angles, ratios, counts: never converted
      {"angle_deg", kNone}, {"angle", kNone}, {"angle0", kNone}, {"initial_angle", kNone}, {"amplitude", kNone},
      {"phase", kNone}, {"min", kNone}, {"max", kNone}, {"restitution", kNone}, {"axes", kNone},
      {"orientation", kNone}, {"shear_correction", kNone}, {"static_error", kNone}, {"damping_ratio", kNone},
      {"rtol", kNone}, {"atol", kNone}, {"penalty", kNone}, {"stabilization_damping", kNone},
      // mass and inertia
      {"mass", kMass}, {"inertia", kInertia}, {"non_structural_mass", kArealMass},
      // time and rates
      {"t_end", kTime}, {"output_step", kTime}, {"max_step", kTime}, {"time", kTime},
      {"frequency", kRate}, {"max_frequency_hz", kRate}, {"speed", kRate}, {"rate", kRate},
      {"stabilization_frequency", kRate}, {"angular_velocity", kRate},
      // motion and loads
      {"velocity", kVelocity}, {"impact_speed", kVelocity}, {"g", kAcceleration}, {"force", kForce}, {"torque", kTorque}, {"value", kTorque},
      {"stiffness", kLinearStiffness}, {"EI", Dimension{3, 1, -2}},
      {"modal_coordinates", kModal}, {"modal_velocities", kModalRate},
  };
  if (key == "damping") {
    // N s/m for a translational spring-damper, N m s/rad for a rotational one.
    out = parent_type == "translational_spring_damper" ? Dimension{0, 1, -1} : Dimension{2, 1, -1};
    return true;
  }
  auto it = table.find(key);
  if (it == table.end()) return false;
  out = it->second;
  return true;
}

}  // namespace fc
