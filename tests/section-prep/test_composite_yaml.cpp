// Composite sections entered through the YAML path (gmsh meshes of our own)
// against VABS's published results for the same section on VABS's own mesh:
// the circumferentially uniform stiffness (CUS) box [15]6 of the VABS
// examples (tests/data/vabs/box_cus_comp.sg, in inches and psi). This checks
// the ply-angle and wall-orientation conventions of the box mesher, including
// the signs of the extension-twist and shear-bending couplings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/input.h"
#include "section-prep/cross_section.h"
#include "section-prep/section_mesher.h"
#include "section-prep/section_spec.h"
#include "vabs_k_file.h"

namespace fc::section {
namespace {

std::string cusBoxYaml(double angle, double h = 0.005) {
  std::string plies;
  for (int i = 0; i < 6; ++i)
    plies += "      - {material: as4, thickness: 0.005, angle_deg: " + std::to_string(angle) + "}\n";
  return "materials:\n"
         "  as4: {type: orthotropic, E1: 2.059e7, E2: 1.42e6, E3: 1.42e6, G12: 8.7e5, G13: 8.7e5,\n"
         "        G23: 6.96e5, nu12: 0.3, nu13: 0.3, nu23: 0.34, rho: 1.0}\n"
         "section:\n"
         "  shape: box\n"
         "  width: 0.953\n"
         "  height: 0.53\n"
         "  mesh_size: " + std::to_string(h) + "\n"
         "  wall:\n"
         "    plies:\n" + plies;
}

TEST(CompositeBox, CusBoxMatchesVabs) {
  const SectionSpec spec = readSectionSpec(InputNode::loadString(cusBoxYaml(15), "cus.yaml"));
  const SectionProperties p = analyzeSection(meshSection(spec));
  const auto ref = testing::readVabsK(std::string(FLEXCOMP_DATA_DIR) +
                                      "/vabs/box_cus_comp.sg.K");
  double worst = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      const double s = std::sqrt(ref.timoshenko(i, i) * ref.timoshenko(j, j));
      worst = std::max(worst, std::abs(p.timoshenko(i, j) - ref.timoshenko(i, j)) / s);
    }
  std::printf("CUS box via YAML: largest Timoshenko difference %.2e of the diagonal\n", worst);
  // VABS's mesh has one 4-node quadrilateral per ply through the thickness;
  // ours, 6-node triangles of the ply thickness. The two discretisations
  // differ by ~0.2 % in the transverse shear and torsion terms (VABS on its own
  // mesh is reproduced to 1e-11 by test_vabs_reference), so 5e-3 is the
  // discretisation allowance, not a convention allowance: a sign error in a
  // coupling (K14 = -0.25 of the diagonal scale) would fail by 50x.
  EXPECT_LT(worst, 5e-3);
  // Extension-twist coupling and its sign, and the bending-shear couplings.
  EXPECT_NEAR(p.timoshenko(0, 3) / ref.timoshenko(0, 3), 1.0, 1e-3);
  EXPECT_NEAR(p.timoshenko(1, 4) / ref.timoshenko(1, 4), 1.0, 5e-3);
  EXPECT_NEAR(p.timoshenko(2, 5) / ref.timoshenko(2, 5), 1.0, 5e-3);
}

TEST(CompositeBox, CusBoxInInchPoundUnitsGivesTheSIStiffness) {
  // The same deck as a VABS user writes it: `units: in-lbf-s` (inches, lbf, psi, mass in
  // slinch = lbf s^2/in), the ply density a real AS4 value, 1.353e-4 slinch/in^3 (1446
  // kg/m^3), which the SI range check would refuse as a unit slip. Read it, convert it at
  // read time, and the section's stiffness comes out in SI: VABS's matrix (lb, lb in,
  // lb in^2) times the exact factors lbf = 4.4482216152605 N, in = 0.0254 m.
  std::string yaml = cusBoxYaml(15);
  yaml.replace(yaml.find("rho: 1.0"), 8, "rho: 1.353e-4");
  const SectionSpec spec = readSectionSpec(InputNode::loadString("units: in-lbf-s\n" + yaml, "cus_in.yaml"));
  const SectionProperties p = analyzeSection(meshSection(spec));
  const auto ref = testing::readVabsK(std::string(FLEXCOMP_DATA_DIR) + "/vabs/box_cus_comp.sg.K");
  const double lbf = 4.4482216152605, in = 0.0254;
  // Rows and columns 0-2 pair with forces and strains, 3-5 with moments and curvatures.
  Eigen::Matrix<double, 6, 6> ref_si;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) ref_si(i, j) = ref.timoshenko(i, j) * lbf * std::pow(in, (i >= 3) + (j >= 3));
  double worst = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      worst = std::max(worst, std::abs(p.timoshenko(i, j) - ref_si(i, j)) / std::sqrt(ref_si(i, i) * ref_si(j, j)));
  std::printf("CUS box in in-lbf-s: largest Timoshenko difference from VABS (in SI) %.2e of the diagonal\n", worst);
  // The discretisation allowance of CusBoxMatchesVabs above (the same mesh, scaled): a
  // missed or doubled length factor would be off by 0.0254 or 39 in the bending terms.
  EXPECT_LT(worst, 5e-3);
  EXPECT_NEAR(p.timoshenko(0, 0) / ref_si(0, 0), 1.0, 1e-3);
  EXPECT_NEAR(p.timoshenko(4, 4) / ref_si(4, 4), 1.0, 1e-3);
  // Mass per length: VABS's mass(0, 0) at its density 1 is the wall area (in^2); times
  // 1.353e-4 slinch/in^3 and slinch/in -> kg/m. The straight walls make the area exact.
  const double mu_si = ref.mass(0, 0) * 1.353e-4 * (lbf / in) / in;
  EXPECT_NEAR(p.mass_per_length / mu_si, 1.0, 1e-6);
}

TEST(CompositeBox, MirroredLayupFlipsTheCouplings) {
  // Reflecting every ply angle is a mirror image in x1: the extension-twist
  // and shear-bending couplings change sign, the diagonal stays.
  const auto a = analyzeSection(meshSection(readSectionSpec(InputNode::loadString(cusBoxYaml(15, 0.01)))));
  const auto b = analyzeSection(meshSection(readSectionSpec(InputNode::loadString(cusBoxYaml(-15, 0.01)))));
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(b.timoshenko(i, i) / a.timoshenko(i, i), 1.0, 1e-9);
  EXPECT_NEAR(b.timoshenko(0, 3) / a.timoshenko(0, 3), -1.0, 1e-9);
  EXPECT_NEAR(b.timoshenko(1, 4) / a.timoshenko(1, 4), -1.0, 1e-9);
}

TEST(LaminatedTube, AxialFibresAndRotatedWallFrameAgree) {
  // A tube whose plies are all at 0 degrees is transversely isotropic about
  // x1 at every point whatever theta1 is: EA = E1 A and EI = E1 I exactly, and
  // GJ = G12 J (torsion of a circular tube does not warp); no couplings.
  const char* yaml =
      "materials:\n"
      "  ud: {type: orthotropic, E1: 140e9, E2: 9e9, E3: 9e9, G12: 5e9, G13: 5e9, G23: 3e9,\n"
      "       nu12: 0.3, nu13: 0.3, nu23: 0.5, rho: 1550}\n"
      "section:\n"
      "  shape: tube\n"
      "  outer_diameter: 0.02\n"
      "  mesh_size: 0.0005\n"
      "  wall: {plies: [{material: ud, thickness: 0.001, angle_deg: 0},\n"
      "                 {material: ud, thickness: 0.001, angle_deg: 0}]}\n";
  const auto p = analyzeSection(meshSection(readSectionSpec(InputNode::loadString(yaml))));
  const double pi = 3.14159265358979323846, Ro = 0.01, Ri = 0.008;
  const double A = pi * (Ro * Ro - Ri * Ri), I = pi * (std::pow(Ro, 4) - std::pow(Ri, 4)) / 4;
  // Curved quadratic elements: geometry exact to ~1e-8 (see test_closed_forms).
  EXPECT_NEAR(p.classical(0, 0) / (140e9 * A), 1.0, 1e-5);
  EXPECT_NEAR(p.classical(2, 2) / (140e9 * I), 1.0, 1e-5);
  EXPECT_NEAR(p.classical(1, 1) / (5e9 * 2 * I), 1.0, 1e-5);
  EXPECT_LT(std::abs(p.classical(0, 1)), 1e-8 * std::sqrt(p.classical(0, 0) * p.classical(1, 1)));
  EXPECT_NEAR(p.mass_per_length / (1550 * A), 1.0, 1e-5);
}

}  // namespace
}  // namespace fc::section
