// Laminate ABD and transverse shear against classical lamination theory worked
// by hand (Reddy, Mechanics of Laminated Composite Plates and Shells, 2nd ed.,
// eqs. 3.3.14 and 3.4.28) for the paper's IM6/SC1081 lay-ups (Table 1).
#include <gtest/gtest.h>

#include "common/laminate.h"

namespace {

fc::MaterialLibrary library() {
  auto root = fc::InputNode::loadString(R"(
materials:
  im6_sc1081: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9,
               G12: 7.6e9, G13: 7.6e9, G23: 8.504e9,
               nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600}
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
)");
  return fc::readMaterials(root["materials"]);
}

fc::LaminateLibrary laminates(const fc::MaterialLibrary& mats) {
  auto root = fc::InputNode::loadString(R"(
laminates:
  layup1: [{material: im6_sc1081, thickness: 0.0005, angle_deg: 0},
           {material: im6_sc1081, thickness: 0.0005, angle_deg: 0},
           {material: im6_sc1081, thickness: 0.0005, angle_deg: 0},
           {material: im6_sc1081, thickness: 0.0005, angle_deg: 0}]
  layup2:
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 0}
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 90}
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 90}
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 0}
  angled: {plies: [{material: im6_sc1081, thickness: 0.001, angle_deg: 30}]}
)");
  return fc::readLaminates(root["laminates"], mats);
}

// Hand values: nu21 = nu12 E2/E1 = 0.0164746, 1 - nu12 nu21 = 0.99555186,
// Q11 = E1/0.99555186 = 177.790838 GPa, Q22 = 10.8482545 GPa, Q12 = nu12 Q22 =
// 2.92902872 GPa, Q66 = G12 = 7.6 GPa.
constexpr double Q11 = 177.790837753e9, Q22 = 10.848254507e9, Q12 = 2.929028717e9, Q66 = 7.6e9;
// Relative tolerance: the hand values above carry 10 significant digits.
constexpr double kRel = 1e-9;

}  // namespace

TEST(Laminate, ReducedStiffnessByHand) {
  auto mats = library();
  Eigen::Matrix3d Q = fc::reducedStiffness(mats.at("im6_sc1081"));
  EXPECT_NEAR(Q(0, 0), Q11, kRel * Q11);
  EXPECT_NEAR(Q(1, 1), Q22, kRel * Q11);
  EXPECT_NEAR(Q(0, 1), Q12, kRel * Q11);
  EXPECT_NEAR(Q(2, 2), Q66, kRel * Q11);
  EXPECT_NEAR(Q(0, 2), 0.0, kRel * Q11);
}

TEST(Laminate, Layup1UnidirectionalByHand) {
  auto mats = library();
  auto lams = laminates(mats);
  auto s = fc::laminateStiffness(lams.at("layup1"), mats);
  const double h = 0.002;
  EXPECT_NEAR(s.thickness, h, 1e-15);
  EXPECT_NEAR(s.A(0, 0), Q11 * h, kRel * Q11 * h);          // 355.581676e6 N/m
  EXPECT_NEAR(s.A(1, 1), Q22 * h, kRel * Q11 * h);
  EXPECT_NEAR(s.A(0, 1), Q12 * h, kRel * Q11 * h);
  EXPECT_NEAR(s.A(2, 2), Q66 * h, kRel * Q11 * h);
  EXPECT_NEAR(s.D(0, 0), Q11 * h * h * h / 12, kRel * 118.53);  // 118.527225 N m
  EXPECT_NEAR(s.D(0, 0), 118.527225169, 1e-8 * 118.53);
  EXPECT_NEAR(s.D(1, 1), 7.232169671, 1e-8 * 118.53);
  EXPECT_LT(s.B.norm(), 1e-12 * Q11 * h * h);  // symmetric: no coupling
  // Shear: kappa = 5/6, 0-degree plies carry G13 in xz and G23 in yz.
  EXPECT_NEAR(s.As(0, 0), 5.0 / 6.0 * 7.6e9 * h, 1e-9 * 7.6e9 * h);
  EXPECT_NEAR(s.As(1, 1), 5.0 / 6.0 * 8.504e9 * h, 1e-9 * 7.6e9 * h);
  EXPECT_NEAR(s.As(0, 1), 0.0, 1e-9 * 7.6e9 * h);
  EXPECT_NEAR(s.mass_per_area, 1600 * h, 1e-12);
  EXPECT_NEAR(s.rotary_per_area, 1600 * h * h * h / 12, 1e-15);
}

TEST(Laminate, Layup2CrossPlyByHand) {
  auto mats = library();
  auto lams = laminates(mats);
  auto s = fc::laminateStiffness(lams.at("layup2"), mats);
  // Outer 0-degree plies |z| in [0.5, 1] mm, inner 90-degree plies |z| < 0.5 mm:
  // D11 = Q11 * 2 (1e-9 - 1.25e-10)/3 + Q22 * 2 (1.25e-10)/3 = 104.615343 N m.
  EXPECT_NEAR(s.D(0, 0), 104.615343232, 1e-8 * 104.6);
  EXPECT_NEAR(s.D(1, 1), 21.144051609, 1e-8 * 104.6);
  EXPECT_NEAR(s.D(0, 1), Q12 * 0.002 * 0.002 * 0.002 / 12, 1e-8 * 104.6);  // 1.95268581
  EXPECT_NEAR(s.A(0, 0), 188.639092261e6, 1e-9 * 188.6e6);
  EXPECT_NEAR(s.A(1, 1), 188.639092261e6, 1e-9 * 188.6e6);
  EXPECT_LT(s.B.norm(), 1e-12 * Q11 * 4e-6);
  EXPECT_NEAR(s.A(0, 2), 0.0, 1e-6);
  EXPECT_NEAR(s.D(0, 2), 0.0, 1e-12);
  // Each direction sees G13 through one half of the thickness and G23 through the other.
  const double as = 5.0 / 6.0 * (7.6e9 + 8.504e9) * 0.001;
  EXPECT_NEAR(s.As(0, 0), as, 1e-9 * as);
  EXPECT_NEAR(s.As(1, 1), as, 1e-9 * as);
}

TEST(Laminate, UnsymmetricLaminateHasCoupling) {
  // A [0/90] laminate: B11 = (Q11 - Q22) * (-(h/2)^2/2 ... ) by hand:
  // B11 = 1/2 [Q11 (0 - t^2) + Q22 (t^2 - 0)] with t = 1 mm.
  auto mats = library();
  fc::Laminate lam{"u", {{"im6_sc1081", 0.001, 0}, {"im6_sc1081", 0.001, 90}}};
  auto s = fc::laminateStiffness(lam, mats);
  const double t = 0.001;
  EXPECT_NEAR(s.B(0, 0), 0.5 * (Q22 - Q11) * t * t, 1e-9 * Q11 * t * t);
  EXPECT_NEAR(s.B(1, 1), 0.5 * (Q11 - Q22) * t * t, 1e-9 * Q11 * t * t);
}

TEST(Laminate, AngledPlyShearCoupling) {
  // Q16 of an off-axis ply (Reddy eq. 3.3.25): Qbar16 = (Q11 - Q12 - 2Q66) c^3 s
  // + (Q12 - Q22 + 2Q66) c s^3.
  auto mats = library();
  auto lams = laminates(mats);
  auto s = fc::laminateStiffness(lams.at("angled"), mats);
  const double a = 30 * 3.14159265358979323846 / 180, c = std::cos(a), sn = std::sin(a);
  const double q16 = (Q11 - Q12 - 2 * Q66) * c * c * c * sn + (Q12 - Q22 + 2 * Q66) * c * sn * sn * sn;
  EXPECT_NEAR(s.A(0, 2), q16 * 0.001, 1e-8 * Q11 * 0.001);
}

TEST(Laminate, UnknownMaterialIsAnInputErrorWithLine) {
  auto mats = library();
  auto root = fc::InputNode::loadString(
      "laminates:\n  l: [{material: im6_sc1081, thickness: 0.001},\n      {material: im6_sc108, "
      "thickness: 0.001}]\n",
      "lam.yaml");
  try {
    fc::readLaminates(root["laminates"], mats);
    FAIL() << "no error";
  } catch (const fc::InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.message().find("did you mean 'im6_sc1081'"), std::string::npos) << e.what();
  }
}

TEST(Laminate, InadmissibleMaterialReportsEntry) {
  auto root = fc::InputNode::loadString(
      "materials:\n  ok: {type: isotropic, E: 1e9, nu: 0.3, rho: 1}\n  bad: {type: isotropic, E: "
      "1e9, nu: 0.6, rho: 1}\n",
      "m.yaml");
  try {
    fc::readMaterials(root["materials"]);
    FAIL() << "no error";
  } catch (const fc::InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.keyPath(), "materials.bad");
    EXPECT_NE(e.message().find("Poisson"), std::string::npos) << e.what();
  }
}
