// Stress recovery kernels (mbs-run/monitors/stress_recovery.h) against hand values and
// independent transformations, the `strength` key, the body-file data round
// trip and the scene's outputs.stresses errors. The whole chain against
// classical lamination theory and CalculiX: tests/fe-prep/test_stress_validation.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/h5io.h"
#include "common/laminate.h"
#include "common/materials.h"
#include "flexible/random_body.h"
#include "helpers.h"
#include "mbs-run/output/animation.h"
#include "mbs-run/output/results.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/monitors/stress_recovery.h"

namespace fc::mbs::test {
namespace {

const char* kIm6 = R"(materials:
  im6: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9, G12: 7.6e9, G13: 7.6e9, G23: 3.6e9,
        nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600,
        strength: {Xt: 2.0e9, Xc: 1.2e9, Yt: 50e6, Yc: 200e6, S12: 80e6}}
)";

fc::MaterialLibrary materials(const std::string& yaml) {
  return fc::readMaterials(fc::InputNode::loadString(yaml, "m.yaml")["materials"]);
}

TEST(StressKernels, StrainRotationIsTheTensorRotation) {
  // Independent route: rotate the strain tensor [[ex, g/2], [g/2, ey]] into the
  // ply axes e1 = (c, s), e2 = (-s, c): eps_ab = e_a^T eps e_b, gamma_12 = 2 eps_12.
  const Eigen::Vector3d e(1.3e-3, -0.4e-3, 0.9e-3);
  Eigen::Matrix2d t;
  t << e(0), e(2) / 2, e(2) / 2, e(1);
  for (double deg : {0.0, 30.0, 45.0, 90.0, -60.0, 135.0}) {
    const double a = deg * M_PI / 180;
    const Eigen::Vector2d e1(std::cos(a), std::sin(a)), e2(-std::sin(a), std::cos(a));
    const Eigen::Vector3d want(e1.dot(t * e1), e2.dot(t * e2), 2 * e1.dot(t * e2));
    // Rounding only: entries are products of cosines of order 1 times 1e-3.
    EXPECT_LT((strainToPlyAxes(a) * e - want).norm(), 1e-18) << deg;
  }
  EXPECT_LT((strainToPlyAxes(0) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(StressKernels, PlyStiffnessSeenFromTheLaminateIsQbar) {
  // sigma_12 = Q T eps and the stress energy sigma . eps_12 = eps^T (T^T Q T) eps:
  // T^T Q T must be Reddy's Q-bar, which common/laminate computes by an
  // independent route (Bond rotation of the 3-D stiffness, then plane stress).
  const fc::Material& m = materials(kIm6).at("im6");
  const Eigen::Matrix3d Q = fc::reducedStiffness(m);
  for (double deg : {0.0, 25.0, 45.0, 90.0, -30.0}) {
    const double a = deg * M_PI / 180;
    const Eigen::Matrix3d T = strainToPlyAxes(a);
    // 1e-9 relative: two routes through 6x6 inversions of a stiffness with
    // condition ~1e2, rounding at 1e-14 each.
    EXPECT_LT((T.transpose() * Q * T - fc::rotatedReducedStiffness(m, a)).norm(), 1e-9 * Q.norm()) << deg;
  }
}

TEST(StressKernels, TsaiWuHandValues) {
  Strength5 s;
  s << 2.0e9, 1.2e9, 50e6, 200e6, 80e6;
  const TsaiWu c = tsaiWuCoefficients(s);
  // Each uniaxial strength is exactly on the failure surface: F1 Xt + F11 Xt^2 =
  // 1 - Xt/Xc + Xt/Xc = 1, and likewise for Xc, Yt, Yc and S12.
  const double tol = 1e-14;  // rounding of a handful of products of order 1
  EXPECT_NEAR(tsaiWuIndex(c, {2.0e9, 0, 0}), 1.0, tol);
  EXPECT_NEAR(tsaiWuIndex(c, {-1.2e9, 0, 0}), 1.0, tol);
  EXPECT_NEAR(tsaiWuIndex(c, {0, 50e6, 0}), 1.0, tol);
  EXPECT_NEAR(tsaiWuIndex(c, {0, -200e6, 0}), 1.0, tol);
  EXPECT_NEAR(tsaiWuIndex(c, {0, 0, 80e6}), 1.0, tol);
  EXPECT_NEAR(tsaiWuIndex(c, {0, 0, -80e6}), 1.0, tol);
  // By hand, sigma = (500, 20, 30) MPa:
  //   F1 s1 = (1/2000 - 1/1200) 500 = -0.1666667     F2 s2 = (1/50 - 1/200) 20 = 0.3
  //   F11 s1^2 = 500^2/(2000*1200) = 0.1041667      F22 s2^2 = 20^2/(50*200) = 0.04
  //   F66 t^2 = 30^2/80^2 = 0.140625                 2 F12 s1 s2 = -sqrt(0.1041667*0.04) = -0.0645497
  //   sum = 0.3535753
  EXPECT_NEAR(tsaiWuIndex(c, {500e6, 20e6, 30e6}), 0.3535753, 1e-7);  // the hand sum's 7 digits
  s(2) = -1;
  EXPECT_THROW(tsaiWuCoefficients(s), std::invalid_argument);
}

TEST(StressKernels, RecoveryOfTwoPliesByHand) {
  // One element, plies 0 and 90 deg at z = -/+ 0.5 mm, generalised strains per
  // mode given: the recovered stresses must be Q T (eps0 + z kappa) of each ply.
  fc::StressRecoveryData d;
  d.centroids = Eigen::MatrixXd::Zero(1, 3);
  d.shell_strains.resize(6, 2);
  d.shell_strains.col(0) << 1e-4, -2e-5, 3e-5, 0.02, -0.01, 0.005;
  d.shell_strains.col(1) << -3e-5, 1e-5, 0, 0.0, 0.04, -0.01;
  fc::Laminate lam;
  lam.plies = {{"im6", 0.001, 0.0}, {"im6", 0.001, 90.0}};
  d.plies = fc::plyTable(lam, materials(kIm6));
  ASSERT_TRUE(d.plies.hasStrength());
  EXPECT_DOUBLE_EQ(d.plies.z_mid(0), -0.0005);
  EXPECT_DOUBLE_EQ(d.plies.z_mid(1), 0.0005);
  const auto r = shellStressRecovery(d);
  ASSERT_EQ(r->outputs.size(), 3u);  // ply_stress, failure_index, hashin
  const Eigen::Vector2d q(0.7, -1.9);
  std::vector<Eigen::VectorXd> f;
  r->recover(q, f);
  const Vector6d e = d.shell_strains * q;
  const Eigen::Matrix3d Q = d.plies.stiffness[0];
  // Ply 0 (0 deg): material axes are the laminate axes.
  const Eigen::Vector3d s0 = Q * (e.head<3>() - 0.0005 * e.tail<3>());
  // Ply 1 (90 deg): eps_1 = eps_y, eps_2 = eps_x, gamma_12 = -gamma_xy.
  const Eigen::Vector3d l1 = e.head<3>() + 0.0005 * e.tail<3>();
  const Eigen::Vector3d s1 = Q * Eigen::Vector3d(l1(1), l1(0), -l1(2));
  for (int c = 0; c < 3; ++c) {
    // Rounding of sums of products of size |Q| |eps| ~ 1e7 Pa.
    EXPECT_NEAR(f[0](c), s0(c), 1e-6);
    EXPECT_NEAR(f[0](3 + c), s1(c), 1e-6);
  }
  const TsaiWu c = tsaiWuCoefficients(d.plies.strength.row(0).transpose());
  EXPECT_NEAR(f[1](0), tsaiWuIndex(c, s0), 1e-14);
  EXPECT_NEAR(f[1](1), tsaiWuIndex(c, s1), 1e-14);
  // Hashin's plane-stress form written out (S_T = Yc / 2, S_A = S12) for each ply.
  const Eigen::VectorXd st = d.plies.strength.row(0).transpose();
  const double Xt = st(0), Xc = st(1), Yt = st(2), Yc = st(3), S = st(4), ST = Yc / 2;
  ASSERT_EQ(f[2].size(), 8);
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d& sk = k == 0 ? s0 : s1;
    const double axial = sk(2) * sk(2) / (S * S);
    const double ft = sk(0) >= 0 ? sk(0) * sk(0) / (Xt * Xt) + axial : 0.0;
    const double fc = sk(0) < 0 ? sk(0) * sk(0) / (Xc * Xc) : 0.0;
    const double mt = sk(1) >= 0 ? sk(1) * sk(1) / (Yt * Yt) + axial : 0.0;
    const double mc = sk(1) < 0 ? ((Yc / (2 * ST)) * (Yc / (2 * ST)) - 1) * sk(1) / Yc + sk(1) * sk(1) / (4 * ST * ST) + axial : 0.0;
    const double want[4] = {ft, fc, mt, mc};
    // The 1e-6 Pa of the stresses above, relative to strengths of 1e7..1e9 Pa.
    for (int m = 0; m < 4; ++m) EXPECT_NEAR(f[2](4 * k + m), want[m], 1e-12) << k << " " << m;
  }
  const FailureLocation at = largestFailureIndex(*r, f[1]);
  EXPECT_EQ(at.element, 0);
  EXPECT_EQ(at.ply, f[1](1) > f[1](0) ? 1 : 0);
}

void expectMaterialError(const std::string& strength, const std::string& key, const std::string& words) {
  const std::string yaml = "materials:\n  cfrp: {type: isotropic, E: 70e9, nu: 0.3, rho: 1600,\n         strength: " +
                           strength + "}\n";
  try {
    materials(yaml);
    FAIL() << "accepted " << strength;
  } catch (const fc::InputError& e) {
    EXPECT_EQ(e.line(), 3) << e.what();
    EXPECT_NE(e.keyPath().find(key), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(MaterialStrength, ReadAndCheckedAtTheKey) {
  const fc::Material& m = materials(kIm6).at("im6");
  ASSERT_TRUE(m.strength.has_value());
  EXPECT_EQ(m.strength->Xc, 1.2e9);
  EXPECT_EQ(m.strength->S12, 80e6);
  EXPECT_FALSE(materials("materials:\n  a: {type: isotropic, E: 70e9, nu: 0.3, rho: 2700}\n").at("a").strength);
  expectMaterialError("{Xt: 1e9, Xc: -1e9, Yt: 5e7, Yc: 2e8, S12: 8e7}", "strength.Xc", "positive");
  expectMaterialError("{Xt: 1e9, Xc: 1e9, Yt: 5e7, Yc: 2e8}", "strength", "S12");
  expectMaterialError("{Xt: 1e9, Xc: 1e9, Yt: 5e7, Yc: 2e8, S12: 8e7, S13: 1e7}", "strength", "unknown key 'S13'");
  expectMaterialError("{Xt: 2000, Xc: 1e9, Yt: 5e7, Yc: 2e8, S12: 8e7}", "strength.Xt", "outside the physical range");
  expectMaterialError("1e9", "strength", "expected a map");
}

// A small body file with (or without) shell stress data: random mass-normalised
// modes on 6 nodes, four triangles.
std::string stressBody(bool with_stress, const std::string& tag) {
  fc::FlexBody b = fc::testing::randomBody(6, 3, 5);
  b.elements["triangles"] = (fc::IndexMatrix(4, 3) << 0, 1, 2, 1, 2, 3, 2, 3, 4, 3, 4, 5).finished();
  if (with_stress) {
    b.stress.centroids = Eigen::MatrixXd::Random(4, 3);
    b.stress.shell_strains = Eigen::MatrixXd::Random(24, 3) * 1e-3;
    fc::Laminate lam;
    lam.plies = {{"im6", 0.0005, 0.0}, {"im6", 0.0005, 45.0}, {"im6", 0.0005, -45.0}};
    b.stress.plies = fc::plyTable(lam, materials(kIm6));
  }
  return writeTempBody(b, tag);
}

TEST(StressData, BodyFileRoundTripReadsTheLeadingModes) {
  fc::FlexBody b = fc::testing::randomBody(6, 3, 5);
  b.elements["triangles"] = (fc::IndexMatrix(4, 3) << 0, 1, 2, 1, 2, 3, 2, 3, 4, 3, 4, 5).finished();
  b.stress.centroids = Eigen::MatrixXd::Random(4, 3);
  b.stress.shell_strains = Eigen::MatrixXd::Random(24, 3);
  fc::Laminate lam;
  lam.plies = {{"im6", 0.0005, 0.0}, {"im6", 0.001, 90.0}};
  b.stress.plies = fc::plyTable(lam, materials(kIm6));
  const std::string path = writeTempBody(b, "stress_roundtrip");
  const fc::StressRecoveryData d = fc::readStressData(path, 2);
  EXPECT_EQ(d.centroids, b.stress.centroids);
  EXPECT_EQ(d.shell_strains, b.stress.shell_strains.leftCols(2));
  EXPECT_EQ(d.plies.z_mid, b.stress.plies.z_mid);
  EXPECT_EQ(d.plies.angle_deg, b.stress.plies.angle_deg);
  EXPECT_EQ(d.plies.stiffness[1], b.stress.plies.stiffness[1]);
  EXPECT_EQ(d.plies.strength, b.stress.plies.strength);
  // The mesh reader keeps centroids out of the element connectivity.
  const fc::FlexBodyFile all = fc::readFlexBody(path, -1, fc::FlexBodyParts::All);
  EXPECT_EQ(all.body.elements.size(), 1u);
  std::remove(path.c_str());
}

const std::string kGround = "  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}\n";

TEST(StressScene, OutputsStressesErrorsAreLocated) {
  const std::string with = stressBody(true, "stress_scene_with");
  const std::string without = stressBody(false, "stress_scene_without");
  const std::string head = "bodies:\n" + kGround + "  - {name: p, flexible: {file: " + with + "}}\n" +
                           "  - {name: q, flexible: {file: " + without + "}}\n" +
                           "simulation: {t_end: 0.1}\n";  // lines 1-5
  auto expect = [&](const std::string& list, int index, const std::string& words) {
    try {
      sceneFromText(head + "outputs: {stresses: " + list + "}\n");
      FAIL() << list;
    } catch (const fc::InputError& e) {
      EXPECT_EQ(e.line(), 6) << e.what();
      EXPECT_NE(e.keyPath().find("outputs.stresses[" + std::to_string(index) + "]"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  expect("[ground]", 0, "not flexible");
  expect("[p, pp]", 1, "unknown body 'pp'");
  expect("[q]", 0, "no stress recovery data");
  expect("[p, p]", 1, "named twice");
  // Plies without strengths: stresses, no failure index, and a warning.
  {
    fc::FlexBody b = fc::testing::randomBody(6, 3, 5);
    b.elements["triangles"] = (fc::IndexMatrix(4, 3) << 0, 1, 2, 1, 2, 3, 2, 3, 4, 3, 4, 5).finished();
    b.stress.centroids = Eigen::MatrixXd::Random(4, 3);
    b.stress.shell_strains = Eigen::MatrixXd::Random(24, 3) * 1e-3;
    fc::Laminate lam;
    lam.plies = {{"a", 0.001, 0.0}};
    b.stress.plies = fc::plyTable(lam, materials("materials:\n  a: {type: isotropic, E: 70e9, nu: 0.3, rho: 2700}\n"));
    const std::string weak = writeTempBody(b, "stress_scene_weak");
    const Model mw = sceneFromText("bodies:\n  - {name: w, flexible: {file: " + weak +
                                   "}}\nsimulation: {t_end: 0.1}\noutputs: {stresses: [w]}\n");
    ASSERT_TRUE(mw.bodies[0].stress);
    EXPECT_EQ(mw.bodies[0].stress->outputs.size(), 1u);
    EXPECT_EQ(mw.bodies[0].stress->failure_output, -1);
    const std::vector<std::string> warn = samplingWarnings(mw);
    ASSERT_EQ(warn.size(), 1u);
    EXPECT_NE(warn[0].find("no failure_index"), std::string::npos);
    std::remove(weak.c_str());
  }
  // Named: recovery set up with the file's data; not named: nothing at all.
  const Model m = sceneFromText(head + "outputs: {stresses: [p]}\n");
  ASSERT_TRUE(m.bodies[1].stress);
  EXPECT_FALSE(m.bodies[2].stress);
  EXPECT_EQ(m.bodies[1].stress->n_plies, 3);
  const std::vector<Channel> ch = resultChannels(m);
  int stress_channels = 0;
  for (const Channel& c : ch) {
    if (c.name == "bodies/p/ply_stress") {
      ++stress_channels;
      EXPECT_EQ(c.dims, (std::vector<hsize_t>{4, 3, 3}));
    }
    if (c.name == "bodies/p/failure_index") ++stress_channels;
    EXPECT_EQ(c.name.find("bodies/q/ply"), std::string::npos);
    EXPECT_EQ(c.name.find("bodies/q/failure"), std::string::npos);
  }
  EXPECT_EQ(stress_channels, 2);
  const Model none = sceneFromText(head);
  for (const Body& b : none.bodies) EXPECT_FALSE(b.stress);
  std::remove(with.c_str());
  std::remove(without.c_str());
}

TEST(StressScene, RunWritesStressesAndPeakAtEveryOutput) {
  // A free random body given modal velocities: every output row carries the
  // recovery of that row's modal coordinates, and the summary's peak is the
  // largest index over all rows, elements and plies.
  const std::string path = stressBody(true, "stress_run");
  const Model m = sceneFromText("bodies:\n  - {name: p, flexible: {file: " + path +
                                "}, modal_velocities: [0.01, -0.02, 0.015]}\n"
                                "simulation: {t_end: 0.2, output_step: 0.05}\noutputs: {stresses: [p]}\n");
  const Results r = simulate(m);
  ASSERT_EQ(r.time.size(), 5u);
  double peak = -1e300;
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    std::vector<Eigen::VectorXd> f;
    m.bodies[0].stress->recover(r.modal[0][i], f);
    EXPECT_EQ(f[0], r.stress[0][i][0]);
    EXPECT_EQ(f[1], r.stress[0][i][1]);
    peak = std::max(peak, f[1].maxCoeff());
  }
  ASSERT_TRUE(r.peak_failure_index.found);
  EXPECT_EQ(r.peak_failure_index.value, peak);
  EXPECT_EQ(r.peak_failure_index.body, "p");
  std::remove(path.c_str());
}

TEST(StressScene, AnimationCarriesTheLargestPlyIndexPerElement) {
  // The animation's cell field failure_index is, per triangle, the largest
  // index over its plies in that row of the results file.
  const std::string body = stressBody(true, "stress_anim");
  const std::string dir = std::filesystem::temp_directory_path() / ("stress_anim_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string scene = dir + "/scene.yaml", results = dir + "/r.h5";
  {
    std::FILE* f = std::fopen(scene.c_str(), "w");
    std::fprintf(f, "bodies:\n  - {name: p, flexible: {file: %s}, modal_velocities: [0.01, -0.02, 0.015]}\n"
                    "simulation: {t_end: 0.1, output_step: 0.05}\noutputs: {stresses: [p]}\n", body.c_str());
    std::fclose(f);
  }
  const Model m = loadScene(scene);
  const Results r = simulate(m);
  writeResults(results, m, r, "test");
  writeAnimation(dir + "/a.pvd", scene, m, results);
  std::ifstream in(dir + "/a/a_0002_p.vtp", std::ios::binary);
  const std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string key = "Name=\"failure_index\" NumberOfComponents=\"1\" format=\"appended\" offset=\"";
  const std::size_t at = raw.find(key);
  ASSERT_NE(at, std::string::npos);
  const long offset = std::stol(raw.substr(at + key.size()));
  const std::size_t data = raw.find('_', raw.find("<AppendedData")) + 1 + static_cast<std::size_t>(offset);
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, raw.data() + data, 8);
  ASSERT_EQ(bytes, 4 * sizeof(double));
  const Eigen::VectorXd& fi = r.stress[0][2][1];  // row 2, failure index (4 elements x 3 plies)
  for (int e = 0; e < 4; ++e) {
    double v = 0;
    std::memcpy(&v, raw.data() + data + 8 + 8 * e, 8);
    EXPECT_EQ(v, fi.segment(3 * e, 3).maxCoeff()) << e;
  }
  std::filesystem::remove_all(dir);
  std::remove(body.c_str());
}


// ---- envelope and decimation (docs/stresses.md, "Envelope and decimation")

// Three free random bodies given modal velocities, one of each kind of
// recovery: p a shell with strengths, w a shell without, b a beam.
struct EnvelopeBodies {
  std::string p, w, b;
  void remove() const {
    for (const std::string* f : {&p, &w, &b}) std::remove(f->c_str());
  }
};
// p has n_el triangles (the four of stressBody repeated): 700 make a row wider
// than the results writer's 1 MB block holds 16 of, so that a run of 41 rows
// is written in three blocks (ResultsFileWriter::writeBlock).
EnvelopeBodies envelopeBodies(int n_el = 4) {
  EnvelopeBodies e;
  {
    fc::FlexBody b = fc::testing::randomBody(6, 3, 5);
    fc::IndexMatrix tri(n_el, 3);
    for (int k = 0; k < n_el; ++k) tri.row(k) << k % 4, k % 4 + 1, k % 4 + 2;
    b.elements["triangles"] = tri;
    b.stress.centroids = Eigen::MatrixXd::Random(n_el, 3);
    b.stress.shell_strains = Eigen::MatrixXd::Random(6 * n_el, 3) * 1e-3;
    fc::Laminate lam;
    lam.plies = {{"im6", 0.0005, 0.0}, {"im6", 0.0005, 45.0}, {"im6", 0.0005, -45.0}};
    b.stress.plies = fc::plyTable(lam, materials(kIm6));
    e.p = writeTempBody(b, "env_p");
  }
  fc::FlexBody wb = fc::testing::randomBody(6, 3, 5);
  wb.elements["triangles"] = (fc::IndexMatrix(4, 3) << 0, 1, 2, 1, 2, 3, 2, 3, 4, 3, 4, 5).finished();
  wb.stress.centroids = Eigen::MatrixXd::Random(4, 3);
  wb.stress.shell_strains = Eigen::MatrixXd::Random(24, 3) * 1e-3;
  fc::Laminate lam;
  lam.plies = {{"a", 0.001, 0.0}, {"a", 0.001, 90.0}};
  wb.stress.plies = fc::plyTable(lam, materials("materials:\n  a: {type: isotropic, E: 70e9, nu: 0.3, rho: 2700}\n"));
  e.w = writeTempBody(wb, "env_w");
  fc::FlexBody bb = fc::testing::randomBody(5, 3, 7);
  bb.elements.clear();
  bb.elements["beams"] = (fc::IndexMatrix(4, 2) << 0, 1, 1, 2, 2, 3, 3, 4).finished();
  bb.stress.centroids = Eigen::MatrixXd::Random(4, 3);
  bb.stress.beam_resultants = Eigen::MatrixXd::Random(24, 3) * 1e3;
  e.b = writeTempBody(bb, "env_b");
  return e;
}

// Rows at 0, 0.05, ..., t_end; `extra` goes into outputs.
std::string envelopeScene(const EnvelopeBodies& e, const std::string& path, double t_end, const std::string& extra) {
  std::ofstream f(path);
  f << "bodies:\n"
    << "  - {name: p, flexible: {file: " << e.p << "}, modal_velocities: [0.01, -0.02, 0.015]}\n"
    << "  - {name: w, flexible: {file: " << e.w << "}, modal_velocities: [-0.01, 0.02, 0.01]}\n"
    << "  - {name: b, flexible: {file: " << e.b << "}, modal_velocities: [0.02, 0.01, -0.01]}\n"
    << "simulation: {t_end: " << t_end << ", output_step: 0.05}\n"
    << "outputs: {stresses: [p, w, b]" << extra << "}\n";
  return path;
}

std::string tempDir(const std::string& tag) {
  const std::string dir = std::filesystem::temp_directory_path() / (tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs the scene to a results file through the streaming writer, as mbs-run does.
std::string runToFile(const std::string& scene, const std::string& out) {
  const Model m = loadScene(scene);
  const Results r = simulate(m);
  writeResults(out, m, r, "test");
  return out;
}

TEST(StressEnvelope, IsTheMaxOverEveryFullRowAndItsTime) {
  // Without stress_every every row is written, and the envelope must be what
  // the test computes from those rows by itself: the same numbers exactly
  // (same doubles compared, nothing recomputed), the FIRST row reaching the
  // peak for its time, the ply stresses of that row.
  const std::string dir = tempDir("stress_env");
  const EnvelopeBodies bodies = envelopeBodies();
  const std::string res = runToFile(envelopeScene(bodies, dir + "/s.yaml", 0.5, ""), dir + "/r.h5");
  fc::H5File f(res, fc::H5File::Mode::Read);
  EXPECT_FALSE(f.exists("/stress_time"));  // absent key: the file as before
  const Eigen::VectorXd t = f.readVector("/time");
  const long n = t.size();
  ASSERT_EQ(n, 11);
  // p: failure index (n, 4, 3), ply stresses (n, 4, 3, 3).
  ASSERT_EQ(f.shape("/bodies/p/failure_index"), (std::vector<hsize_t>{11, 4, 3}));
  const std::vector<double> fi = f.readArray("/bodies/p/failure_index"), ps = f.readArray("/bodies/p/ply_stress");
  const std::vector<double> peak = f.readArray("/bodies/p/failure_index_peak"),
                            when = f.readArray("/bodies/p/failure_index_peak_time"),
                            at = f.readArray("/bodies/p/ply_stress_at_peak");
  ASSERT_EQ(f.shape("/bodies/p/failure_index_peak"), (std::vector<hsize_t>{4, 3}));
  ASSERT_EQ(f.shape("/bodies/p/failure_index_peak_time"), (std::vector<hsize_t>{4, 3}));
  ASSERT_EQ(f.shape("/bodies/p/ply_stress_at_peak"), (std::vector<hsize_t>{4, 3, 3}));
  double largest = -1e300;
  int rows_differ = 0;  // the peaks must not all sit in one row, or the time test is weak
  for (int i = 0; i < 12; ++i) {
    long row = 0;
    for (long k = 1; k < n; ++k)
      if (fi[k * 12 + i] > fi[row * 12 + i]) row = k;
    rows_differ += row != 0 && row != n - 1;
    EXPECT_EQ(peak[i], fi[row * 12 + i]) << i;
    EXPECT_EQ(when[i], t(row)) << i;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(at[3 * i + c], ps[row * 36 + 3 * i + c]) << i << " " << c;
    largest = std::max(largest, peak[i]);
  }
  EXPECT_GT(rows_differ, 0);
  // The summary's largest index is the envelope's largest.
  EXPECT_EQ(f.doubleAttribute("/", "peak_failure_index"), largest);
  // The per-member table: one row for p (w has no strengths, b no section
  // basis), its peak, the first time it is reached, its element and ply.
  {
    const Eigen::MatrixXd mt = f.readMatrix("/margins/failure_index");
    ASSERT_EQ(mt.rows(), 1);
    ASSERT_EQ(mt.cols(), 4);
    EXPECT_EQ(f.stringAttribute("/margins/failure_index", "bodies"), "p");
    EXPECT_EQ(mt(0, 0), largest);
    int at = 0;
    for (int i = 1; i < 12; ++i)
      if (peak[i] > peak[at]) at = i;
    EXPECT_EQ(mt(0, 1), when[at]);
    EXPECT_EQ(mt(0, 2), at / 3);
    EXPECT_EQ(mt(0, 3), at % 3);
  }
  EXPECT_FALSE(f.exists("/bodies/p/ply_stress_max"));
  // Each Hashin mode's peak is the largest of its rows.
  ASSERT_EQ(f.shape("/bodies/p/hashin"), (std::vector<hsize_t>{11, 4, 3, 4}));
  ASSERT_EQ(f.shape("/bodies/p/hashin_peak"), (std::vector<hsize_t>{4, 3, 4}));
  const std::vector<double> hs = f.readArray("/bodies/p/hashin"), hp = f.readArray("/bodies/p/hashin_peak");
  for (int i = 0; i < 48; ++i) {
    double mx = hs[i];
    for (long k = 1; k < n; ++k) mx = std::max(mx, hs[k * 48 + i]);
    EXPECT_EQ(hp[i], mx) << i;
  }
  // w (no strengths): min and max of each ply stress component; b: of each section force.
  for (const std::string& field : {std::string("/bodies/w/ply_stress"), std::string("/bodies/b/section_forces")}) {
    const std::vector<double> v = f.readArray(field), hi = f.readArray(field + "_max"), lo = f.readArray(field + "_min");
    std::vector<hsize_t> trailing = f.shape(field);
    ASSERT_EQ(trailing[0], static_cast<hsize_t>(n));
    trailing.erase(trailing.begin());
    EXPECT_EQ(f.shape(field + "_max"), trailing);
    const std::size_t w = hi.size();
    ASSERT_EQ(v.size(), n * w);
    for (std::size_t i = 0; i < w; ++i) {
      double mx = v[i], mn = v[i];
      for (long k = 1; k < n; ++k) mx = std::max(mx, v[k * w + i]), mn = std::min(mn, v[k * w + i]);
      EXPECT_EQ(hi[i], mx) << field << " " << i;
      EXPECT_EQ(lo[i], mn) << field << " " << i;
      EXPECT_LT(mn, mx) << field << " " << i;  // the rows do differ
    }
  }
  EXPECT_FALSE(f.exists("/bodies/w/failure_index_peak"));
  EXPECT_FALSE(f.exists("/bodies/b/failure_index_peak"));
  std::filesystem::remove_all(dir);
  bodies.remove();
}

TEST(StressEnvelope, StressEveryWritesEveryKthRowAndTheLastWithTheSameEnvelope) {
  // stress_every: 3 against stress_every: 1 of the same run: the full fields
  // hold exactly rows 0, 3, 6, ... and the last, bit for bit; everything else
  // (the envelope included) is identical. 11 rows (last 10, not a multiple),
  // 10 rows (last 9, a multiple: written once), and 41 rows of a wide body
  // written in three blocks of 16.
  for (const auto& [n_el, t_end] : {std::pair{4, 0.5}, std::pair{4, 0.45}, std::pair{700, 2.0}}) {
    const EnvelopeBodies bodies = envelopeBodies(n_el);
    const std::string dir = tempDir("stress_every");
    const std::string s3 = envelopeScene(bodies, dir + "/s3.yaml", t_end, ", stress_every: 3");
    const std::string r1 = runToFile(envelopeScene(bodies, dir + "/s1.yaml", t_end, ", stress_every: 1"), dir + "/r1.h5");
    const std::string r3 = runToFile(s3, dir + "/r3.h5");
    fc::H5File f1(r1, fc::H5File::Mode::Read), f3(r3, fc::H5File::Mode::Read);
    const Eigen::VectorXd t = f1.readVector("/time");
    const long n = t.size();
    ASSERT_EQ(n, std::lround(t_end / 0.05) + 1);
    std::vector<long> kept;
    for (long k = 0; k < n; k += 3) kept.push_back(k);
    if (kept.back() != n - 1) kept.push_back(n - 1);
    EXPECT_EQ(f1.readVector("/stress_time"), t);  // stress_every: 1 keeps every row
    const Eigen::VectorXd ts = f3.readVector("/stress_time");
    ASSERT_EQ(ts.size(), static_cast<long>(kept.size()));
    for (std::size_t j = 0; j < kept.size(); ++j) EXPECT_EQ(ts(j), t(kept[j])) << j;
    for (const char* d : {"/bodies/p/ply_stress", "/bodies/p/failure_index", "/bodies/w/ply_stress",
                                 "/bodies/b/section_forces"}) {
      std::vector<hsize_t> s1 = f1.shape(d), s3 = f3.shape(d);
      ASSERT_EQ(s1[0], static_cast<hsize_t>(n)) << d;
      ASSERT_EQ(s3[0], kept.size()) << d;
      s1.erase(s1.begin());
      s3.erase(s3.begin());
      ASSERT_EQ(s1, s3) << d;
      const std::vector<double> a = f1.readArray(d), b = f3.readArray(d);
      const std::size_t w = a.size() / n;
      for (std::size_t j = 0; j < kept.size(); ++j)
        for (std::size_t i = 0; i < w; ++i) ASSERT_EQ(b[j * w + i], a[kept[j] * w + i]) << d << " row " << kept[j];
    }
    for (const char* d : {"/time", "/bodies/p/modal_coordinates", "/bodies/p/failure_index_peak",
                                 "/bodies/p/failure_index_peak_time", "/bodies/p/ply_stress_at_peak",
                                 "/bodies/w/ply_stress_max", "/bodies/w/ply_stress_min", "/bodies/b/section_forces_max",
                                 "/bodies/b/section_forces_min"})
      EXPECT_EQ(f1.readArray(d), f3.readArray(d)) << d;
    EXPECT_EQ(f1.doubleAttribute("/", "peak_failure_index"), f3.doubleAttribute("/", "peak_failure_index"));
    // Some peak of p lies in a row stress_every: 3 does not write, or the
    // envelope's claim to see every row is untested.
    const std::vector<double> when = f3.readArray("/bodies/p/failure_index_peak_time");
    EXPECT_TRUE(std::any_of(when.begin(), when.end(), [&](double x) { return (ts.array() != x).all(); }));
    // The animation holds the latest stress row.
    const Model m3 = loadScene(s3);
    EXPECT_NO_THROW(writeAnimation(dir + "/a.pvd", s3, m3, r3));
    std::filesystem::remove_all(dir);
    bodies.remove();
  }
}

TEST(StressEnvelope, StressEveryErrorsAreLocated) {
  const std::string p = stressBody(true, "env_err");
  const std::string head = "bodies:\n  - {name: p, flexible: {file: " + p + "}}\nsimulation: {t_end: 0.1}\n";  // lines 1-3
  auto expect = [&](const std::string& outputs, const std::string& words) {
    try {
      sceneFromText(head + "outputs: " + outputs + "\n");
      FAIL() << outputs;
    } catch (const fc::InputError& e) {
      EXPECT_EQ(e.line(), 4) << e.what();
      EXPECT_NE(e.keyPath().find("outputs.stress_every"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  expect("{stresses: [p], stress_every: 0}", "expected a whole number of output rows from 1 to 1000000, got 0");
  expect("{stresses: [p], stress_every: -3}", "got -3");
  expect("{stresses: [p], stress_every: 2.5}", "expected an integer, got '2.5'");
  expect("{stresses: [p], stress_every: ten}", "expected an integer");
  expect("{stresses: [p], stress_every: [3]}", "expected an integer");
  expect("{stresses: [p], stress_every: 2000000}", "got 2000000");
  expect("{stress_every: 3}", "outputs.stresses, which is not given");
  EXPECT_EQ(sceneFromText(head + "outputs: {stresses: [p], stress_every: 7}\n").stress_every, 7);
  EXPECT_EQ(sceneFromText(head + "outputs: {stresses: [p]}\n").stress_every, 0);
  std::remove(p.c_str());
}

}  // namespace
}  // namespace fc::mbs::test
