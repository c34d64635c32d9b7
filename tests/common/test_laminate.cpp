// Laminate ABD and transverse shear against classical lamination theory worked
// by hand (Reddy, Mechanics of Laminated Composite Plates and Shells, 2nd ed.,
// eqs. 3.3.14 and 3.4.28) for the paper's IM6/SC1081 lay-ups (Table 1).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

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

// One layer of a symmetric stack for equilibriumShear: bending modulus along the
// bending direction (Qbar_11), transverse shear modulus (G_xz), thickness.
struct Layer {
  double E, G, t;
};

// Transverse shear stiffness of a symmetric stack in cylindrical bending, by the
// closed-form layer sums of the Dlubal RF-LAMINATE manual (FAQ 004281): with
// chi_i = E_i z_i,max^2 / 2 + sum_{k > i} E_k (z_k,max^2 - z_k,min^2) / 2 the shear
// flow int_z^{h/2} E s ds = chi_i - E_i z^2 / 2 in layer i, and
//   I = sum_i [chi_i^2 dz - chi_i E_i dz^3 / 3 + E_i^2 dz^5 / 20] / G_i
// (dz^n short for z_max^n - z_min^n), As = (int E z^2 dz)^2 / I. Integrates from
// the top (the library from the bottom) with exact polynomials (the library with
// Gauss points): an independent route to the same equilibrium stress.
double equilibriumShear(const std::vector<Layer>& layers) {
  double h = 0;
  for (const Layer& l : layers) h += l.t;
  std::vector<double> z0, z1;
  double z = -h / 2;
  for (const Layer& l : layers) {
    z0.push_back(z);
    z += l.t;
    z1.push_back(z);
  }
  const std::size_t n = layers.size();
  double EI = 0, I = 0;
  for (std::size_t i = 0; i < n; ++i) EI += layers[i].E * (std::pow(z1[i], 3) - std::pow(z0[i], 3)) / 3;
  for (std::size_t i = 0; i < n; ++i) {
    double chi = layers[i].E * z1[i] * z1[i] / 2;
    for (std::size_t k = i + 1; k < n; ++k) chi += layers[k].E * (z1[k] * z1[k] - z0[k] * z0[k]) / 2;
    const double E = layers[i].E;
    const auto d = [&](int p) { return std::pow(z1[i], p) - std::pow(z0[i], p); };
    I += (chi * chi * d(1) - chi * E * d(3) / 3 + E * E * d(5) / 20) / layers[i].G;
  }
  return EI * EI / I;
}

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
  // Transverse shear from the stacking, by the closed-form integration of a
  // symmetric stack (equilibriumShear below, not the library's quadrature). Each
  // direction sees G13 through one half of the thickness and G23 through the
  // other, summed 16.104e6 N/m; the stacking gives k_x = 0.88650 (the stiff 0-degree
  // plies outside carry the bending, the shear peaks in the G13 plies) and
  // k_y = 0.51927 (bending about x is carried by the inner 90-degree plies, whose
  // shear flows through the soft G23 of the outer plies). Was 5/6 for both.
  const double t = 0.0005;
  const double ax = equilibriumShear({{Q11, 7.6e9, t}, {Q22, 8.504e9, t}, {Q22, 8.504e9, t}, {Q11, 7.6e9, t}});
  const double ay = equilibriumShear({{Q22, 8.504e9, t}, {Q11, 7.6e9, t}, {Q11, 7.6e9, t}, {Q22, 8.504e9, t}});
  EXPECT_NEAR(s.As(0, 0), ax, 1e-9 * ax);  // 14.276188e6 N/m
  EXPECT_NEAR(s.As(1, 1), ay, 1e-9 * ay);  //  8.362346e6 N/m
  EXPECT_NEAR(s.As(0, 0), 14.276188e6, 1e-7 * ax);
  EXPECT_NEAR(s.As(1, 1), 8.362346e6, 1e-7 * ay);
  EXPECT_NEAR(s.As(0, 1), 0.0, 1e-9 * ax);
  // The user's explicit factor keeps the old rule: 5/6 of the summed G t.
  auto legacy = fc::laminateStiffness(lams.at("layup2"), mats, 5.0 / 6.0);
  const double as = 5.0 / 6.0 * (7.6e9 + 8.504e9) * 0.001;
  EXPECT_NEAR(legacy.As(0, 0), as, 1e-9 * as);
  EXPECT_NEAR(legacy.As(1, 1), as, 1e-9 * as);
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

// A homogeneous plate of any material and orientation keeps exactly 5/6 of its
// shear stiffness (the parabolic shear of a homogeneous section, Reissner 1945),
// including the xz-yz coupling of an off-axis ply, and so does a stack of equal
// plies of it.
TEST(LaminateShear, HomogeneousPlateIsFiveSixths) {
  auto mats = library();
  for (const double angle : {0.0, 30.0, 90.0}) {
    for (const char* m : {"im6_sc1081", "cfrp_iso"}) {
      fc::Laminate one{"one", {{m, 0.002, angle}}};
      fc::Laminate four{"four", {{m, 0.0005, angle}, {m, 0.0005, angle}, {m, 0.0005, angle}, {m, 0.0005, angle}}};
      const Eigen::Matrix2d summed = fc::rotatedTransverseShear(mats.at(m), angle * M_PI / 180) * 0.002;
      for (const auto& lam : {one, four}) {
        const auto s = fc::transverseShearFromStacking(lam, mats);
        // 1e-12: round-off of a few dozen products.
        EXPECT_LT((s.As - 5.0 / 6.0 * summed).norm(), 1e-12 * summed.norm()) << m << " " << angle;
        EXPECT_NEAR(s.factor(0), 5.0 / 6.0, 1e-12);
        EXPECT_NEAR(s.factor(1), 5.0 / 6.0, 1e-12);
      }
    }
  }
}

// Published worked example: a five-layer cross-laminated timber plate (Dlubal,
// RF-LAMINATE, FAQ 004281), layers of 20 mm with E_x = 11000 / 300 N/mm^2 and
// G_xz = 690 / 50 N/mm^2 alternating (a [0/90/0/90/0] cross-ply, nu = 0). The
// page gives EI = 731.2e6 N mm and int (shear flow)^2 / G dz = 6.7133e13 (its
// chi_i are rounded to 4 digits, hence the 1e-4 tolerance on I).
TEST(LaminateShear, PublishedCrossLaminatedTimberExample) {
  auto root = fc::InputNode::loadString(R"(
materials:
  timber: {type: orthotropic, E1: 11000e6, E2: 300e6, E3: 300e6, G12: 690e6, G13: 690e6, G23: 50e6,
           nu12: 0, nu13: 0, nu23: 0, rho: 450}
)");
  const auto mats = fc::readMaterials(root["materials"]);
  fc::Laminate clt{"clt", {}};
  for (int i = 0; i < 5; ++i) clt.plies.push_back({"timber", 0.020, i % 2 ? 90.0 : 0.0});
  const auto s = fc::laminateStiffness(clt, mats);
  EXPECT_NEAR(s.D(0, 0), 731.2e6 * 1e-3, 1e-12 * 731.2e3);  // N mm -> N m
  const double EI = 731.2e6, I = 6.7133e13;  // N mm, N mm^3 (the page's units)
  const double published = EI * EI / I * 1e3;  // N/mm -> N/m: 7.9641e6
  EXPECT_NEAR(s.As(0, 0), published, 1e-4 * published);
  // The page's factor sum G_i A_i / As = 5.45 (in our terms k_x = 0.1835).
  EXPECT_NEAR(1 / fc::transverseShearFromStacking(clt, mats).factor(0), 5.4497, 1e-4);
}

// Thin stiff faces on a honeycomb core: sandwich theory (Allen, Analysis and
// Design of Structural Sandwich Panels, 1969, ch. 2; Zenkert 1995, ch. 3). With
// the core's in-plane modulus negligible the core shear stress is uniform,
// tau_c = Q E_f t d / (2 D) (Allen's eq. 2.11 with E_c = 0), and in a face it
// falls to 0 at the surface as s (h - s) / (t (h - t)), s from the surface. The
// energy gives S = G_c d^2 / c (D / D0)^2 / (1 + 2 (G_c / G_f) J / c), with
// D0 = E_f t d^2 / 2 the faces' Steiner part and J = int_0^t [s (h - s)]^2 ds /
// [t (h - t)]^2 the faces' share. Thin faces: S -> G_c d^2 / c.
TEST(LaminateShear, SandwichTendsToCoreShearTheory) {
  auto root = fc::InputNode::loadString(R"(
materials:
  face: {type: isotropic, E: 70e9, nu: 0.3, rho: 2700}
  core: {type: honeycomb, E3: 600e6, G13: 200e6, G23: 100e6, rho: 50}
)");
  const auto mats = fc::readMaterials(root["materials"]);
  const double c = 0.020, Gc[2] = {200e6, 100e6}, Ef = 70e9 / (1 - 0.09), Gf = 70e9 / 2.6;
  for (const double t : {2e-3, 0.5e-3, 0.05e-3}) {
    fc::Laminate lam{"sw", {{"face", t, 0}, {"core", c, 0}, {"face", t, 0}}};
    const auto s = fc::laminateStiffness(lam, mats);
    const double d = c + t, h = c + 2 * t, D0 = Ef * t * d * d / 2, D = D0 + Ef * t * t * t / 6;
    const double J = (h * h * std::pow(t, 3) / 3 - h * std::pow(t, 4) / 2 + std::pow(t, 5) / 5) /
                     std::pow(t * (h - t), 2);
    for (int k = 0; k < 2; ++k) {
      const double allen = Gc[k] * d * d / c * (D / D0) * (D / D0) / (1 + 2 * Gc[k] / Gf * J / c);
      // Neglected: the core's in-plane modulus (1e-3 G_c = 1e5 Pa): its bending
      // is ~1e-5 of the faces'.
      EXPECT_NEAR(s.As(k, k), allen, 5e-5 * allen) << "t " << t << " dir " << k;
    }
    // The old rule, 5/6 of the summed G t, is dominated by the faces' G.
    EXPECT_GT(5.0 / 6.0 * (2 * Gf * t + 200e6 * c), 1.1 * s.As(0, 0)) << t;
  }
  // Thin-face limit G_c d^2 / c: t / d = 2.5e-3, so (D/D0)^2 - 1 = 2 t^2 / (3 d^2)
  // = 4e-6 and the faces' shear share 2 (G_c/G_f) t / (3 c) = 1.2e-5.
  fc::Laminate thin{"thin", {{"face", 0.05e-3, 0}, {"core", c, 0}, {"face", 0.05e-3, 0}}};
  const auto s = fc::laminateStiffness(thin, mats);
  const double d = c + 0.05e-3;
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(s.As(k, k) / (Gc[k] * d * d / c), 1.0, 3e-5);
}

TEST(Materials, HoneycombCore) {
  auto root = fc::InputNode::loadString(R"(
materials:
  core: {type: honeycomb, E3: 600e6, G13: 200e6, G23: 100e6, rho: 50}
  core2: {type: honeycomb, E3: 600e6, G13: 200e6, G23: 100e6, rho: 50, E1: 1e6, E2: 2e6, G12: 0.5e6}
)");
  const auto mats = fc::readMaterials(root["materials"]);
  const auto& m = mats.at("core");
  EXPECT_EQ(m.E3, 600e6);
  EXPECT_EQ(m.G13, 200e6);
  EXPECT_EQ(m.G23, 100e6);
  EXPECT_EQ(m.E1, 1e-3 * 100e6);  // negligible in-plane moduli by default
  EXPECT_EQ(m.E2, 1e-3 * 100e6);
  EXPECT_EQ(m.G12, 1e-3 * 100e6);
  EXPECT_EQ(mats.at("core2").E2, 2e6);
  // Transverse shear in laminate axes: G13 along the ribbon (0 deg), swapped at 90.
  const Eigen::Matrix2d g0 = fc::rotatedTransverseShear(m, 0), g90 = fc::rotatedTransverseShear(m, M_PI / 2);
  EXPECT_NEAR(g0(0, 0), 200e6, 1e-6);
  EXPECT_NEAR(g90(0, 0), 100e6, 1e-6);
  // A strength (Tsai-Wu ply data) means nothing for a core: named as unknown.
  auto bad = fc::InputNode::loadString(
      "materials:\n  c: {type: honeycomb, E3: 6e8, G13: 2e8, G23: 1e8, rho: 50,\n     strength: {Xt: 1e6}}\n", "m.yaml");
  try {
    fc::readMaterials(bad["materials"]);
    FAIL() << "no error";
  } catch (const fc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("strength"), std::string::npos) << e.what();
  }
}
