// `units:` on input files: every number converted to SI by its key's dimension
// when read, the range checks applied to the SI value (common/units.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "common/input.h"
#include "common/materials.h"

using fc::InputError;
using fc::InputNode;

namespace {

// Exact conversion factors by definition (NIST SP 811): inch 0.0254 m, lbf 4.4482216152605 N.
constexpr double kIn = 0.0254, kLbf = 4.4482216152605, kSlinch = kLbf / kIn;

std::string errorText(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

TEST(Units, NoUnitsKeyIsSI) {
  const auto root = InputNode::loadString("materials: {al: {type: isotropic, E: 70e9, nu: 0.33, rho: 2700}}\n");
  EXPECT_EQ(root.units(), nullptr);
  EXPECT_EQ(root["materials"]["al"]["E"].asDouble(), 70e9);
}

TEST(Units, MillimetreTonneSecondToSI) {
  const auto root = InputNode::loadString(
      "units: mm-t-s\n"
      "materials: {al: {type: isotropic, E: 70000, nu: 0.33, rho: 2.7e-9}}\n"
      "body: {shell: {rectangle: {length: 2000, width: 1300}, mesh: {triangles: 86, size: 50}}, modes: 14,\n"
      "       interfaces: {S1: [0, 100, 70.5], P: {point: [1000, 0, 0], nodes: {within: 50}}}}\n");
  ASSERT_NE(root.units(), nullptr);
  EXPECT_EQ(root.units()->name, "mm-t-s");
  // MPa -> Pa, t/mm^3 -> kg/m^3, mm -> m; ratios and counts untouched.
  EXPECT_DOUBLE_EQ(root["materials"]["al"]["E"].asDouble(), 70e9);
  EXPECT_DOUBLE_EQ(root["materials"]["al"]["rho"].asDouble(), 2700.0);
  EXPECT_DOUBLE_EQ(root["materials"]["al"]["nu"].asDouble(), 0.33);
  const auto shell = root["body"]["shell"];
  EXPECT_DOUBLE_EQ(shell["rectangle"]["length"].asDouble(), 2.0);
  EXPECT_DOUBLE_EQ(shell["mesh"]["size"].asDouble(), 0.05);
  EXPECT_EQ(shell["mesh"]["triangles"].asInt(), 86);
  EXPECT_EQ(root["body"]["modes"].asInt(), 14);
  // Interface names take the dimension of `interfaces:` (lengths).
  EXPECT_DOUBLE_EQ(root["body"]["interfaces"]["S1"].asVector(3)(2), 0.0705);
  EXPECT_DOUBLE_EQ(root["body"]["interfaces"]["P"]["point"].asVector(3)(0), 1.0);
  EXPECT_DOUBLE_EQ(root["body"]["interfaces"]["P"]["nodes"]["within"].asDouble(), 0.05);
  // The material library reads the SI values (its range checks pass).
  const auto lib = fc::readMaterials(root["materials"]);
  EXPECT_DOUBLE_EQ(lib.at("al").E1, 70e9);
  EXPECT_DOUBLE_EQ(lib.at("al").rho, 2700.0);
}

TEST(Units, InchPoundSlinchDensityPassesTheRangeCheckAfterConversion) {
  const char* deck = "materials: {as4: {type: isotropic, E: 2.059e7, nu: 0.3, rho: 1.353e-4}}\n";
  // Without units, 1.353e-4 kg/m^3 is a unit slip and refused.
  const std::string e = errorText([&] { fc::readMaterials(InputNode::loadString(deck, "a.yaml")["materials"]); });
  EXPECT_NE(e.find("rho"), std::string::npos) << e;
  // In in-lbf-s it is 1.353e-4 slinch/in^3 = 1445.9 kg/m^3, and psi -> Pa.
  const auto lib = fc::readMaterials(InputNode::loadString(std::string("units: in-lbf-s\n") + deck)["materials"]);
  EXPECT_NEAR(lib.at("as4").rho / (1.353e-4 * kSlinch / (kIn * kIn * kIn)), 1.0, 1e-14);
  EXPECT_NEAR(lib.at("as4").rho, 1445.94, 0.01);
  EXPECT_NEAR(lib.at("as4").E1 / (2.059e7 * kLbf / (kIn * kIn)), 1.0, 1e-14);
  // in-lb-s is the same system under the name VABS users often give it.
  const auto lb = fc::readMaterials(InputNode::loadString(std::string("units: in-lb-s\n") + deck)["materials"]);
  EXPECT_EQ(lb.at("as4").rho, lib.at("as4").rho);
}

TEST(Units, SceneQuantitiesByDimension) {
  const auto root = InputNode::loadString(
      "units: mm-kg-ms\n"
      "bodies:\n"
      "  - {name: a, rigid: {mass: 2, center_of_mass: [1, 0, 0], inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},\n"
      "     velocity: [1, 0, 0], angular_velocity: [0, 0, 0.001], modal_coordinates: [1]}\n"
      "forces:\n"
      "  - {type: gravity, g: [0, 0, -9.81e-3]}\n"
      "  - {type: translational_spring_damper, stiffness: 1, damping: 1, free_length: 10}\n"
      "  - {type: rotational_spring_damper, damping: 1, torque: {angle: [-0.2, 0.2], value: [-2, 2]}}\n"
      "  - {type: torque, torque: [0, 0, 1]}\n"
      "simulation: {t_end: 10000, output_step: 10, rtol: 1e-6, atol: 1e-9}\n");
  const auto b = root["bodies"].at(0);
  EXPECT_DOUBLE_EQ(b["rigid"]["mass"].asDouble(), 2.0);                        // kg
  EXPECT_DOUBLE_EQ(b["rigid"]["center_of_mass"].asVector(3)(0), 1e-3);         // mm
  EXPECT_DOUBLE_EQ(b["rigid"]["inertia"].asMatrix(3, 3)(0, 0), 1e-6);          // kg mm^2
  EXPECT_DOUBLE_EQ(b["velocity"].asVector(3)(0), 1.0);                         // mm/ms = m/s
  EXPECT_DOUBLE_EQ(b["angular_velocity"].asVector(3)(2), 1.0);                 // rad/ms
  EXPECT_DOUBLE_EQ(b["modal_coordinates"].asVector(1)(0), 1e-3);               // kg^1/2 mm
  const auto f = root["forces"];
  EXPECT_DOUBLE_EQ(f.at(0)["g"].asVector(3)(2), -9.81e3 * 1e-3);               // mm/ms^2 = 1e3 m/s^2
  EXPECT_DOUBLE_EQ(f.at(1)["stiffness"].asDouble(), 1e6);                      // kN/mm = 1e6 N/m
  EXPECT_DOUBLE_EQ(f.at(1)["damping"].asDouble(), 1e3);                        // kg/ms = N s/m x 1e3
  EXPECT_DOUBLE_EQ(f.at(1)["free_length"].asDouble(), 1e-2);
  EXPECT_DOUBLE_EQ(f.at(2)["damping"].asDouble(), 1e-3);                       // kg mm^2/ms = N m s x 1e-3
  EXPECT_DOUBLE_EQ(f.at(2)["torque"]["angle"].asVector(2)(1), 0.2);            // rad, never converted
  EXPECT_DOUBLE_EQ(f.at(2)["torque"]["value"].asVector(2)(1), 2.0);            // kN mm = N m
  EXPECT_DOUBLE_EQ(f.at(3)["torque"].asVector(3)(2), 1.0);
  const auto s = root["simulation"];
  EXPECT_DOUBLE_EQ(s["t_end"].asDouble(), 10.0);                               // ms -> s
  EXPECT_DOUBLE_EQ(s["output_step"].asDouble(), 0.01);
  EXPECT_DOUBLE_EQ(s["rtol"].asDouble(), 1e-6);
  EXPECT_DOUBLE_EQ(s["atol"].asDouble(), 1e-9);                                // SI always (m and rad mixed)
}

TEST(Units, CustomSystemAndBadNames) {
  const auto root = InputNode::loadString("units: {length: 0.001, mass: 1000, time: 1}\nx: {E: 1}\n");
  EXPECT_DOUBLE_EQ(root["x"]["E"].asDouble(), 1e6);  // t/(mm s^2) = MPa
  const std::string e = errorText([] { InputNode::loadString("units: in-lbf\n", "u.yaml"); });
  EXPECT_NE(e.find("u.yaml:1:8: units: unknown unit system 'in-lbf' (did you mean 'in-lbf-s'?)"), std::string::npos) << e;
  EXPECT_NE(e.find("mm-t-s"), std::string::npos) << e;
  const std::string z = errorText([] { InputNode::loadString("units: {length: 0, mass: 1, time: 1}\n", "u.yaml"); });
  EXPECT_NE(z.find("units.length"), std::string::npos) << z;
}

TEST(Units, RangeErrorsShowTheSIValue) {
  // 1e6 mm = 1 km: beyond the 1 m ply limit, and the message says what it was in SI.
  const std::string e = errorText([] {
    InputNode::loadString("units: mm-t-s\nt: {thickness: 1.0e6}\n", "r.yaml")["t"]["thickness"].asLength(1e-7, 1.0);
  });
  EXPECT_NE(e.find("got '1.0e6' = 1000 m in SI (the file's units: mm-t-s)"), std::string::npos) << e;
}

TEST(Units, AnIncludedFileHasItsOwnUnits) {
  const std::string dir = ::testing::TempDir();
  const std::string inc = dir + "/units_mats.yaml";
  {
    std::ofstream f(inc);
    f << "units: mm-t-s\nsteel: {type: isotropic, E: 210000, nu: 0.3, rho: 7.85e-9}\n";
  }
  const auto root = InputNode::loadString("materials: {include: units_mats.yaml,\n"
                                          "  al: {type: isotropic, E: 70e9, nu: 0.33, rho: 2700}}\n",
                                          dir + "/main.yaml");
  const auto lib = fc::readMaterials(root["materials"]);
  ASSERT_EQ(lib.size(), 2u);  // `units` of the included file is not a material
  EXPECT_DOUBLE_EQ(lib.at("steel").E1, 210e9);
  EXPECT_DOUBLE_EQ(lib.at("steel").rho, 7850.0);
  EXPECT_DOUBLE_EQ(lib.at("al").E1, 70e9);
  std::remove(inc.c_str());
}

}  // namespace
