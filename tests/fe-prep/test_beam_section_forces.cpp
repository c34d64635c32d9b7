// Beam section forces from a run: a cantilever clamped to the
// ground under a static tip force in mbs-run, settled by heavy modal damping.
// Reference nobody here wrote: statics, M(x) = P (L - x), V = P, N = T = 0,
// and the clamp's reaction moment P L. Recovered by the mode-displacement
// method (mbs-run/mechanics/flexible/section_forces.h) from fe-prep's per-mode midpoint
// resultants: with clamped-root modes it converges as modes are added (the
// table printed), and with every mode of the model, or with a Craig-Bampton
// body whose boundary includes the loaded tip, it is the finite element
// model's static solution, which the flexibility-based element makes exact at
// the element midpoints.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "common/flexbody.h"
#include "common/input.h"
#include "fe-prep/elements/beam_element.h"
#include "feprep_test_support.h"
#include "mbs-run/mechanics/flexible/section_forces.h"
#include "mbs-run/scene/scene.h"
#include "mbs-run/run/simulation.h"

namespace fc::feprep::test {
namespace {

const double kL = 1.0, kP = 1.0;  // [m], [N]
const int kElements = 10;

std::string bodyYaml(const std::string& modes, bool craig_bampton) {
  return std::string(R"(
materials:
  steel: {type: isotropic, E: 210.0e9, nu: 0.3, rho: 7850}
body:
  name: cantilever
  beam: {length: 1.0, elements: 10, section: {shape: solid_circle, diameter: 0.02, material: steel}}
  interfaces: {root: [-0.5, 0, 0], tip: [0.5, 0, 0]}
)") + (craig_bampton ? "  reference: {clamp: [root, tip]}\n  reduction: craig_bampton\n" : "  reference: {clamp: [end_min]}\n") +
         "  modes: " + modes + "\n";
}

struct Settled {
  Eigen::VectorXd forces;                  // (6 n_el) section forces at the end of the run
  Eigen::Vector3d reaction, reaction_torque;  // on the ground, global
  std::string status;
  double peak_moment = 0.0;  // the run summary's largest |(M2, M3)| and its element
  long peak_element = -1;
};

// The body clamped to the ground at its root (global origin, body along +x),
// tip force -P z from t = 0, every mode critically damped: with clamped-root
// modes, after 0.4 s (6 periods of the 14.5 Hz first mode, e^-(omega t)
// (1 + omega t) < 1e-14) the body is at rest under the load. P = 1 N keeps
// the deflection (P L^3 / 3EI = 0.2 mm) linear.
Settled settle(const std::string& yaml, const std::string& tag, double t_end = 0.4) {
  const BodySpec spec = parseBodySpec(InputNode::loadString(yaml, tag + ".yaml"));
  const BuildResult built = runYaml(yaml, tag + ".yaml");
  const FlexBody& body = built.body;
  const std::string path = scratchDir("beam-forces-" + tag) + "/cantilever.h5";
  Provenance p;
  p.inputs_sha256 = std::string(64, '0');
  writeFlexBody(path, body, computeInertiaInvariants(body), p);
  char scene[2048];
  std::snprintf(scene, sizeof scene, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - {name: beam, flexible: {file: %s, modes: all, damping_ratio: 1.0}, position: [0.5, 0, 0]}
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
forces:
  - {type: force, body: beam, point: tip, force: [0, 0, %g]}
outputs: {stresses: [beam]}
simulation: {t_end: %g, output_step: 0.1, rtol: 1.0e-8}
)",
                path.c_str(), -kP, t_end);
  const mbs::Model model = mbs::parseScene(InputNode::loadString(scene, tag + "-scene.yaml"));
  const mbs::Results r = mbs::simulate(model, {true});
  // The file holds what the element kernel gives for the body's modes.
  std::vector<std::array<long, 2>> beams;
  const IndexMatrix& conn = body.elements.at("beams");
  for (long e = 0; e < conn.rows(); ++e) beams.push_back({conn(e, 0), conn(e, 1)});
  const Eigen::MatrixXd R =
      fe::beamModalResultants(body.nodes, beams, Eigen::Vector3d::UnitY(), spec.beam->Ks, body.shapes);
  const StressRecoveryData d = readStressData(path, body.modeCount());
  EXPECT_EQ((d.beam_resultants - R).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(d.centroids.rows(), kElements);
  // The run's /bodies/beam/section_forces at its last output, and its summary's peak.
  EXPECT_TRUE(r.peak_section_moment.found);
  EXPECT_EQ(r.peak_section_moment.body, "beam");
  return {r.stress[1].back()[0], r.reaction[0].back(), r.reaction_torque[0].back(), r.status,
          r.peak_section_moment.value, r.peak_section_moment.element};
}

// Largest error of the bending moment M2 against P (L - x) at the midpoints,
// relative to P L; x from the clamp.
double momentError(const Eigen::VectorXd& s) {
  double worst = 0.0;
  for (int e = 0; e < kElements; ++e) {
    const double x = (e + 0.5) * kL / kElements;
    worst = std::max(worst, std::abs(s(6 * e + 4) - kP * (kL - x)) / (kP * kL));
  }
  return worst;
}

TEST(BeamSectionForces, CantileverUnderTipLoadConvergesWithModesAndIsExactWithAll) {
  // Convergence with clamped-root modes: the tip load excites every bending
  // mode in the x-z plane, whose static participation falls as 1/omega^2.
  double previous = 1.0;
  std::printf("[   info   ] cantilever, tip load %.0f N: max |M2 - P (L - x)| / (P L) at the element midpoints\n", kP);
  for (const char* modes : {"2", "4", "8", "16"}) {
    const Settled s = settle(bodyYaml(modes, false), std::string("free") + modes);
    ASSERT_EQ(s.status, "completed");
    const double err = momentError(s.forces);
    std::printf("[   info   ]   %2s clamped modes: %.3e\n", modes, err);
    EXPECT_LT(err, previous) << modes << " modes";
    previous = err;
  }
  // All 60 modes of the 10-element model: the model's static solution, exact at
  // the midpoints. What is left: the settling (< 1e-20), the integrator (rtol
  // 1e-8 on modal coordinates whose static parts span 1e-2..1e-9 of the
  // largest) and the roundoff of the resultants (1e-9, test_beam_resultants):
  // 1e-6 of P L.
  const Settled all = settle(bodyYaml("60", false), "all");
  ASSERT_EQ(all.status, "completed");
  std::printf("[   info   ]   60 clamped modes (all): %.3e\n", momentError(all.forces));
  EXPECT_LT(momentError(all.forces), 1e-6);
  for (int e = 0; e < kElements; ++e) {
    // V3 = F3 = -P; N, V2, T, M3 zero (to the same 1e-6 of P and P L).
    EXPECT_NEAR(all.forces(6 * e + 2), -kP, 1e-6 * kP) << "element " << e;
    for (int c : {0, 1, 3, 5}) EXPECT_NEAR(all.forces(6 * e + c), 0.0, 1e-6 * kP * kL) << "element " << e << " c " << c;
  }
  // The clamp's reaction on the ground: the tip force and its moment about the
  // clamp, L e_x x (-P e_z) = P L e_y, passed on to the ground.
  // The torque is the multiplier of the state's own solve, so it also carries
  // the residual motion of the stiff modes (to 2.7e4 Hz) that the section
  // forces at the midpoints do not: measured at settled rows 2e-10..1.1e-6
  // of P L with dopri5, imex, trbdf2 and rtol 1e-8..1e-10 (it follows the
  // step sequence, not rtol; docs/validation.md). 5e-6 of P L stays far below
  // what a wrong lever or frame would give (the deflection ratio, 2e-4).
  EXPECT_NEAR(all.reaction.z(), -kP, 1e-6 * kP);
  EXPECT_NEAR(all.reaction_torque.y(), kP * kL, 5e-6 * kP * kL) << all.reaction_torque.transpose();
  EXPECT_NEAR(all.reaction_torque.x(), 0.0, 5e-6 * kP * kL);
  EXPECT_NEAR(all.reaction_torque.z(), 0.0, 5e-6 * kP * kL);
  // The summary's peak: the element next to the clamp, P (L - L/20) (the
  // step response overshoots nothing with critical damping).
  EXPECT_EQ(all.peak_element, 0);
  EXPECT_NEAR(all.peak_moment, kP * (kL - 0.5 * kL / kElements), 1e-6 * kP * kL);
}

TEST(BeamSectionForces, CraigBamptonWithTheLoadedTipIsExactWithFewShapes) {
  // Boundary: the clamp and the loaded tip (12 constraint modes - 6 rigid) plus
  // 2 fixed-interface modes = 8 shapes: the static response to a tip load is in
  // the basis, so the recovery is the finite element model's, exact at the
  // midpoints, with 8 shapes where 16 clamped modes miss (table above).
  // The frame of a Craig-Bampton body is not held at the root: the pair's
  // first mode is mostly frame rotation about the clamp, which the shapes'
  // modal damping damps weakly (as in test_craig_bampton.cpp), so it settles
  // in ~2 s, not 0.4 (at 1 s the error is still 7e-4 of P L). The frame then
  // rotates by ~ the tip slope P L^2 / 2EI = 3e-4 rad, tilting the global
  // force in body axes: M2 is P L cos(theta), 1 - 5e-8; within the 1e-6.
  const Settled cb = settle(bodyYaml("2", true), "cb", 3.0);
  ASSERT_EQ(cb.status, "completed");
  std::printf("[   info   ] Craig-Bampton (8 shapes): max |M2 - P (L - x)| / (P L) = %.3e\n", momentError(cb.forces));
  EXPECT_LT(momentError(cb.forces), 1e-6);
  for (int e = 0; e < kElements; ++e) EXPECT_NEAR(cb.forces(6 * e + 2), -kP, 1e-6 * kP) << "element " << e;
  EXPECT_NEAR(cb.reaction_torque.y(), kP * kL, 1e-6 * kP * kL);
}

}  // namespace
}  // namespace fc::feprep::test
