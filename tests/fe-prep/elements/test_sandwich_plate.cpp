// A simply supported sandwich plate (aluminium faces on a honeycomb core) with
// the transverse shear stiffness from the stacking (common/laminate.h), against
// two references nobody here wrote: the Navier solution of first-order shear
// deformation theory (Reddy, Mechanics of Laminated Composite Plates and Shells,
// 2nd ed., ch. 6, hard simple supports) and a layered 3-D CalculiX 2.20 model
// (C3D20R bricks, 1 + 4 + 1 through the thickness, 20 x 20 in plane) whose
// results tests/data/sandwich/ccx_sandwich_plate.py wrote to the fixture read
// here. A shell with the core as one ply of CalculiX's S8R is no reference: its
// single brick through the thickness lets the faces take the shear.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "closed_forms.h"
#include "common/input.h"
#include "common/laminate.h"
#include "plate_model.h"

namespace fc::fe {
namespace {

// The plate of the fixture: a = b = 0.5 m, faces 1 mm, core 20 mm (a/h = 23).
constexpr double kA = 0.5, kFace = 1e-3, kCore = 20e-3, kPressure = 1000.0;

LaminateStiffness sandwich(std::optional<double> shear_correction = std::nullopt) {
  auto root = InputNode::loadString(R"(
materials:
  al: {type: isotropic, E: 70e9, nu: 0.3, rho: 2700}
  honeycomb: {type: honeycomb, E3: 600e6, G13: 200e6, G23: 100e6, rho: 50, E1: 1e5, E2: 1e5, G12: 1e5}
)");
  const MaterialLibrary mats = readMaterials(root["materials"]);
  const Laminate lam{"sandwich", {{"al", kFace, 0}, {"honeycomb", kCore, 0}, {"al", kFace, 0}}};
  return laminateStiffness(lam, mats, shear_correction);
}

// Navier FSDT centre deflection under uniform pressure q: the load's double
// sine series 16 q / (pi^2 m n) over odd m, n, each term's amplitude from the
// same 3x3 stiffness as navierMindlinOmega. Terms fall as 1 / (m n (m^2 + n^2)):
// 399 x 399 terms leave < 1e-5 of the sum.
double navierCentreDeflection(const LaminateStiffness& L, double q) {
  double w = 0;
  for (int m = 1; m < 400; m += 2)
    for (int n = 1; n < 400; n += 2) {
      const double al = m * M_PI / kA, be = n * M_PI / kA, A55 = L.As(0, 0), A44 = L.As(1, 1);
      Eigen::Matrix3d S;
      S << A55 * al * al + A44 * be * be, A55 * al, A44 * be,
          A55 * al, L.D(0, 0) * al * al + L.D(2, 2) * be * be + A55, (L.D(0, 1) + L.D(2, 2)) * al * be,
          A44 * be, (L.D(0, 1) + L.D(2, 2)) * al * be, L.D(2, 2) * al * al + L.D(1, 1) * be * be + A44;
      const double amplitude = S.inverse()(0, 0) * 16 * q / (M_PI * M_PI * m * n);
      w += amplitude * std::sin(m * M_PI / 2) * std::sin(n * M_PI / 2);
    }
  return w;
}

struct Reference3d {
  std::vector<double> hz;
  double w_mid = 0;
};

Reference3d calculix() {
  const InputNode f = InputNode::loadFile(std::string(FLEXCOMP_DATA_DIR) + "/sandwich/ccx_sandwich_plate.yaml");
  Reference3d r;
  for (std::size_t i = 0; i < f["frequencies_hz"].size(); ++i) r.hz.push_back(f["frequencies_hz"].at(i).asDouble());
  r.w_mid = -f["centre_w"].at(1).asDouble();  // ccx's u_z at the mid-surface, downward
  return r;
}

// DST shell model (20 x 20 cells, consistent mass) against Navier FSDT with the
// sandwich shear and against the 3-D model.
TEST(SandwichPlate, FrequenciesAndDeflectionMatchFsdtAndLayered3d) {
  const LaminateStiffness lam = sandwich();
  const Reference3d ccx = calculix();
  const int count = 6;
  const std::vector<double> navier =
      test::lowestNavier(true, lam.D, lam.As, lam.mass_per_area, lam.rotary_per_area, kA, kA, count);

  // DST converges at second order (Batoz & Lardeur 1989; observed below), so the
  // 10 x 10 and 20 x 20 meshes give the converged shell by Richardson's
  // extrapolation f = f20 + (f20 - f10) / 3; the raw 20 x 20 errors are
  // +0.1 .. +1.4 % (modes 4-6 have 3-4 cells per half-wave).
  const auto hz = [&](int n) {
    const test::PlateMesh mesh = test::rectangleMesh(kA, kA, n, n);
    const Eigen::VectorXd ev = test::eigenvalues(test::assembleShell(mesh, lam, ShellKind::DST, false),
                                                 test::plateBendingDofs(mesh, 'S'));
    std::vector<double> f;
    for (int i = 0; i < count; ++i) f.push_back(std::sqrt(ev(i)) / (2 * M_PI));
    return f;
  };
  const std::vector<double> f10 = hz(10), f20 = hz(20);
  for (int i = 0; i < count; ++i) {
    const double fsdt = navier[i] / (2 * M_PI), fe = f20[i] + (f20[i] - f10[i]) / 3;
    // Second order: log2 of the error ratio within [1.6, 2.4] (measured
    // 1.99 .. 2.06); 1 % on the extrapolated shell against FSDT and 3-D, the
    // issue's criterion (measured within 0.04 % of both); FSDT against 3-D measured within 0.05 % (the 3-D model's core
    // compressibility E3 and the faces' own bending about their mid-planes,
    // which FSDT ties to the section's rotation, are O(t^2/d^2) effects here:
    // 0.2 % allows for them and the 3-D mesh).
    EXPECT_NEAR(std::log2((f10[i] - fsdt) / (f20[i] - fsdt)), 2.0, 0.4) << "mode " << i;
    EXPECT_NEAR(fe / fsdt, 1.0, 0.01) << "mode " << i << ": " << fe << " Hz, FSDT " << fsdt;
    EXPECT_NEAR(fe / ccx.hz[i], 1.0, 0.01) << "mode " << i << ": " << fe << " Hz, 3-D " << ccx.hz[i];
    EXPECT_NEAR(fsdt / ccx.hz[i], 1.0, 0.002) << "mode " << i << ": FSDT " << fsdt << " Hz, 3-D " << ccx.hz[i];
    std::printf("mode %d: DST 10x10 %.2f, 20x20 %.2f, extrapolated %.2f, FSDT %.2f, 3-D %.2f Hz\n", i + 1, f10[i],
                f20[i], fe, fsdt, ccx.hz[i]);
  }

  const test::PlateMesh mesh = test::rectangleMesh(kA, kA, 20, 20);
  const test::Assembled sys = test::assembleShell(mesh, lam, ShellKind::DST, false);
  const std::vector<int> keep = test::plateBendingDofs(mesh, 'S');
  // Uniform pressure: nodal loads by tributary area (a third of each triangle).
  Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.K.rows());
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d e1 = mesh.nodes[tri[1]] - mesh.nodes[tri[0]], e2 = mesh.nodes[tri[2]] - mesh.nodes[tri[0]];
    const double area = 0.5 * e1.cross(e2).norm();
    for (int v : tri) f(6 * v + 2) += kPressure * area / 3;
  }
  const int m = static_cast<int>(keep.size());
  Eigen::MatrixXd K(m, m);
  Eigen::VectorXd fk(m);
  for (int r = 0; r < m; ++r) {
    fk(r) = f(keep[r]);
    for (int c = 0; c < m; ++c) K(r, c) = sys.K(keep[r], keep[c]);
  }
  const Eigen::VectorXd u = K.ldlt().solve(fk);
  const int centre = 6 * mesh.node(10, 10) + 2;
  double w_fe = 0;
  for (int r = 0; r < m; ++r)
    if (keep[r] == centre) w_fe = u(r);
  const double w_fsdt = navierCentreDeflection(lam, kPressure);
  // 1 %: measured -0.21 % against FSDT and -0.18 % against 3-D at 20 x 20 (the
  // tributary-area load and the mesh); FSDT against 3-D +0.04 %.
  EXPECT_NEAR(w_fe / w_fsdt, 1.0, 0.01) << w_fe << " m, FSDT " << w_fsdt;
  EXPECT_NEAR(w_fe / ccx.w_mid, 1.0, 0.01) << w_fe << " m, 3-D " << ccx.w_mid;
  EXPECT_NEAR(w_fsdt / ccx.w_mid, 1.0, 0.002) << "FSDT " << w_fsdt << " m, 3-D " << ccx.w_mid;
  std::printf("centre deflection: DST 20x20 %.6g, FSDT %.6g, 3-D %.6g m\n", w_fe, w_fsdt, ccx.w_mid);
}

// The old rule, 5/6 of the summed ply shear stiffness, lets the aluminium faces
// carry the shear: the first frequency 18 % and the deflection 27 % away from
// the 3-D model, the error the stacking rule removes.
TEST(SandwichPlate, FiveSixthsOfSummedShearIsFarFrom3d) {
  const LaminateStiffness old = sandwich(5.0 / 6.0);
  const Reference3d ccx = calculix();
  const double f1 = test::lowestNavier(true, old.D, old.As, old.mass_per_area, old.rotary_per_area, kA, kA, 1)[0] /
                    (2 * M_PI);
  EXPECT_GT(f1 / ccx.hz[0], 1.15);
  EXPECT_LT(navierCentreDeflection(old, kPressure) / ccx.w_mid, 0.75);
}

}  // namespace
}  // namespace fc::fe
