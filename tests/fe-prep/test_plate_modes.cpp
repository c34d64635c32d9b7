// Plate frequencies through the whole tool path (YAML -> gmsh -> PETSc/SLEPc)
// against closed forms (Navier, classical and first-order shear theory) and
// Leissa's tables. Meshes are unstructured (gmsh Frontal-Delaunay); tolerances
// are a few times the discretisation error measured at these sizes and shrink
// with the mesh (see the convergence test), never the other way round.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "common/laminate.h"
#include "feprep_test_support.h"
#include "plate_references.h"

namespace fc::feprep::test {
namespace {

const char* kMaterials = R"(
materials:
  alu: {type: isotropic, E: 70.0e9, nu: 0.3, rho: 2700}
  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}
  im6_sc1081: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9,
               G12: 7.6e9, G13: 7.6e9, G23: 8.504e9, nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600}
laminates:
  layup2:
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 0}
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 90}
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 90}
    - {material: im6_sc1081, thickness: 0.0005, angle_deg: 0}
)";

std::string plateYaml(const std::string& section, double a, double b, const std::string& element, double size,
                      const std::string& reference, int modes) {
  std::ostringstream os;
  os << kMaterials << "body:\n  name: plate\n  shell:\n    rectangle: {length: " << a << ", width: " << b << "}\n"
     << "    " << section << "\n    element: " << element << "\n    mesh: {size: " << size << "}\n"
     << "  reference: " << reference << "\n  modes: " << modes << "\n";
  return os.str();
}

const char* kSimplySupported = "{pin: [edge_xmin, edge_xmax, edge_ymin, edge_ymax]}";

LaminateStiffness stiffnessOf(const std::string& yaml_section) {
  const BodySpec s = parseBodySpec(InputNode::loadString(plateYaml(yaml_section, 1, 1, "dkt", 0.1, "free", 1)));
  return s.shell->laminate;
}

// Lowest `count` Navier frequencies [Hz] over (m, n).
std::vector<double> navierList(const LaminateStiffness& L, double a, double b, int count, bool shear) {
  std::vector<double> f;
  for (int m = 1; m <= 8; ++m)
    for (int n = 1; n <= 8; ++n)
      f.push_back((shear ? navierFirstOrderShear(L.D, L.As, L.mass_per_area, L.rotary_per_area, a, b, m, n)
                         : navierClassical(L.D, L.mass_per_area, a, b, m, n)) /
                  (2 * M_PI));
  std::sort(f.begin(), f.end());
  f.resize(static_cast<std::size_t>(count));
  return f;
}

void expectRelative(const Eigen::VectorXd& got, const std::vector<double>& want, double tol, const char* what) {
  ASSERT_GE(got.size(), static_cast<long>(want.size()));
  for (std::size_t i = 0; i < want.size(); ++i)
    EXPECT_NEAR(got(static_cast<long>(i)) / want[i], 1.0, tol) << what << " mode " << i + 1 << ": " << got(static_cast<long>(i))
                                                              << " Hz vs " << want[i] << " Hz";
}

TEST(PlateModes, SimplySupportedSquareIsotropicMatchesNavier) {
  const std::string sec = "material: alu\n    thickness: 0.01";
  const BuildResult r = runYaml(plateYaml(sec, 1.0, 1.0, "dkt", 0.05, kSimplySupported, 6));
  EXPECT_EQ(r.rigid_removed, 0);
  // Measured errors at h = a/20: 0.05 % (mode 1) to 0.3 % (modes 5-6); 1 % leaves room
  // for gmsh version differences in the unstructured mesh.
  expectRelative(r.body.frequencies_hz, navierList(stiffnessOf(sec), 1.0, 1.0, 6, false), 0.01, "SS square");
}

TEST(PlateModes, SimplySupportedSarPanelIsotropicMatchesNavier) {
  const std::string sec = "material: cfrp_iso\n    thickness: 0.002";
  const BuildResult r = runYaml(plateYaml(sec, 2.0, 1.3, "dst", 0.05, kSimplySupported, 6));
  // Measured: 0.01-0.14 % at h = 0.05 (a/h = 1000: DST is DKT here).
  expectRelative(r.body.frequencies_hz, navierList(stiffnessOf(sec), 2.0, 1.3, 6, false), 0.005, "SS 2.0 x 1.3");
}

TEST(PlateModes, SimplySupportedCrossPlyMatchesNavier) {
  // [0/90/90/0] is specially orthotropic (D16 = D26 = 0, B = 0): Navier is exact.
  const std::string sec = "laminate: layup2";
  const BuildResult r = runYaml(plateYaml(sec, 2.0, 1.3, "dst", 0.05, kSimplySupported, 6));
  // Measured: 0.005-0.12 % at h = 0.05.
  expectRelative(r.body.frequencies_hz, navierList(stiffnessOf(sec), 2.0, 1.3, 6, false), 0.005, "SS cross-ply");
}

TEST(PlateModes, ThickPlateDstFollowsShearTheoryAndDktDoesNot) {
  // A strip (nu = 0, a/h = 5) pinned on its short edges and free on the long
  // ones vibrates in exact cylindrical bending w = sin(pi x / a): the Navier
  // solutions with n = 0 hold whatever the simple support's tangential rotation
  // ("soft" pins here, "hard" in Navier), which is not true of four pinned edges.
  // DST must follow first-order shear theory, DKT the classical plate; both with
  // the rotary inertia of the section, which the lumped mass carries (a classical
  // plate with rotary inertia: omega^2 = D k^4 / (I0 + I2 k^2)). Measured errors:
  // 0.11 % (DST) and 0.02 % (DKT) at h = a/20; the theories differ by 3.6 %.
  const std::string sec = "material: alu0\n    thickness: 0.2";
  const std::string yaml_mat = "  alu0: {type: isotropic, E: 70.0e9, nu: 0.0, rho: 2700}\n";
  auto yaml = [&](const char* el) {
    std::string y = plateYaml(sec, 1.0, 0.5, el, 0.05, "{pin: [edge_xmin, edge_xmax]}", 1);
    y.insert(y.find("  alu:"), yaml_mat);
    return y;
  };
  const BodySpec spec = parseBodySpec(InputNode::loadString(yaml("dst")));
  const LaminateStiffness& L = spec.shell->laminate;
  const double f_fsdt = navierFirstOrderShear(L.D, L.As, L.mass_per_area, L.rotary_per_area, 1, 0.5, 1, 0) / (2 * M_PI);
  const double k2 = M_PI * M_PI;
  const double f_rayleigh = std::sqrt(L.D(0, 0) * k2 * k2 / (L.mass_per_area + L.rotary_per_area * k2)) / (2 * M_PI);
  ASSERT_LT(f_fsdt / f_rayleigh, 0.98);  // the case really is thick
  const BuildResult dst = runYaml(yaml("dst"));
  const BuildResult dkt = runYaml(yaml("dkt"));
  EXPECT_NEAR(dst.body.frequencies_hz(0) / f_fsdt, 1.0, 0.005);
  EXPECT_NEAR(dkt.body.frequencies_hz(0) / f_rayleigh, 1.0, 0.005);
  EXPECT_GT(dkt.body.frequencies_hz(0) / dst.body.frequencies_hz(0), 1.03);
}

TEST(PlateModes, ThickSquareWithFourPinnedEdgesIsBelowHardSupportNavier) {
  // Four pinned edges leave the tangential rotation free (soft support), which
  // is more flexible than Navier's hard support: DST must lie below FSDT Navier,
  // within the 3 % (a/h = 10) that soft/hard differences reach, and DKT on the
  // classical plate with rotary inertia (measured 0.002 %).
  const std::string sec = "material: alu\n    thickness: 0.1";
  const LaminateStiffness L = stiffnessOf(sec);
  const double f_fsdt = navierFirstOrderShear(L.D, L.As, L.mass_per_area, L.rotary_per_area, 1, 1, 1, 1) / (2 * M_PI);
  const double k2 = 2 * M_PI * M_PI;
  const double f_rayleigh = std::sqrt(L.D(0, 0) * k2 * k2 / (L.mass_per_area + L.rotary_per_area * k2)) / (2 * M_PI);
  // Measured with row-sum lumping (the element, not the lumping, is under test
  // here; the default lumped_moments moves mass to the pinned edges and lowers
  // this 20 x 20 mesh's DKT frequency by 0.3 %).
  const BuildResult dst = runYaml(plateYaml(sec, 1.0, 1.0, "dst", 0.05, kSimplySupported, 1) + "  mass: lumped\n");
  const BuildResult dkt = runYaml(plateYaml(sec, 1.0, 1.0, "dkt", 0.05, kSimplySupported, 1) + "  mass: lumped\n");
  EXPECT_LT(dst.body.frequencies_hz(0), f_fsdt);
  EXPECT_GT(dst.body.frequencies_hz(0), 0.96 * f_fsdt);
  EXPECT_NEAR(dkt.body.frequencies_hz(0) / f_rayleigh, 1.0, 0.003);
}

TEST(PlateModes, ThinPlateDstEqualsDkt) {
  // a/h = 1000: the shear energy is ~(h/a)^2 = 1e-6 of the bending energy.
  const std::string sec = "material: alu\n    thickness: 0.001";
  const BuildResult dst = runYaml(plateYaml(sec, 1.0, 1.0, "dst", 0.1, kSimplySupported, 4));
  const BuildResult dkt = runYaml(plateYaml(sec, 1.0, 1.0, "dkt", 0.1, kSimplySupported, 4));
  for (long i = 0; i < 4; ++i) EXPECT_NEAR(dst.body.frequencies_hz(i) / dkt.body.frequencies_hz(i), 1.0, 1e-4);
}

TEST(PlateModes, CantileverSquareMatchesLeissa) {
  const std::string sec = "material: alu\n    thickness: 0.01";
  const LaminateStiffness L = stiffnessOf(sec);
  const double scale = std::sqrt(L.D(0, 0) / L.mass_per_area) / (2 * M_PI);  // a = 1
  std::vector<double> want;
  for (double lam : kLeissaCantileverSquare) want.push_back(lam * scale);
  const BuildResult r = runYaml(plateYaml(sec, 1.0, 1.0, "dkt", 0.05, "{clamp: [edge_xmin]}", 5));
  EXPECT_EQ(r.rigid_removed, 0);
  // Leissa's Ritz values are upper bounds; DKT with lumped mass at h = a/20 lies
  // 0.4-1.1 % below them (measured).
  expectRelative(r.body.frequencies_hz, want, 0.015, "cantilever");
}

TEST(PlateModes, FreeFreeRemovesExactlySixRigidModes) {
  const std::string sec = "material: alu\n    thickness: 0.01";
  const LaminateStiffness L = stiffnessOf(sec);
  const double scale = std::sqrt(L.D(0, 0) / L.mass_per_area) / (2 * M_PI);
  const BuildResult r = runYaml(plateYaml(sec, 1.0, 1.0, "dkt", 0.05, "free", 3));
  EXPECT_EQ(r.rigid_removed, 6);
  // The removed modes lie in the rigid space (share 1) and are at omega ~ 0;
  // the kept ones have no rigid part (exact M-orthogonality up to solver tolerance).
  EXPECT_GT(r.rigid_share_removed_min, 1 - 1e-8);
  EXPECT_LT(r.rigid_share_kept_max, 1e-8);
  for (long i = 0; i < r.rigid_eigenvalues.size(); ++i)
    EXPECT_LT(std::abs(r.rigid_eigenvalues(i)), 1e-6 * r.body.eigenvalues(0));
  std::vector<double> want;
  for (double lam : kLeissaFreeSquare) want.push_back(lam * scale);
  expectRelative(r.body.frequencies_hz, want, 0.015, "free-free");
}

TEST(PlateModes, TwoPinsLeaveOneRigidRotationWhichIsRemoved) {
  // Pinned at two points of the x axis, the panel still turns about that line.
  std::string yaml = plateYaml("material: alu\n    thickness: 0.01", 1.0, 0.6, "dkt", 0.1, "{pin: [A, B]}", 3);
  yaml.replace(yaml.find("  reference:"), 0, "  interfaces: {A: [-0.5, 0.0, 0.0], B: [0.5, 0.0, 0.0]}\n");
  const BuildResult r = runYaml(yaml);
  EXPECT_EQ(r.rigid_removed, 1);
  EXPECT_GT(r.rigid_share_removed_min, 1 - 1e-8);
  EXPECT_LT(r.rigid_share_kept_max, 1e-8);
  EXPECT_GT(r.body.frequencies_hz(0), 1.0);
}

TEST(PlateModes, FrequenciesConvergeWithTheMesh) {
  // The error against Navier must fall as the mesh is refined (DKT: O(h^2)).
  const std::string sec = "material: alu\n    thickness: 0.01";
  const double f = navierList(stiffnessOf(sec), 1.0, 1.0, 1, false)[0];
  double previous = 1.0;
  for (double h : {0.2, 0.1, 0.05}) {
    const double err = std::abs(runYaml(plateYaml(sec, 1.0, 1.0, "dkt", h, kSimplySupported, 1)).body.frequencies_hz(0) / f - 1);
    EXPECT_LT(err, previous) << "h = " << h;
    previous = err;
  }
}

}  // namespace
}  // namespace fc::feprep::test
