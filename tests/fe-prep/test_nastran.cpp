// Nastran bulk-data decks as bodies (fe-prep/mesh_files/nastran.h, docs/nastran.md):
// the stiffened panel of examples/stiffened-panel as a deck (tests/data/fe-prep/nastran,
// make_decks.py) against the same mesh as a gmsh .msh with YAML regions; the field
// formats; the units; every refusal located; PBARL sections against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "common/h5io.h"
#include "common/input.h"
#include "common/inspect.h"
#include "fe-prep/mesh_files/nastran.h"
#include "feprep_test_support.h"

namespace fc::feprep::test {
namespace {

const std::string kData = std::string(FLEXCOMP_DATA_DIR) + "/fe-prep/nastran/";

// The .msh route: the example's YAML (examples/stiffened-panel/panel.yaml) on the
// structured mesh, the root edge clamped.
std::string mshYaml() {
  return R"(
materials:
  alu: {type: isotropic, E: 70.0e9, nu: 0.33, rho: 2700}
  im6: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9,
        G12: 7.6e9, G13: 7.6e9, G23: 3.6e9, nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600}
laminates:
  skin_layup:
    - {material: im6, thickness: 0.00025, angle_deg: 0}
    - {material: im6, thickness: 0.00025, angle_deg: 45}
    - {material: im6, thickness: 0.00025, angle_deg: -45}
    - {material: im6, thickness: 0.00025, angle_deg: 90}
    - {material: im6, thickness: 0.00025, angle_deg: 90}
    - {material: im6, thickness: 0.00025, angle_deg: -45}
    - {material: im6, thickness: 0.00025, angle_deg: 45}
    - {material: im6, thickness: 0.00025, angle_deg: 0}
body:
  name: stiffened_panel
  mesh: {file: )" + kData + R"(panel.msh}
  regions:
    skin:
      shell: {laminate: skin_layup, element: dst, axis: [1, 0, 0]}
      non_structural_mass: 0.2
    stringers:
      beam: {section: {shape: rectangle, width: 0.004, height: 0.025, material: alu}, orientation: [0, 1, 0]}
  masses:
    - {at: fitting, mass: 0.15}
  interfaces:
    hinge: {point: [-0.4, 0.0, 0.0], coupling: rigid, nodes: {set: root}}
    fitting: [0.4, 0.25, 0.0]
  reference: {clamp: [hinge]}
  modes: 10
)";
}

// The deck route: properties, the clamp (SPC1 1), the hinge (RBE2 9100) and the
// fitting's mass (CONM2 9200 on GRID 153) all from the deck.
std::string deckYaml(const std::string& deck, const std::string& units = "m-kg-s") {
  return "body:\n  name: stiffened_panel\n  mesh: {file: " + kData + deck + "}\n  units: " + units +
         "\n  interfaces:\n    hinge: {rbe: 9100}\n    fitting: {grid: 153}\n  reference: {clamp: [hinge]}\n  modes: 10\n";
}

Eigen::MatrixXd sortedRows(const Eigen::MatrixXd& a) {
  std::vector<Eigen::RowVectorXd> r;
  for (long i = 0; i < a.rows(); ++i) r.push_back(a.row(i));
  std::sort(r.begin(), r.end(), [](const Eigen::RowVectorXd& x, const Eigen::RowVectorXd& y) {
    return std::lexicographical_compare(x.data(), x.data() + x.size(), y.data(), y.data() + y.size());
  });
  Eigen::MatrixXd s(a.rows(), a.cols());
  for (long i = 0; i < a.rows(); ++i) s.row(i) = r[static_cast<std::size_t>(i)];
  return s;
}

// The same mesh and properties by the two routes give the same body: nodes (the
// decks' decimals are the .msh's: exact in m, 1 ulp after the mm-t-s scaling),
// mass, inertia and eigenvalues to 1e-10 (the same matrices up to node order and
// the last bits of the unit conversions; the eigen-solver converges to 1e-10
// relative residual, and an eigenvalue's error is of the residual's square).
TEST(Nastran, DeckGivesTheMshBody) {
  const BuildResult msh = runYaml(mshYaml());
  ASSERT_EQ(msh.body.elements.at("triangles").rows(), 2 * 16 * 8);
  ASSERT_EQ(msh.body.elements.at("beams").rows(), 32);
  for (const auto& [deck, units] : std::vector<std::pair<std::string, std::string>>{
           {"panel_small.bdf", "m-kg-s"}, {"panel_large.bdf", "m-kg-s"}, {"panel_free.bdf", "m-kg-s"}, {"panel_mm.bdf", "mm-t-s"}}) {
    SCOPED_TRACE(deck);
    const BuildResult d = runYaml(deckYaml(deck, units));
    ASSERT_EQ(d.body.nodes.rows(), msh.body.nodes.rows());
    EXPECT_LT((sortedRows(d.body.nodes) - sortedRows(msh.body.nodes)).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(d.body.elements.at("triangles").rows(), msh.body.elements.at("triangles").rows());
    EXPECT_EQ(d.body.elements.at("beams").rows(), msh.body.elements.at("beams").rows());
    EXPECT_NEAR(d.body.mass, msh.body.mass, 1e-12 * msh.body.mass);
    EXPECT_LT((d.body.inertia_tensor - msh.body.inertia_tensor).cwiseAbs().maxCoeff(),
              1e-12 * msh.body.inertia_tensor.cwiseAbs().maxCoeff());
    ASSERT_EQ(d.body.eigenvalues.size(), msh.body.eigenvalues.size());
    for (long j = 0; j < msh.body.eigenvalues.size(); ++j)
      EXPECT_NEAR(d.body.eigenvalues(j), msh.body.eigenvalues(j), 1e-10 * msh.body.eigenvalues(j)) << j;
    for (const char* name : {"hinge", "fitting"})
      EXPECT_LT((d.body.interface(name).position - msh.body.interface(name).position).norm(), 1e-15) << name;
  }
  // The deck's SPC1 set 1 (the root grids, 123456) held as the .msh's root group.
  std::string spc = deckYaml("panel_small.bdf"), root = mshYaml();
  spc.replace(spc.find("clamp: [hinge]"), 14, "clamp: [SPC1]");
  root.replace(root.find("clamp: [hinge]"), 14, "clamp: [root]");
  root.replace(root.find("    hinge: {point"), root.find("    fitting: [") - root.find("    hinge: {point"), "");
  spc.replace(spc.find("    hinge: {rbe: 9100}\n"), 23, "");
  const BuildResult by_spc = runYaml(spc), by_root = runYaml(root);
  for (long j = 0; j < by_root.body.eigenvalues.size(); ++j)
    EXPECT_NEAR(by_spc.body.eigenvalues(j), by_root.body.eigenvalues(j), 1e-10 * by_root.body.eigenvalues(j)) << j;
  // A pin: of a set the deck clamps is refused.
  std::string pin = spc;
  pin.replace(pin.find("clamp: [SPC1]"), 13, "pin: [SPC1]");
  try {
    runYaml(pin);
    ADD_FAILURE() << "pin of a 123456 set accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds components 123456; expected clamp:"), std::string::npos) << e.what();
  }
  // 0.8 x 0.5 m x 2 mm at 1600 kg/m^3 + 0.2 kg/m^2, two 0.8 m 4 x 25 mm aluminium stringers, 0.15 kg.
  EXPECT_NEAR(msh.body.mass, 0.4 * (1600 * 0.002 + 0.2) + 2 * 0.8 * 0.004 * 0.025 * 2700 + 0.15, 1e-12);
}

// Every field format and unit system reads to the same model: nodes, laminates,
// sections and material axes.
TEST(Nastran, FieldFormatsAndUnitsReadEqual) {
  const NastranModel ref = nastranModel(readNastranCards(kData + "panel_small.bdf"), unitSystem("m-kg-s"), {});
  for (const auto& [deck, units] : std::vector<std::pair<std::string, std::string>>{
           {"panel_large.bdf", "m-kg-s"}, {"panel_free.bdf", "m-kg-s"}, {"panel_mm.bdf", "mm-t-s"}}) {
    SCOPED_TRACE(deck);
    const NastranModel m = nastranModel(readNastranCards(kData + deck), unitSystem(units), {});
    ASSERT_EQ(m.mesh.nodes.rows(), ref.mesh.nodes.rows());
    EXPECT_LT((m.mesh.nodes - ref.mesh.nodes).cwiseAbs().maxCoeff(), 1e-15);
    ASSERT_EQ(m.mesh.shell_properties.size(), 1u);
    const LaminateStiffness &a = m.mesh.shell_properties[0].laminate, &b = ref.mesh.shell_properties[0].laminate;
    EXPECT_LT((a.A - b.A).norm(), 1e-12 * b.A.norm());
    EXPECT_LT((a.D - b.D).norm(), 1e-12 * b.D.norm());
    EXPECT_LT((a.As - b.As).norm(), 1e-12 * b.As.norm());
    EXPECT_NEAR(a.mass_per_area, b.mass_per_area, 1e-12 * b.mass_per_area);
    ASSERT_EQ(m.mesh.beam_properties.size(), 1u);
    EXPECT_LT((m.mesh.beam_properties[0].Ks - ref.mesh.beam_properties[0].Ks).norm(), 1e-12 * ref.mesh.beam_properties[0].Ks.norm());
    EXPECT_LT((m.mesh.beam_properties[0].Ms - ref.mesh.beam_properties[0].Ms).norm(), 1e-12 * ref.mesh.beam_properties[0].Ms.norm());
    for (std::size_t e = 0; e < ref.mesh.triangle_axis.size(); ++e)
      EXPECT_LT((m.mesh.triangle_axis[e] - ref.mesh.triangle_axis[e]).norm(), 1e-15) << e;
    EXPECT_EQ(m.mesh.sets.at("SPC1"), ref.mesh.sets.at("SPC1"));
    EXPECT_EQ(m.mesh.point_masses.size(), 1u);
    EXPECT_NEAR(m.mesh.point_masses[0].mass, 0.15, 1e-15);
  }
  EXPECT_EQ(ref.element_counts.at("CQUAD4"), 128);
  EXPECT_EQ(ref.element_counts.at("CBAR"), 32);
  // The card after ENDDATA (GRID 999999) is not read.
  EXPECT_FALSE(ref.grid_point.count(999999));
}

std::string writeDeck(const std::string& name, const std::string& text) {
  const std::string path = scratchDir("nastran_decks") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// Reads `text` as a deck and returns the error message ("" if it was accepted).
std::string deckError(const std::string& text, const std::vector<std::string>& ignore = {}) {
  const std::string path = writeDeck("bad.bdf", text);
  try {
    nastranModel(readNastranCards(path), unitSystem("m-kg-s"), ignore);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A continuation read from an included file: its fields are located there
// (NastranCard::other_files), the card's first line stays in the deck.
TEST(Nastran, ContinuationFromAnIncludeIsLocatedThere) {
  writeDeck("cont.inc", "+,abc\n");
  const std::string path = writeDeck("cont.bdf", "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nMAT1,1,7.e10,,0.3,2700.\n"
                                                 "PBARL,1,1,,ROD\nINCLUDE 'cont.inc'\nCBAR,1,1,1,2,0.,1.,0.\n");
  std::string e;
  try {
    nastranModel(readNastranCards(path), unitSystem("m-kg-s"), {});
  } catch (const InputError& x) {
    e = x.what();
  }
  EXPECT_NE(e.find("cont.inc:1"), std::string::npos) << e;
  EXPECT_NE(e.find("ABC"), std::string::npos) << e;
}

// A one-element deck the error cases edit.
const char* const kPlate = R"($ one plate and one bar
GRID,1,,0.,0.,0.
GRID,2,,1.,0.,0.
GRID,3,,1.,1.,0.
GRID,4,,0.,1.,0.
MAT1,1,7.e10,,0.3,2700.
PSHELL,1,1,0.002,1
CQUAD4,1,1,1,2,3,4
PBARL,2,1,,BAR
+,0.01,0.02
CBAR,2,2,1,2,0.,0.,1.
)";

TEST(Nastran, BadInputIsLocated) {
  EXPECT_EQ(deckError(kPlate), "");
  struct Case {
    std::string edit, expect[3];
  };
  const std::vector<Case> cases = {
      {"GRID,5,,abc,0.,0.\n", {"bad.bdf:12", "GRID", "field 4 (X1)"}},
      {"CQUAD4,7,1,1,2,3,9\n", {"bad.bdf:12", "no GRID 9", "field 7 (G4)"}},
      {"PCOMP,5,,,,,,,SMEAR\n+,1,0.001,0.\n", {"bad.bdf:12", "LAM = SMEAR is not supported", "field 9 (LAM)"}},
      {"PCOMP,5,-0.004\n+,1,0.001,0.\n", {"bad.bdf:12", "Z0", "offset"}},
      {"CBAR,9,2,2,3,0.,0.,1.\n+,,,0.1\n", {"bad.bdf:13", "W1A", "offsets of the element ends are not supported"}},
      {"CQUAD4,8,1,1,2,3,4,,0.001\n", {"bad.bdf:12", "ZOFFS", "offset shells"}},
      {"CQUAD4,8,2,1,2,3,4\n", {"bad.bdf:12", "property 2 is a PBARL", "expected a PSHELL or PCOMP"}},
      {"PBARL,6,1,,HAT\n+,0.01,0.02,0.001,0.01\n", {"bad.bdf:12", "cross-section 'HAT' is not supported", "ROD, TUBE, BAR or BOX"}},
      {"CBAR,9,2,2,3,0.,1.,0.\n", {"bad.bdf:12", "parallel to the element", "X1/G0"}},
      {"RBE2,9,1,123,2\n", {"bad.bdf:12", "CM", "expected 123456"}},
      {"SPC1,1,12,1\n", {"bad.bdf:12", "components '12'", "123456 (clamp) or 123 (pin)"}},
      {"MAT1,3,7.e10,2.e10,0.3,2700.\n", {"bad.bdf:12", "field 4 (G)", "consistent"}},
      {"GRID,1,,0.,0.,0.\n", {"bad.bdf:12", "a second GRID with id 1", "field 2 (ID)"}},
      {"+,1,2\n", {"bad.bdf:12", "CBAR 2, field 2 of continuation 1 (PA)", "pin flags"}},
      {"CONM2,9,3,,-1.\n", {"bad.bdf:12", "field 5 (M)", "mass >= 0"}},
      {"CQUAD4,8,1,1,2,3,4\n+,,,,0.002\n", {"bad.bdf:13", "T1", "thicknesses are not supported"}},
      // Found by the mutation campaign: a grid moved onto its neighbours' line (was an error without location).
      {"GRID,5,,0.5,0.,0.\nCTRIA3,9,1,1,5,2\n", {"bad.bdf:13", "CTRIA3 9", "collinear"}},
  };
  for (const auto& c : cases) {
    const std::string m = deckError(std::string(kPlate) + c.edit);
    for (const auto& x : c.expect) EXPECT_NE(m.find(x), std::string::npos) << c.edit << " -> " << m;
  }
  // A continuation first in the file; a free-field line of too many fields.
  std::string m = deckError("+,1,2\n" + std::string(kPlate));
  EXPECT_NE(m.find("bad.bdf:1"), std::string::npos) << m;
  EXPECT_NE(m.find("no card before it"), std::string::npos) << m;
  m = deckError(std::string(kPlate) + "GRID,7,,0.,0.,0.,,,,,,,\n");
  EXPECT_NE(m.find("expected at most 10"), std::string::npos) << m;
}

// Cards the reader does not support are named with their count and first line,
// and are left out when listed under ignore:.
TEST(Nastran, UnsupportedCardsNamedAndIgnored) {
  const std::string deck = std::string(kPlate) + "PARAM,POST,-1\nEIGRL,10,,,12\nPARAM,AUTOSPC,YES\nCELAS2,50,1.e3,1,3\n";
  const std::string m = deckError(deck);
  EXPECT_NE(m.find("PARAM (2, first at "), std::string::npos) << m;
  EXPECT_NE(m.find("bad.bdf:12)"), std::string::npos) << m;
  EXPECT_NE(m.find("EIGRL (1, first at "), std::string::npos) << m;
  EXPECT_NE(m.find("CELAS2 (1, first at "), std::string::npos) << m;
  EXPECT_NE(m.find("bad.bdf:15"), std::string::npos) << m;
  EXPECT_NE(m.find("ignore:"), std::string::npos) << m;
  EXPECT_EQ(deckError(deck, {"PARAM", "EIGRL", "CELAS2"}), "");
  // ignore: also takes a property: its elements are left out.
  const std::string path = writeDeck("ignored.bdf", deck);
  const NastranModel without_bar = nastranModel(readNastranCards(path), unitSystem("m-kg-s"), {"PARAM", "EIGRL", "CELAS2", "PID2"});
  EXPECT_EQ(without_bar.mesh.beams.size(), 0u);
  EXPECT_EQ(without_bar.mesh.triangles.size(), 2u);
}

// PBARL ROD, TUBE, BAR and BOX against the closed forms of their area, second
// moments and torsion constant (exact for ROD, TUBE, BOX's area and moments;
// BAR's J is Roark's series, 0.5 %; BOX's J is Bredt's thin-walled formula,
// written here as 4 Am^2 / (closed integral ds / t)), and the orientation
// vector: DIM1 lies along v (x2), DIM2 along z (x3).
TEST(Nastran, PbarlSectionsAgainstClosedForms) {
  const double E = 7.0e10, nu = 0.3, G = E / (2 * (1 + nu)), rho = 2700;
  const std::string deck = std::string(R"(GRID,1,,0.,0.,0.
GRID,2,,1.,0.,0.
MAT1,1,7.e10,,0.3,2700.
PBARL,1,1,,ROD
+,0.01
PBARL,2,1,,TUBE
+,0.02,0.015
PBARL,3,1,,BAR
+,0.01,0.03
PBARL,4,1,,BOX
+,0.04,0.06,0.003,0.002,0.5
CBAR,1,1,1,2,0.,1.,0.
CBAR,2,2,1,2,0.,1.,0.
CBAR,3,3,1,2,0.,1.,0.
CBAR,4,4,1,2,0.,1.,0.
)");
  const NastranModel m = nastranModel(readNastranCards(writeDeck("pbarl.bdf", deck)), unitSystem("m-kg-s"), {});
  ASSERT_EQ(m.mesh.beam_properties.size(), 4u);
  struct Expect {
    double A, Iy, Iz, J;  // Iy = int z^2 (about the v-normal axis: bending in the x-z plane), Iz = int y^2
  };
  const double r = 0.01, ro = 0.02, ri = 0.015, b = 0.01, h = 0.03;
  const double W = 0.04, H = 0.06, t1 = 0.003, t2 = 0.002;
  const double Am = (W - t2) * (H - t1);
  const Expect ex[4] = {
      {M_PI * r * r, M_PI * std::pow(r, 4) / 4, M_PI * std::pow(r, 4) / 4, M_PI * std::pow(r, 4) / 2},
      {M_PI * (ro * ro - ri * ri), M_PI * (std::pow(ro, 4) - std::pow(ri, 4)) / 4, M_PI * (std::pow(ro, 4) - std::pow(ri, 4)) / 4,
       M_PI * (std::pow(ro, 4) - std::pow(ri, 4)) / 2},
      {b * h, b * h * h * h / 12, h * b * b * b / 12, b * b * b * h * (1.0 / 3 - 0.21 * b / h * (1 - std::pow(b / h, 4) / 12))},
      // BOX: two flanges W x t1 at z = +-(H - t1)/2 and two webs t2 x (H - 2 t1).
      {2 * W * t1 + 2 * (H - 2 * t1) * t2,
       2 * (W * t1 * t1 * t1 / 12 + W * t1 * std::pow((H - t1) / 2, 2)) + 2 * t2 * std::pow(H - 2 * t1, 3) / 12,
       2 * t1 * W * W * W / 12 + 2 * ((H - 2 * t1) * t2 * t2 * t2 / 12 + (H - 2 * t1) * t2 * std::pow((W - t2) / 2, 2)),
       4 * Am * Am / (2 * (W - t2) / t1 + 2 * (H - t1) / t2)},
  };
  for (int p = 0; p < 4; ++p) {
    SCOPED_TRACE(p);
    const Matrix6d& K = m.mesh.beam_properties[static_cast<std::size_t>(p)].Ks;
    const Matrix6d& M = m.mesh.beam_properties[static_cast<std::size_t>(p)].Ms;
    EXPECT_NEAR(K(0, 0) / E, ex[p].A, 1e-12 * ex[p].A);
    EXPECT_NEAR(K(4, 4) / E, ex[p].Iy, 1e-12 * ex[p].Iy);
    EXPECT_NEAR(K(5, 5) / E, ex[p].Iz, 1e-12 * ex[p].Iz);
    EXPECT_NEAR(K(3, 3) / G, ex[p].J, 1e-12 * ex[p].J);
    const double nsm = p == 3 ? 0.5 : 0.0;
    EXPECT_NEAR(M(0, 0), rho * ex[p].A + nsm, 1e-12 * M(0, 0));
    EXPECT_NEAR(M(4, 4), rho * ex[p].Iy, 1e-12 * M(4, 4));
  }
  for (const auto& v : m.mesh.beam_x2) EXPECT_LT((v - Eigen::Vector3d::UnitY()).norm(), 1e-15);
}

// GRID in CORD2R/CORD2C systems (a system defined in another), THETA and MCID
// material axes, CONM2 offset and inertia, RBE3 weights as given.
TEST(Nastran, CoordinateSystemsAxesMassesAndRbe3) {
  const std::string deck = std::string(R"(CORD2R,1,,1.,0.,0.,1.,0.,1.
+,1.,1.,0.
CORD2C,2,1,0.,0.,0.,0.,0.,1.
+,1.,0.,0.
GRID,1,,0.,0.,0.
GRID,2,,1.,0.,0.
GRID,3,2,1.,90.,2.
GRID,4,,0.,1.,0.
GRID,9,,0.5,0.5,1.
MAT8,1,1.5e11,1.e10,0.3,5.e9,5.e9,3.e9,1600.
PSHELL,1,1,0.002,1,,1
CTRIA3,1,1,1,2,4,30.
CTRIA3,2,1,2,9,4,1
CONM2,5,1,,2.,0.,0.,1.
+,3.,0.5,4.,0.,0.,5.
RBE3,7,,9,123456,2.,123,1,2
+,1.,123,4
)");
  const NastranModel m = nastranModel(readNastranCards(writeDeck("systems.bdf", deck)), unitSystem("m-kg-s"), {});
  // CORD2R 1: origin (1, 0, 0), z along basic y, x along basic x (C - A = (0, 1, 0)... A = (1,0,0), B = (1,0,1): z = basic z;
  // C = (1,1,0): x along basic y. CORD2C 2 in 1: its z along 1's z; (r=1, 90 deg, z=2) is 1's (0, 1, 2) = basic (1, 0, 0) + (-1, 0, 2).
  EXPECT_LT((m.grid_point.at(3) - Eigen::Vector3d(0.0, 0.0, 2.0)).norm(), 1e-15) << m.grid_point.at(3).transpose();
  // THETA = 30 deg from G1-G2 (basic x) about the normal (+z).
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  EXPECT_LT((m.mesh.triangle_axis[0] - Eigen::Vector3d(c, s, 0)).norm(), 1e-15);
  // MCID 1: its x axis (basic y), projected by the element.
  EXPECT_LT((m.mesh.triangle_axis[1] - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  // MID3 given: DST; the laminate is one MAT8 layer.
  EXPECT_EQ(m.mesh.shell_properties[0].kind, fe::ShellKind::DST);
  // CONM2: 2 kg at GRID 1 + (0, 0, 1); inertia [I11 -I21 -I31; -I21 I22 -I32; -I31 -I32 I33].
  ASSERT_EQ(m.mesh.point_masses.size(), 1u);
  EXPECT_LT((m.mesh.point_masses[0].point - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
  EXPECT_EQ(m.mesh.point_masses[0].inertia(0, 1), -0.5);
  EXPECT_EQ(m.mesh.point_masses[0].inertia(1, 1), 4.0);
  // RBE3: reference GRID 9, weights 2 on GRID 1, 2 and 1 on GRID 4 (mesh nodes by ascending id).
  const NastranRbe& r = m.rbes.at(7);
  EXPECT_FALSE(r.rigid);
  EXPECT_LT((r.point - Eigen::Vector3d(0.5, 0.5, 1.0)).norm(), 1e-15);
  ASSERT_EQ(r.nodes.size(), 3u);
  EXPECT_EQ(r.weights(0), 2.0);
  EXPECT_EQ(r.weights(2), 1.0);
}


// An RBE3 named as an interface ({rbe: EID}) is a distributing coupling at its
// REFGRID with the deck's weights: scaling every weight leaves the body as it
// is (the fit is a weighted mean), while the tributary weights fe-prep takes
// for the same nodes as a set give other interface shapes (the edge's end
// nodes carry half) - the deck's weights are the ones used. RBE3 adds no
// stiffness: the modes of the three bodies are the same.
TEST(Nastran, Rbe3InterfaceUsesTheDecksWeights) {
  std::ifstream in(kData + "panel_free.bdf");
  const std::string base((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto deckWith = [&](const std::string& name, const std::string& w) {
    return writeDeck(name, base + "GRID,9999,,0.4,0.,0.05\nRBE3,9300,,9999,123456," + w +
                               ",123,17,34\n+,51,68,85,102,119,136,153\n");
  };
  const std::string one = deckWith("rbe3_one.bdf", "1."), two = deckWith("rbe3_two.bdf", "2.");
  auto yaml = [](const std::string& deck, const std::string& tip) {
    return "body:\n  mesh: {file: " + deck + "}\n  interfaces:\n    hinge: {rbe: 9100}\n    tip: " + tip +
           "\n  reference: {clamp: [hinge]}\n  modes: 6\n";
  };
  const BuildResult a = runYaml(yaml(one, "{rbe: 9300}")), b = runYaml(yaml(two, "{rbe: 9300}"));
  const BuildResult t = runYaml(yaml(one, "{point: [0.4, 0.0, 0.05], coupling: distributing, nodes: {set: RBE9300}}"));
  EXPECT_LT((a.body.interface("tip").position - Eigen::Vector3d(0.4, 0.0, 0.05)).norm(), 1e-15);
  const Eigen::MatrixXd &sa = a.body.interface("tip").shapes, &sb = b.body.interface("tip").shapes,
                        &st = t.body.interface("tip").shapes;
  // Same matrices: the shapes agree to rounding (1e-9 of the largest: the
  // eigen-solver's tolerance), each mode up to its sign (the solver's start
  // vector differs from one solve to the next).
  auto signFree = [](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
    double d = 0;
    for (long j = 0; j < x.rows(); ++j)
      d = std::max(d, std::min((x.row(j) - y.row(j)).cwiseAbs().maxCoeff(), (x.row(j) + y.row(j)).cwiseAbs().maxCoeff()));
    return d;
  };
  EXPECT_LT(signFree(sa, sb), 1e-9 * sa.cwiseAbs().maxCoeff());
  for (long j = 0; j < 6; ++j) EXPECT_NEAR(a.body.eigenvalues(j), t.body.eigenvalues(j), 1e-10 * t.body.eigenvalues(j));
  // The torsion-like modes move the edge's ends most: equal weights and tributary
  // weights (ends at half) differ there by far more than rounding.
  EXPECT_GT(signFree(sa, st), 1e-3 * sa.cwiseAbs().maxCoeff());
}

// The body file records each region (/regions/NAME, docs/body-file.md
// "Regions") and --inspect lists them: on the example's panel (16 x 8 cells)
// by both routes, the counts are the mesh's, the masses closed forms (skin
// (1600 kg/m^3 x 2 mm + 0.2 kg/m^2) x 0.8 x 0.5 m = 1.36 kg, stringers
// 2 x 2700 x 4 x 25 mm^2 x 0.8 m = 0.432 kg: to 1e-12, sums of areas and
// lengths), the axes the fibre axis and x2 the input gives.
TEST(Nastran, BodyFileRecordsRegionsAndInspectListsThem) {
  const std::string dir = scratchDir("regions_record");
  for (const bool deck : {false, true}) {
    const BuildResult r = runYaml(deck ? deckYaml("panel_free.bdf") : mshYaml());
    const std::string path = dir + (deck ? "/deck.h5" : "/msh.h5");
    fc::Provenance prov;
    prov.inputs_sha256 = "test";
    fc::writeFlexBody(path, r.body, fc::computeInertiaInvariants(r.body), prov);
    H5File f(path, H5File::Mode::Read);
    const std::string skin = deck ? "/regions/PID1" : "/regions/skin", str = deck ? "/regions/PID2" : "/regions/stringers";
    ASSERT_TRUE(f.exists(skin + "/members") && f.exists(str + "/members") && f.exists("/regions/masses/members")) << path;
    EXPECT_EQ(f.stringAttribute(skin, "kind"), "shell");
    EXPECT_EQ(f.stringAttribute(skin, "members_of"), "triangles");
    EXPECT_EQ(f.stringAttribute(skin, "element"), "dst");
    EXPECT_EQ(f.readIntVector(skin + "/members").size(), 256u);
    EXPECT_NEAR(f.readScalar(skin + "/mass"), 1.36, 1e-12 * 1.36);
    const Eigen::MatrixXd fibre = f.readMatrix(skin + "/axes");
    ASSERT_EQ(fibre.rows(), 256);
    EXPECT_LT((fibre.rowwise() - Eigen::RowVector3d(1, 0, 0)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(f.stringAttribute(str, "kind"), "beam");
    EXPECT_EQ(f.stringAttribute(str, "members_of"), "beams");
    EXPECT_EQ(f.readIntVector(str + "/members").size(), 32u);
    EXPECT_NEAR(f.readScalar(str + "/mass"), 0.432, 1e-12 * 0.432);
    const Eigen::MatrixXd x2 = f.readMatrix(str + "/axes");
    ASSERT_EQ(x2.rows(), 32);
    EXPECT_LT((x2.rowwise() - Eigen::RowVector3d(0, 1, 0)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_NEAR(f.readScalar("/regions/masses/mass"), 0.15, 1e-15);
    if (!deck) {
      EXPECT_EQ(f.stringAttribute("/regions/root", "kind"), "set");
      EXPECT_EQ(f.readIntVector("/regions/root/members").size(), 9u);  // the root edge's 8 cells
    }
    // Every triangle and beam is in exactly one region.
    std::vector<int> tri(static_cast<std::size_t>(r.body.elements.at("triangles").rows()), 0),
        beam(static_cast<std::size_t>(r.body.elements.at("beams").rows()), 0);
    for (const std::string& g : f.children("/regions")) {
      const std::string of = f.stringAttribute("/regions/" + g, "members_of");
      for (long m : f.readIntVector("/regions/" + g + "/members")) {
        if (of == "triangles") ++tri.at(static_cast<std::size_t>(m));
        if (of == "beams") ++beam.at(static_cast<std::size_t>(m));
      }
    }
    EXPECT_EQ(std::count(tri.begin(), tri.end(), 1), static_cast<long>(tri.size()));
    EXPECT_EQ(std::count(beam.begin(), beam.end(), 1), static_cast<long>(beam.size()));
    // This mixed body carries the stress data of both kinds (docs/stresses.md,
    // "Mixed bodies"): the triangles' centroids, then the beams' midpoints.
    const fc::StressRecoveryData sd = fc::readStressData(path, 10);
    EXPECT_EQ(sd.centroids.rows(), 256 + 32);
    EXPECT_EQ(sd.shell_strains.rows(), 6 * 256);
    EXPECT_EQ(sd.beam_resultants.rows(), 6 * 32);
    EXPECT_EQ(sd.plies.size(), 8);
    const std::string listing = fc::inspectFile(path);
    const std::string shell_line = deck ? "PID1: shell, 256 triangles (dst), 1.36 kg, laminate PCOMP 1, fibre axis [1, 0, 0]"
                                        : "skin: shell, 256 triangles (dst), 1.36 kg, laminate skin_layup, fibre axis [1, 0, 0] projected";
    EXPECT_NE(listing.find(shell_line), std::string::npos) << listing;
    EXPECT_NE(listing.find(deck ? "PID2: beam, 32 beam elements (timoshenko), 0.432 kg" : "stringers: beam, 32 beam elements (timoshenko), 0.432 kg, section rectangle, x2 [0, 1, 0]"),
              std::string::npos) << listing;
  }
}

// A sandwich PCOMP: aluminium faces (MAT1) on a honeycomb core given as a MAT8
// with negligible in-plane moduli and the core's G1Z, G2Z. The laminate equals
// the YAML route's (type: honeycomb), its transverse shear the stacking's
// (docs/laminate-shear.md), not 5/6 of the summed G t.
TEST(Nastran, PcompSandwichWithHoneycombCore) {
  const std::string path = writeDeck("sandwich.bdf", R"($ sandwich plate
GRID,1,,0.,0.,0.
GRID,2,,1.,0.,0.
GRID,3,,1.,1.,0.
GRID,4,,0.,1.,0.
MAT1,1,7.e10,,0.3,2700.
MAT8,2,1.e5,1.e5,0.,1.e5,2.e8,1.e8,50.
PCOMP,1,,,,,,,
+,1,0.001,0.,,2,0.02,0.,
+,1,0.001,0.
CQUAD4,1,1,1,2,3,4
)");
  const NastranModel m = nastranModel(readNastranCards(path), unitSystem("m-kg-s"), {});
  ASSERT_EQ(m.mesh.shell_properties.size(), 1u);
  const LaminateStiffness& deck = m.mesh.shell_properties[0].laminate;
  auto root = InputNode::loadString(R"(
materials:
  al: {type: isotropic, E: 70e9, nu: 0.3, rho: 2700}
  core: {type: honeycomb, E3: 600e6, G13: 200e6, G23: 100e6, rho: 50, E1: 1e5, E2: 1e5, G12: 1e5}
)");
  const MaterialLibrary mats = readMaterials(root["materials"]);
  const LaminateStiffness yaml =
      laminateStiffness(Laminate{"sw", {{"al", 0.001, 0}, {"core", 0.02, 0}, {"al", 0.001, 0}}}, mats);
  // Same plies, same formulas: round-off.
  EXPECT_LT((deck.D - yaml.D).norm(), 1e-12 * yaml.D.norm());
  EXPECT_LT((deck.As - yaml.As).norm(), 1e-12 * yaml.As.norm());
  // Sandwich theory's G_c d^2 / c (4.41e6 N/m along x), a tenth of 5/6 sum G t (48.2e6 N/m).
  EXPECT_NEAR(deck.As(0, 0), 2e8 * 0.021 * 0.021 / 0.02, 0.01 * deck.As(0, 0));
  EXPECT_NEAR(deck.As(1, 1), 1e8 * 0.021 * 0.021 / 0.02, 0.01 * deck.As(1, 1));
}

}  // namespace
}  // namespace fc::feprep::test
