// Bodies from mesh files with regions (contracts.md, "General bodies"): gmsh
// physical groups carry shell and beam properties, shells and beams sharing
// nodes form one body, each element has its own laminate and material axis.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/input.h"
#include "fe-prep/body_inertia.h"
#include "fe-prep/element_properties.h"
#include "feprep_test_support.h"

namespace fc::feprep::test {
namespace {

const char* const kLibrary = R"(
materials:
  alu: {type: isotropic, E: 70.0e9, nu: 0.3, rho: 2700}
  im6: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9,
        G12: 7.6e9, G13: 7.6e9, G23: 8.504e9, nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600}
laminates:
  layup2:
    - {material: im6, thickness: 0.0005, angle_deg: 0}
    - {material: im6, thickness: 0.0005, angle_deg: 90}
    - {material: im6, thickness: 0.0005, angle_deg: 90}
    - {material: im6, thickness: 0.0005, angle_deg: 0}
  ud0: [{material: im6, thickness: 0.002, angle_deg: 0}]
  ud90: [{material: im6, thickness: 0.002, angle_deg: 90}]
)";

void write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// A 0.6 x 0.4 m panel at z = 0 with a stringer line along y = 0 embedded in
// the skin (the stringer's line elements share the skin's nodes), the root
// edge x = -0.3 as a group of two curves. `split` puts the halves y < 0 and
// y > 0 in two surface groups skin_a, skin_b.
std::string panelGeo(double h, bool split) {
  std::string g = "h = " + std::to_string(h) + R"(;
Point(1) = {-0.3, -0.2, 0, h}; Point(2) = {0.3, -0.2, 0, h}; Point(3) = {0.3, 0.2, 0, h};
Point(4) = {-0.3, 0.2, 0, h}; Point(5) = {-0.3, 0, 0, h}; Point(6) = {0.3, 0, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 6}; Line(3) = {6, 3}; Line(4) = {3, 4}; Line(5) = {4, 5}; Line(6) = {5, 1};
Line(7) = {5, 6};
Curve Loop(1) = {1, 2, -7, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {7, 3, 4, 5}; Plane Surface(2) = {2};
Physical Curve("stringer") = {7};
Physical Curve("root") = {5, 6};
Physical Point("corner") = {3};
)";
  g += split ? "Physical Surface(\"skin_a\") = {1};\nPhysical Surface(\"skin_b\") = {2};\n"
             : "Physical Surface(\"skin\") = {1, 2};\n";
  return g;
}

// Meshes a .geo with gmsh and saves it as .msh in the given format version
// (2.2 or 4.1); recombine: quadrilaterals.
void saveMsh(const std::string& geo, const std::string& msh, double version, bool recombine = false, int order = 1) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(geo);
  if (recombine) gmsh::option::setNumber("Mesh.RecombineAll", 1);
  gmsh::model::mesh::generate(2);
  if (order > 1) gmsh::model::mesh::setOrder(order);
  gmsh::option::setNumber("Mesh.MshFileVersion", version);
  gmsh::write(msh);
  gmsh::finalize();
}

std::string stiffenedYaml(const std::string& file, const std::string& extra = "", const std::string& skin = "skin") {
  return std::string(kLibrary) + R"(
body:
  name: stiffened
  mesh: {file: )" + file + R"(}
  regions:
    )" + skin + R"(: {shell: {laminate: layup2, element: dst}}
    stringer: {beam: {section: {shape: rectangle, width: 0.01, height: 0.03, material: alu}, orientation: [0, 0, 1]}}
)" + extra + R"(
  modes: 6
)";
}

double maxRelDiff(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// A `shell:` body on a .geo and the same surface as a one-region mesh-file body
// build the same matrices: the eigenvalues and shapes are equal bit for bit.
TEST(GeneralMesh, OneRegionIsTheShellBody) {
  const std::string dir = scratchDir("general_mesh_legacy");
  write(dir + "/plate.geo", R"(
Point(1) = {-0.3, -0.2, 0, 0.05}; Point(2) = {0.3, -0.2, 0, 0.05}; Point(3) = {0.3, 0.2, 0, 0.05}; Point(4) = {-0.3, 0.2, 0, 0.05};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Surface("plate") = {1};
Physical Curve("root") = {4};
)");
  const BuildResult legacy = runYaml(std::string(kLibrary) + "body:\n  shell: {laminate: layup2, mesh: {file: " + dir +
                                     "/plate.geo}}\n  reference: {clamp: [root]}\n  modes: 6\n");
  const BuildResult general = runYaml(std::string(kLibrary) + "body:\n  mesh: {file: " + dir +
                                      "/plate.geo}\n  regions:\n    plate: {shell: {laminate: layup2}}\n"
                                      "  reference: {clamp: [root]}\n  modes: 6\n");
  ASSERT_EQ(legacy.body.nodes.rows(), general.body.nodes.rows());
  EXPECT_EQ((legacy.body.nodes - general.body.nodes).cwiseAbs().maxCoeff(), 0.0);
  for (long j = 0; j < 6; ++j) EXPECT_EQ(legacy.body.eigenvalues(j), general.body.eigenvalues(j)) << j;
  EXPECT_EQ((legacy.body.shapes - general.body.shapes).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(legacy.body.mass, general.body.mass);
}

// The stiffened panel from its .geo and from .msh files of formats 2.2 and 4.1
// (written by gmsh from the same mesh) is the same body; the stringer's beam
// elements share the skin's nodes, so the stringer stiffens the skin.
TEST(GeneralMesh, GeoAndMshFormatsGiveTheSameStiffenedPanel) {
  const std::string dir = scratchDir("general_mesh_formats");
  write(dir + "/panel.geo", panelGeo(0.05, false));
  saveMsh(dir + "/panel.geo", dir + "/panel22.msh", 2.2);
  saveMsh(dir + "/panel.geo", dir + "/panel41.msh", 4.1);
  const std::string held = "  reference: {clamp: [root]}\n";
  const BuildResult geo = runYaml(stiffenedYaml(dir + "/panel.geo", held));
  const BuildResult m22 = runYaml(stiffenedYaml(dir + "/panel22.msh", held));
  const BuildResult m41 = runYaml(stiffenedYaml(dir + "/panel41.msh", held));
  ASSERT_TRUE(geo.body.elements.count("triangles") && geo.body.elements.count("beams"));
  // The stringer: one beam element per mesh segment of the 0.6 m line, on skin nodes.
  const IndexMatrix& beams = geo.body.elements.at("beams");
  EXPECT_GE(beams.rows(), 12);
  const IndexMatrix& tri = geo.body.elements.at("triangles");
  for (long e = 0; e < beams.rows(); ++e)
    for (int k = 0; k < 2; ++k) EXPECT_TRUE((tri.array() == beams(e, k)).any()) << "beam node not on the skin";
  // Same mesh written twice: equal up to the .msh files' printed digits (gmsh
  // writes coordinates with 16 significant digits: ~1e-16 relative) and the
  // eigen-solver's tolerance (1e-10 relative residual: ~1e-10 on eigenvalues).
  for (const BuildResult* r : {&m22, &m41}) {
    ASSERT_EQ(r->body.nodes.rows(), geo.body.nodes.rows());
    EXPECT_LT((r->body.nodes - geo.body.nodes).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT(maxRelDiff(r->body.eigenvalues, geo.body.eigenvalues), 1e-9);
  }
  // The stringer (EI about the skin normal-stiff axis) raises the clamped panel's first bending mode.
  const BuildResult bare = runYaml(std::string(kLibrary) + "body:\n  mesh: {file: " + dir +
                                   "/panel.geo}\n  regions:\n    skin: {shell: {laminate: layup2}}\n"
                                   "  ignore: [stringer]\n" + held + "  modes: 6\n");
  EXPECT_GT(geo.body.frequencies_hz(0), 1.5 * bare.body.frequencies_hz(0));
}

// Quadrilaterals are split into two triangles each; second-order elements are refused.
TEST(GeneralMesh, QuadrilateralsSplitAndSecondOrderRefused) {
  const std::string dir = scratchDir("general_mesh_quads");
  write(dir + "/panel.geo", panelGeo(0.05, false));
  saveMsh(dir + "/panel.geo", dir + "/quads.msh", 4.1, true);
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(dir + "/quads.msh");
  std::vector<std::size_t> qt, qn, tt, tn;
  gmsh::model::mesh::getElementsByType(3, qt, qn, -1);
  gmsh::model::mesh::getElementsByType(2, tt, tn, -1);
  gmsh::finalize();
  ASSERT_GT(qt.size(), 0u);
  const BuildResult q = runYaml(stiffenedYaml(dir + "/quads.msh", "  reference: {clamp: [root]}\n"));
  EXPECT_EQ(static_cast<std::size_t>(q.body.elements.at("triangles").rows()), 2 * qt.size() + tt.size());

  saveMsh(dir + "/panel.geo", dir + "/order2.msh", 4.1, false, 2);
  try {
    runYaml(stiffenedYaml(dir + "/order2.msh", "  reference: {clamp: [root]}\n"));
    FAIL() << "second-order elements accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gmsh -order 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("body.mesh.file"), std::string::npos) << e.what();
  }
}

// Input errors name the group: a region no group has (did you mean), a group
// with elements that is no region, set or ignored (with its element count).
TEST(GeneralMesh, RegionErrorsNameTheGroup) {
  const std::string dir = scratchDir("general_mesh_errors");
  write(dir + "/panel.geo", panelGeo(0.1, false));
  try {
    runYaml(stiffenedYaml(dir + "/panel.geo", "", "skn"));
    FAIL() << "unknown region accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("region 'skn' is no physical group"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean 'skin'"), std::string::npos) << e.what();
  }
  try {
    runYaml(std::string(kLibrary) + "body:\n  mesh: {file: " + dir +
            "/panel.geo}\n  regions:\n    skin: {shell: {laminate: layup2}}\n  reference: {clamp: [root]}\n  modes: 4\n");
    FAIL() << "a group of elements without a region accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'stringer'"), std::string::npos) << m;
    EXPECT_NE(m.find("belong to no region"), std::string::npos) << m;
    EXPECT_NE(m.find(" has 6 "), std::string::npos) << m;  // 0.6 m at h = 0.1
  }
  try {
    runYaml(std::string(kLibrary) + "body:\n  mesh: {file: " + dir +
            "/panel.geo}\n  regions:\n    skin: {shell: {laminate: layup2}}\n  ignore: [stringer, root]\n"
            "  interfaces:\n    fit: {point: [0.3, 0.2, 0], coupling: rigid, nodes: {set: cornr}}\n  modes: 4\n");
    FAIL() << "an unknown set accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'corner'"), std::string::npos) << e.what();
  }
}

// Two regions of the same laminate are the one-region body; a unidirectional
// ply with its reference axis along y is the 90-degree ply with axis x.
TEST(GeneralMesh, RegionsAndMaterialAxes) {
  const std::string dir = scratchDir("general_mesh_axes");
  write(dir + "/whole.geo", panelGeo(0.05, false));
  write(dir + "/split.geo", panelGeo(0.05, true));
  const std::string stringer =
      "    stringer: {beam: {section: {shape: rectangle, width: 0.01, height: 0.03, material: alu}, orientation: [0, 0, 1]}}\n";
  auto body = [&](const std::string& file, const std::string& regions) {
    return runYaml(std::string(kLibrary) + "body:\n  mesh: {file: " + dir + "/" + file + "}\n  regions:\n" + regions +
                   stringer + "  reference: {clamp: [root]}\n  modes: 6\n");
  };
  const BuildResult whole = body("whole.geo", "    skin: {shell: {laminate: ud0, axis: [0, 1, 0]}}\n");
  const BuildResult split = body("split.geo", "    skin_a: {shell: {laminate: ud0, axis: [0, 1, 0]}}\n"
                                              "    skin_b: {shell: {laminate: ud90, axis: [1, 0, 0]}}\n");
  const BuildResult rotated = body("whole.geo", "    skin: {shell: {laminate: ud90}}\n");
  // The same matrices up to the 90-degree ply rotation's rounding (cos 90 deg
  // = 6e-17): the eigenvalues agree to the solver's tolerance.
  EXPECT_LT(maxRelDiff(split.body.eigenvalues, whole.body.eigenvalues), 1e-8);
  EXPECT_LT(maxRelDiff(rotated.body.eigenvalues, whole.body.eigenvalues), 1e-8);
  // ...and the fibres along x give a different (stiffer in x-bending) panel.
  const BuildResult along_x = body("whole.geo", "    skin: {shell: {laminate: ud0}}\n");
  EXPECT_GT(std::abs(along_x.body.eigenvalues(0) / whole.body.eigenvalues(0) - 1.0), 0.1);
}

// A cylindrical system's hoop direction is axis x radial, its axial the axis.
TEST(GeneralMesh, CylindricalReferenceAxis) {
  MaterialAxis a;
  a.kind = MaterialAxis::Kind::Cylindrical;
  a.origin = Eigen::Vector3d(1, 0, 0);
  a.direction = Eigen::Vector3d::UnitZ();
  a.hoop = true;
  EXPECT_LT((referenceAxisAt(a, Eigen::Vector3d(3, 0, 5)) - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  EXPECT_LT((referenceAxisAt(a, Eigen::Vector3d(1, 2, 5)) + Eigen::Vector3d::UnitX()).norm(), 1e-15);
  a.hoop = false;
  EXPECT_EQ(referenceAxisAt(a, Eigen::Vector3d(3, 0, 5)), Eigen::Vector3d::UnitZ());
}

// Mass properties of the stiffened panel with a concentrated mass and a
// non-structural mass: the closed forms of a uniform plate, a bar along y = 0
// and a point, to rounding (1e-12 relative).
TEST(GeneralMesh, MassPropertiesOfRegionsAndMasses) {
  const std::string dir = scratchDir("general_mesh_mass");
  write(dir + "/panel.geo", panelGeo(0.05, false));
  const std::string yaml = std::string(kLibrary) + "body:\n  mesh: {file: " + dir + "/panel.geo}\n  regions:\n"
      "    skin: {shell: {laminate: layup2}, non_structural_mass: 0.15}\n"
      "    stringer: {beam: {section: {shape: rectangle, width: 0.01, height: 0.03, material: alu}, orientation: [0, 0, 1]}}\n"
      "  ignore: [root]\n  masses:\n    - {at: [0.3, 0.2, 0.0], mass: 0.2, inertia: [[1e-3, 0, 0], [0, 2e-3, 0], [0, 0, 3e-3]]}\n"
      "  modes: 4\n";
  const BuildResult r = runYaml(yaml);
  const double rhoA = 1600 * 0.002 + 0.15, A = 0.6 * 0.4;
  const double mu = 2700 * 0.01 * 0.03, L = 0.6, m = 0.2;
  const double mass = rhoA * A + mu * L + m;
  EXPECT_NEAR(r.body.exact_mass, mass, 1e-12 * mass);
  // Second moments E = int rho p p^T about the origin: the plate (a = 0.6 along
  // x, b = 0.4, symmetric lay-up: rotary int rho z^2 = rho t^3/12 per area, the
  // non-structural mass on the mid-surface), the bar along x at y = z = 0
  // (section terms rho (w h^3 + h w^3)/12 across it, whichever of y and z its
  // x2 is), the point at (0.3, 0.2, 0) with E_c = tr(J)/2 I - J.
  const Eigen::Matrix3d J = r.body.exact_inertia_tensor;
  const double plate_rot = 1600 * std::pow(0.002, 3) / 12 * A;
  const double bar_section = 2700 * (0.01 * std::pow(0.03, 3) + 0.03 * std::pow(0.01, 3)) / 12 * L;
  const double Jxx = rhoA * A * 0.4 * 0.4 / 12 + plate_rot + bar_section + m * 0.04 + 1e-3;
  const double Exx = rhoA * A * 0.6 * 0.6 / 12 + mu * L * L * L / 12 + m * 0.09 + (6e-3 / 2 - 1e-3);
  EXPECT_NEAR(J(0, 0), Jxx, 1e-12 * Jxx);
  EXPECT_NEAR(0.5 * (J(1, 1) + J(2, 2) - J(0, 0)), Exx, 1e-12 * Exx);
  EXPECT_NEAR(J(2, 1), 0.0, 1e-12 * Jxx);  // Jyz: nothing off the z = 0 plane
  EXPECT_NEAR(J(0, 1), -m * 0.3 * 0.2, 1e-12 * Jxx);  // Jxy = -sum m x y: only the point is off-centre
}

// CalculiX's frequencies of the curved panel (tests/data/fe-prep/curved_panel/ccx_frequencies.txt).
std::vector<double> curvedPanelCalculix(const std::string& which) {
  std::ifstream in(std::string(FLEXCOMP_DATA_DIR) + "/fe-prep/curved_panel/ccx_frequencies.txt");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key != which) continue;
    std::vector<double> f;
    for (double v; ls >> v;) f.push_back(v);
    return f;
  }
  throw std::runtime_error("no CalculiX row " + which);
}

// A curved [0/90/90/0] panel (cylindrical segment R = 0.5 m, 60 deg, 0.5 m
// high, clamped on its arc edge) with the 0-degree fibres along the axis and
// then along the arc, from a gmsh 2.2 file of 64 x 64 quadrilaterals, against
// CalculiX 2.20 S8R composite shells whose layers follow the axis or the hoop
// tangent (make_meshes.py there; converged to 1.1e-4). 1 %: the issue's bound;
// the flat DST facets of a 40 x 40 mesh were 1.4 % stiff in modes 3-5, those
// of 64 x 64 are within it. The two lay-ups differ as CalculiX says (its
// first frequency 52.95 Hz axial, 75.35 Hz hoop): each is checked against its own.
TEST(GeneralMesh, CurvedCompositePanelAgainstCalculix) {
  const std::string dir = std::string(FLEXCOMP_DATA_DIR) + "/fe-prep/curved_panel";
  for (const std::string along : {"axial", "hoop"}) {
    const BuildResult r = runYaml(std::string(kLibrary) + "body:\n  mesh: {file: " + dir + "/panel.msh}\n  regions:\n"
                                  "    shell: {shell: {laminate: layup2, axis: {cylindrical: {origin: [0, 0, 0], "
                                  "direction: [0, 0, 1]}, along: " + along + "}}}\n"
                                  "  reference: {clamp: [root]}\n  modes: 6\n");
    const std::vector<double> ccx = curvedPanelCalculix(along);
    for (long j = 0; j < 6; ++j) {
      const double f = r.body.frequencies_hz(j);
      EXPECT_NEAR(f / ccx[static_cast<std::size_t>(j)], 1.0, 0.01) << along << " mode " << j + 1 << ": " << f << " Hz, CalculiX "
                                                                  << ccx[static_cast<std::size_t>(j)];
    }
  }
}

// CalculiX's results for the stiffened panel (tests/data/calculix/stiffened_panel/ccx_results.txt).
std::vector<double> stiffenedPanelCalculix(const std::string& key) {
  std::ifstream in(std::string(FLEXCOMP_DATA_DIR) + "/calculix/stiffened_panel/ccx_results.txt");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string k, n;
    ls >> k >> n;
    if (k + " " + n != key) continue;
    std::vector<double> v;
    for (double x; ls >> x;) v.push_back(x);
    return v;
  }
  throw std::runtime_error("no CalculiX row " + key);
}

// The stiffened panel's skin material and laminate (IM6, 0.25 mm plies;
// [0/45/-45/90]s unless given), as the CalculiX decks and ritz_skin.py have them.
std::string stiffenedSkinLibrary(const std::vector<int>& angles = {0, 45, -45, 90, 90, -45, 45, 0}) {
  std::string lam = "laminates:\n  skin: [";
  for (std::size_t k = 0; k < angles.size(); ++k)
    lam += std::string(k ? ", " : "") + "{material: im6, thickness: 0.00025, angle_deg: " + std::to_string(angles[k]) + "}";
  return "materials:\n  im6: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9, G12: 7.6e9, G13: 7.6e9, "
         "G23: 3.6e9, nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600}\n" + lam + "]\n";
}

// The stiffened panel of examples/stiffened-panel (bare: no paint, no fitting
// mass) clamped at its root, against CalculiX 2.20: [0/45/-45/90]s S8R
// composite shells and B32R stringers on their own nodes tied to the skin's
// translations (make_decks.py there; CalculiX's rigid knots, which a shared
// node makes, stiffen this panel by 20 % in its first mode and are no
// reference). fe-prep: DST on a 64 x 40 mesh (crossed diagonals), the
// stringers sharing the skin's nodes with their torsion taken out of the
// section (stringer.h5), which is what a translation-only tie means for them.
// Measured (fe-prep 64 against CalculiX 64): f1..f10 -0.12, -0.02, +0.13,
// +0.23, +0.08, +0.04, +0.10, +0.30, +0.26, +0.23 %, uz/Fz +0.16 %. What is
// left is both sides' meshes: fe-prep 64 -> 128 moves f8-f10 by -0.14 to
// -0.21 % (O(h^2), so about 0.28 % of f10 is still mesh on 64 x 40; on
// 128 x 80 all ten are within 0.14 % of CalculiX 64), CalculiX 32 -> 64 by
// at most -0.09 %. Bound 0.5 % in all ten and the deflection: those two
// mesh errors with room, half the issue's 1 %. The decks' 90-degree plies
// are written so that CalculiX reads them as 90 degrees (make_decks.py,
// ccx_num): before that they were 58.5-degree plies in CalculiX and modes
// 3-10 differed by up to 1.8 % (docs/validation.md, the stiffened-panel row).
TEST(GeneralMesh, StiffenedPanelAgainstCalculix) {
  const std::string dir = std::string(FLEXCOMP_DATA_DIR) + "/calculix/stiffened_panel";
  const std::string lib = stiffenedSkinLibrary();
  const std::string regions = "  mesh: {file: " + dir + "/panel_64.msh}\n  mass: consistent\n  regions:\n"
                              "    skin: {shell: {laminate: skin, element: dst, axis: [1, 0, 0]}}\n"
                              "    stringers: {beam: {section: {file: " + dir + "/stringer.h5}, orientation: [0, 1, 0]}}\n"
                              "  reference: {clamp: [root]}\n";
  const BuildResult modal = runYaml(lib + "body:\n" + regions + "  ignore: [tip]\n  modes: 10\n");
  const std::vector<double> ccx = stiffenedPanelCalculix("frequencies 64");
  ASSERT_EQ(ccx.size(), 10u);
  ASSERT_EQ(modal.body.modeCount(), 10);
  for (int j = 0; j < 10; ++j) {
    const double f = modal.body.frequencies_hz(j), c = ccx[static_cast<std::size_t>(j)];
    std::printf("[   info   ] f%d: fe-prep %.5f Hz, CalculiX %.5f Hz (%+.2f %%)\n", j + 1, f, c, 100 * (f / c - 1));
    EXPECT_NEAR(f / c, 1.0, 0.005) << "mode " << j + 1;
  }
  const BuildResult stat = runYaml(lib + "body:\n" + regions +
                                   "  interfaces:\n    tip: {point: [0.4, 0, 0], coupling: rigid, nodes: {set: tip}}\n  modes: 2\n");
  const double uz = stat.body.interface("tip").static_compliance(2), c = stiffenedPanelCalculix("compliance 64")[0];
  std::printf("[   info   ] tip uz/Fz: fe-prep %.6e m/N, CalculiX %.6e m/N (%+.2f %%)\n", uz, c, 100 * (uz / c - 1));
  EXPECT_NEAR(uz / c, 1.0, 0.005);
}

// The same panel with a [0/0/90/90]s skin (make_decks.py ccx-crossply): no
// bending-twist coupling, a chordwise stiffness D22 a fifth of D11, so the
// modes reorder (f1 torsion, f2 bending, 0.3 Hz apart, and the chordwise skin
// modes come down) and the 90-degree plies, the ones the old decks misread,
// carry most of D22. Measured (fe-prep 64 against CalculiX 64): f1..f10
// -0.08, -0.12, +0.06, +0.15, +0.00, +0.11, -0.08, +0.18, +0.14, +0.11 %.
// fe-prep 64 -> 128 moves them by at most -0.17 % (f10), CalculiX 32 -> 64 by
// at most -0.09 %; bound 0.5 % as above.
TEST(GeneralMesh, StiffenedCrossPlyPanelAgainstCalculix) {
  const std::string dir = std::string(FLEXCOMP_DATA_DIR) + "/calculix/stiffened_panel";
  const std::string lib = stiffenedSkinLibrary({0, 0, 90, 90, 90, 90, 0, 0});
  const BuildResult modal = runYaml(lib + "body:\n  mesh: {file: " + dir + "/panel_64.msh}\n  mass: consistent\n  regions:\n"
                                    "    skin: {shell: {laminate: skin, element: dst, axis: [1, 0, 0]}}\n"
                                    "    stringers: {beam: {section: {file: " + dir + "/stringer.h5}, orientation: [0, 1, 0]}}\n"
                                    "  reference: {clamp: [root]}\n  ignore: [tip]\n  modes: 10\n");
  const std::vector<double> ccx = stiffenedPanelCalculix("frequencies_crossply 64");
  ASSERT_EQ(ccx.size(), 10u);
  ASSERT_EQ(modal.body.modeCount(), 10);
  for (int j = 0; j < 10; ++j) {
    const double f = modal.body.frequencies_hz(j), c = ccx[static_cast<std::size_t>(j)];
    std::printf("[   info   ] cross-ply f%d: fe-prep %.5f Hz, CalculiX %.5f Hz (%+.2f %%)\n", j + 1, f, c, 100 * (f / c - 1));
    EXPECT_NEAR(f / c, 1.0, 0.005) << "mode " << j + 1;
  }
}

// The same skin without its stringers, the shell theory fe-prep implements:
// its ten frequencies against a Ritz solution of classical lamination theory
// for the cantilever plate with D16, D26 (Legendre degree 18 per direction,
// converged to 1e-5; ritz_skin.py, the fixture's ritz_clt_skin row). DST
// converges to it at O(h^2) from above and its transverse shear puts it below
// by 0.1-0.2 % once converged (first-order shear theory's Ritz: -0.02 to
// -0.27 %); measured on this 64 x 40 mesh -0.03 to +0.17 % (f9, f10 still
// converging: 64 -> 128 moves f9 by 0.17 %), bound 0.5 %. CalculiX's fully
// integrated layered solid of the same skin (make_solid.py, C3D20, an upper
// bound of 3-D elasticity) is within 0.3 % of the same Ritz values
// (ccx_results.txt): no 3-D effect of the +-45 plies at this a / h = 250.
TEST(GeneralMesh, StiffenedPanelSkinAgainstLaminationTheory) {
  const std::string dir = std::string(FLEXCOMP_DATA_DIR) + "/calculix/stiffened_panel";
  const std::string lib = stiffenedSkinLibrary();
  const BuildResult modal = runYaml(lib + "body:\n  mesh: {file: " + dir + "/panel_64.msh}\n  mass: consistent\n  regions:\n"
                                    "    skin: {shell: {laminate: skin, element: dst, axis: [1, 0, 0]}}\n"
                                    "  reference: {clamp: [root]}\n  ignore: [tip, stringers]\n  modes: 10\n");
  const std::vector<double> ritz = stiffenedPanelCalculix("ritz_clt_skin 0");
  ASSERT_EQ(ritz.size(), 10u);
  ASSERT_EQ(modal.body.modeCount(), 10);
  for (int j = 0; j < 10; ++j) {
    const double f = modal.body.frequencies_hz(j), r = ritz[static_cast<std::size_t>(j)];
    std::printf("[   info   ] skin f%d: fe-prep %.5f Hz, Ritz CLT %.5f Hz (%+.3f %%)\n", j + 1, f, r, 100 * (f / r - 1));
    EXPECT_NEAR(f / r, 1.0, 0.005) << "mode " << j + 1;
  }
}

}  // namespace
}  // namespace fc::feprep::test
