// Ply stresses of a composite beam body from a run: section-prep's recovery
// basis carried by fe-prep into the body file and combined in mbs-run with the
// section forces at each station (docs/stresses.md, "Beam ply stresses").
// A cantilever with a [+45/-45/0/90] IM6 tube section clamped to the ground,
// under a static tip force -P z, settled by critical modal damping with every
// mode of the 10-element model (the model's static solution, as in
// test_beam_section_forces.cpp). References nobody here wrote: statics at the
// root, N = V2 = T = M3 = 0, V3 = -P, M2 = P L; the ply stresses there are
// then those the section-level recovery gives for these resultants, and the
// Tsai-Wu index the contract's formula of them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "common/flexbody.h"
#include "common/input.h"
#include "feprep_test_support.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/scene/scene.h"
#include "section-prep/cross_section.h"
#include "section-prep/section_mesher.h"
#include "section-prep/section_output.h"
#include "section-prep/section_spec.h"
#include "section-prep/stress_recovery.h"

namespace fc::feprep::test {
namespace {

// P = 1 N keeps the tip deflection (P L^3 / 3EI ~ 1 mm) linear, as the
// neighbour test; the indices are small but the comparison is relative.
const double kL = 1.0, kP = 1.0;  // [m], [N]
const int kElements = 10;

std::string sectionYaml(bool strengths) {
  return std::string(
             "materials:\n"
             "  im6: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9, G12: 7.6e9, G13: 7.6e9,\n"
             "        G23: 3.6e9, nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600") +
         (strengths ? ",\n        strength: {Xt: 2.5e9, Xc: 1.6e9, Yt: 60e6, Yc: 250e6, S12: 90e6}}\n" : "}\n") +
         "section:\n"
         "  shape: tube\n"
         "  outer_diameter: 0.02\n"
         "  mesh_size: 0.0005\n"
         "  wall:\n"
         "    plies:\n"
         "      - {material: im6, thickness: 0.0005, angle_deg: 45}\n"
         "      - {material: im6, thickness: 0.0005, angle_deg: -45}\n"
         "      - {material: im6, thickness: 0.0005, angle_deg: 0}\n"
         "      - {material: im6, thickness: 0.0005, angle_deg: 90}\n";
}

struct Section {
  section::SectionMesh mesh;
  section::SectionProperties p;
  std::string path;
};

Section writeSection(const std::string& dir, bool strengths) {
  Section s;
  s.mesh = section::meshSection(section::readSectionSpec(InputNode::loadString(sectionYaml(strengths), "tube.yaml")));
  s.p = section::analyzeSection(s.mesh);
  s.path = dir + "/tube.h5";
  section::writeSectionFile(s.path, s.p, std::string(64, '0'), "tube.yaml", s.mesh);
  return s;
}

std::string bodyYaml(const std::string& section_path) {
  return "body:\n"
         "  name: cantilever\n"
         "  beam: {length: 1.0, elements: 10, section: {file: " + section_path + "}}\n"
         "  interfaces: {root: [-0.5, 0, 0], tip: [0.5, 0, 0]}\n"
         "  reference: {clamp: [end_min]}\n"
         "  modes: 60\n";
}

std::string scene(const std::string& body_path, const std::string& stresses) {
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: beam, flexible: {file: %s, modes: all, damping_ratio: 1.0}, position: [0.5, 0, 0]}
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
forces:
  - {type: force, body: beam, point: tip, force: [0, 0, %g]}
%s
simulation: {t_end: 0.4, output_step: 0.1, rtol: 1.0e-8}
)",
                body_path.c_str(), -kP,
                stresses.empty() ? "" : ("outputs: {stresses: [" + stresses + "]}").c_str());
  return buf;
}

std::string writeBody(const std::string& dir, const std::string& section_path) {
  const BuildResult built = runYaml(bodyYaml(section_path), "cantilever.yaml");
  const std::string path = dir + "/cantilever.h5";
  Provenance p;
  p.inputs_sha256 = std::string(64, '0');
  writeFlexBody(path, built.body, computeInertiaInvariants(built.body), p);
  return path;
}

TEST(BeamPlyStress, CantileverRootPliesEqualTheSectionRecoveryForTheStaticResultants) {
  const std::string dir = scratchDir("beam-ply-stress");
  const Section sec = writeSection(dir, true);
  const std::string body = writeBody(dir, sec.path);
  const StressRecoveryData d = readStressData(body, 60);
  const long ns = static_cast<long>(sec.mesh.elements.size());
  ASSERT_EQ(d.section.size(), ns);
  ASSERT_EQ(d.beam_stations.rows(), 3 * kElements);

  const mbs::Model model = mbs::parseScene(InputNode::loadString(scene(body, "beam"), "scene.yaml"));
  const mbs::Results r = mbs::simulate(model, {true});
  ASSERT_EQ(r.status, "completed");
  const std::vector<Eigen::VectorXd>& last = r.stress[1].back();
  ASSERT_EQ(last.size(), 3u);  // section_forces, ply_stress, failure_index
  const Eigen::VectorXd& forces = last[0];
  const Eigen::VectorXd& ply = last[1];
  const Eigen::VectorXd& fi = last[2];
  ASSERT_EQ(ply.size(), 3 * kElements * ns * 3);
  ASSERT_EQ(fi.size(), 3 * kElements * ns);

  // Station 0 is element 0's first node: the clamp (body x = -L/2).
  EXPECT_NEAR(d.beam_stations(0, 0), -0.5 * kL, 1e-12);
  section::Vector6d root;
  root << 0, 0, -kP, 0, kP * kL, 0;  // statics
  // The station's resultants from the run (midpoint + equilibrium) are statics
  // to the 1e-6 of P L of test_beam_section_forces.cpp.
  const mbs::Vector6d at0 = mbs::resultantsAtStation(forces.segment<6>(0), -0.5 * kL / kElements);
  EXPECT_LT((at0 - root).cwiseAbs().maxCoeff(), 1e-6 * kP * kL) << at0.transpose();

  std::vector<int> mat;
  for (const auto& e : sec.mesh.elements) mat.push_back(e.material);
  std::vector<std::optional<PlyStrength>> st;
  for (const auto& m : sec.mesh.materials) st.push_back(m.strength);
  const auto expect = section::recoverStresses(sec.p.recovery, mat, st, root);
  double peak = 0, worst = 0, worst_fi = 0, peak_fi = 0;
  for (long k = 0; k < ns; ++k) peak = std::max(peak, expect[k].ply_stress.cwiseAbs().maxCoeff());
  for (long k = 0; k < ns; ++k) {
    worst = std::max(worst, (ply.segment<3>(3 * k) - expect[k].ply_stress).cwiseAbs().maxCoeff());
    worst_fi = std::max(worst_fi, std::abs(fi(k) - expect[k].tsai_wu));
    peak_fi = std::max(peak_fi, expect[k].tsai_wu);
  }
  std::printf("[   info   ] root ply stresses: largest difference %.3e of the peak %.4e Pa; Tsai-Wu %.3e "
              "(largest index %.4e)\n", worst / peak, peak, worst_fi, peak_fi);
  // Linear in the resultants: the 1e-6 of the resultants carries over.
  EXPECT_LT(worst / peak, 2e-6);
  EXPECT_LT(worst_fi, 2e-6 * std::max(1.0, peak_fi) + 2e-6);
  // The run's peak: at the clamp (station 0), the largest index of the section.
  ASSERT_TRUE(r.peak_failure_index.found);
  EXPECT_EQ(r.peak_failure_index.body, "beam");
  EXPECT_EQ(r.peak_failure_index.element, 0);
  EXPECT_NEAR(r.peak_failure_index.value, peak_fi, 2e-6 * peak_fi);
  EXPECT_NEAR(fi(r.peak_failure_index.ply), peak_fi, 2e-6 * peak_fi);
}

TEST(BeamPlyStress, MissingStrengthsNameTheMaterialAndUnnamedBeamsCostNothing) {
  const std::string dir = scratchDir("beam-ply-stress-nostrength");
  const Section sec = writeSection(dir, false);
  const std::string body = writeBody(dir, sec.path);
  try {
    const mbs::Model model = mbs::parseScene(InputNode::loadString(scene(body, "beam"), "scene.yaml"));
    (void)mbs::simulate(model, {true});
    ADD_FAILURE() << "a ply material without strengths was accepted";
  } catch (const std::exception& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'im6'"), std::string::npos) << m;
    EXPECT_NE(m.find("strength"), std::string::npos) << m;
  }
  // Not named in outputs.stresses: no recovery at all.
  const mbs::Model model = mbs::parseScene(InputNode::loadString(scene(body, ""), "scene2.yaml"));
  EXPECT_EQ(model.bodies[1].stress, nullptr);
}

}  // namespace
}  // namespace fc::feprep::test
