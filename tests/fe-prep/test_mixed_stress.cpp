// Stress recovery of a body mixing shell and beam regions (a stiffened panel:
// a [0/90/90/0] CFRP skin with an aluminium stringer sharing its nodes),
// docs/stresses.md "Mixed bodies": the skin's ply stresses and failure indices
// and the stringer's section forces in one recovery, against closed forms.
//
// The states are imposed nodal displacement fields used as two "modes" of the
// body's mesh, so that the recovery's q is that field's amplitude:
//  - a uniform stretch u = eps x: every ply k carries Q_k T(theta_k) [eps, 0, 0]
//    (Jones, Mechanics of Composite Materials, eq. 2.84 and 4.10), the
//    stringer N = E A eps and nothing else;
//  - a uniform bending w = -kappa x^2 / 2, theta_y = kappa x (u = z theta_y):
//    ply k carries Q_k T(theta_k) [z_k kappa, 0, 0], the stringer bends about
//    its x2 axis, M = E I kappa with I = b h^3 / 12 of the section's extent
//    across x2, and no shear force.
// Both fields lie in the span of the elements' interpolations (the DST
// triangle's membrane is linear, its curvature field passes the constant
// curvature patch test; the Timoshenko element's linear rotation and w's mean
// slope give a constant curvature and a zero shear strain at the midpoint), so
// the recovered values are the closed forms to rounding: 1e-9 of the largest
// value is many orders above the products' rounding (~1e-14) and far below any
// discretisation error (none here).
// The same recovery is read back from the body file fe-prep writes for that
// mesh (with its true modes): the mixed layout of /mesh/centroids and
// /stress/* round-trips to the bit, and the shell and beam parts of the mixed
// recovery equal the pure-shell and pure-beam recoveries of the same elements.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>

#include "common/flexbody.h"
#include "common/input.h"
#include "fe-prep/body_spec.h"
#include "fe-prep/build_body.h"
#include "fe-prep/stress_recovery_data.h"
#include "feprep_test_support.h"
#include "lamination_references.h"
#include "mbs-run/mechanics/flexible/section_forces.h"
#include "mbs-run/monitors/stress_envelope.h"
#include "mbs-run/monitors/stress_recovery.h"
#include "mbs-run/monitors/stress_recovery_mixed.h"

namespace fc::feprep::test {
namespace {

const double E1 = 177e9, E2 = 10.8e9, G12 = 7.6e9, NU12 = 0.27;
const double kAngles[4] = {0, 90, 90, 0};
const double kPly = 0.0005;
const double E_ALU = 70e9, WIDTH = 0.01, HEIGHT = 0.03;  // stringer section, x2 across the width

std::string mixedPanelYaml(const std::string& geo) {
  return R"(
materials:
  alu: {type: isotropic, E: 70.0e9, nu: 0.3, rho: 2700}
  im6: {type: orthotropic, E1: 177e9, E2: 10.8e9, E3: 10.8e9,
        G12: 7.6e9, G13: 7.6e9, G23: 8.504e9, nu12: 0.27, nu13: 0.27, nu23: 0.5, rho: 1600,
        strength: {Xt: 3.5e9, Xc: 1.54e9, Yt: 56e6, Yc: 150e6, S12: 98e6}}
laminates:
  layup2:
    - {material: im6, thickness: 0.0005, angle_deg: 0}
    - {material: im6, thickness: 0.0005, angle_deg: 90}
    - {material: im6, thickness: 0.0005, angle_deg: 90}
    - {material: im6, thickness: 0.0005, angle_deg: 0}
body:
  name: stiffened
  mesh: {file: )" + geo + R"(}
  regions:
    skin: {shell: {laminate: layup2, element: dst, axis: [1, 0, 0]}}
    stringer: {beam: {section: {shape: rectangle, width: 0.01, height: 0.03, material: alu}, orientation: [0, 1, 0]}}
  reference: {clamp: [root]}
  modes: 6
)";
}

// A 0.6 x 0.4 m skin with a stringer line along y = 0 embedded in it (its
// beam elements share the skin's nodes), the root edge x = -0.3 a group.
std::string writePanelGeo(const std::string& dir) {
  const std::string path = dir + "/panel.geo";
  std::ofstream(path) << R"(h = 0.1;
Point(1) = {-0.3, -0.2, 0, h}; Point(2) = {0.3, -0.2, 0, h}; Point(3) = {0.3, 0.2, 0, h};
Point(4) = {-0.3, 0.2, 0, h}; Point(5) = {-0.3, 0, 0, h}; Point(6) = {0.3, 0, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 6}; Line(3) = {6, 3}; Line(4) = {3, 4}; Line(5) = {4, 5}; Line(6) = {5, 1};
Line(7) = {5, 6};
Curve Loop(1) = {1, 2, -7, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {7, 3, 4, 5}; Plane Surface(2) = {2};
Physical Surface("skin") = {1, 2};
Physical Curve("stringer") = {7};
Physical Curve("root") = {5, 6};
)";
  return path;
}

Eigen::Matrix3d reducedQ() { return fc::feprep::test::reducedStiffness(E1, E2, G12, NU12); }
using fc::feprep::test::reuterT;  // laminate -> ply axes, engineering strains

// A mixed body's recovery data as its two parts: the triangles alone (a shell
// body's) and the beams alone (a beam body's), for comparison with the mixed one.
std::pair<StressRecoveryData, StressRecoveryData> splitMixed(const StressRecoveryData& d) {
  const long nb = d.beam_resultants.rows() / 6, nt = d.centroids.rows() - nb;
  StressRecoveryData beams;
  beams.centroids = d.centroids.bottomRows(nb);
  beams.beam_resultants = d.beam_resultants;
  StressRecoveryData shells = d;
  shells.centroids = d.centroids.topRows(nt);
  shells.beam_resultants.resize(0, 0);
  return {shells, beams};
}

TEST(MixedBodyStress, SkinPliesAndStringerForcesOfImposedStatesAreTheClosedForms) {
  const std::string dir = scratchDir("mixed_stress_closed_forms");
  const BodySpec spec = parseBodySpec(InputNode::loadString(mixedPanelYaml(writePanelGeo(dir)), "<mixed>"));
  const Mesh mesh = meshBody(PETSC_COMM_WORLD, spec, true);
  ASSERT_FALSE(mesh.triangles.empty());
  ASSERT_FALSE(mesh.beams.empty());
  const double eps = 1e-4, kappa = 1e-2;  // [-], [1/m]
  const long n = mesh.nodes.rows();
  Eigen::MatrixXd shapes = Eigen::MatrixXd::Zero(6 * n, 2);
  for (long i = 0; i < n; ++i) {
    const double x = mesh.nodes(i, 0);
    shapes(6 * i + 0, 0) = eps * x;
    shapes(6 * i + 2, 1) = -0.5 * kappa * x * x;
    shapes(6 * i + 4, 1) = kappa * x;
  }
  std::string note;
  const StressRecoveryData d = stressRecoveryData(mesh, spec, shapes, note);
  const long nt = static_cast<long>(mesh.triangles.size()), nb = static_cast<long>(mesh.beams.size());
  ASSERT_TRUE(d.hasShell() && d.hasBeam()) << note;
  ASSERT_EQ(d.centroids.rows(), nt + nb);  // the triangles' centroids, then the beams' midpoints
  const auto r = mbs::stressRecovery(d, "<mixed>");
  EXPECT_EQ(mbs::mixedShellOutputs(*r), 3u);
  // The layout: the shell outputs over the triangles, then the beams'.
  ASSERT_EQ(r->outputs.size(), 4u);
  EXPECT_EQ(r->outputs[0].name, "ply_stress");
  EXPECT_EQ(r->outputs[0].dims, (std::vector<long>{nt, 4, 3}));
  EXPECT_EQ(r->outputs[1].name, "failure_index");
  EXPECT_EQ(r->outputs[2].name, "hashin");
  EXPECT_EQ(r->outputs[3].name, "section_forces");
  EXPECT_EQ(r->outputs[3].dims, (std::vector<long>{nb, 6}));

  const Eigen::Matrix3d Q = reducedQ();
  const double A = WIDTH * HEIGHT, I = WIDTH * HEIGHT * HEIGHT * HEIGHT / 12.0;  // about x2 (width along x2 = y, height along x3 = z)
  for (int state = 0; state < 2; ++state) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(2);
    q(state) = 1.0;
    std::vector<Eigen::VectorXd> f;
    r->recover(q, f);
    ASSERT_EQ(f.size(), 4u);
    double scale = 0.0, err = 0.0;
    for (long e = 0; e < nt; ++e)
      for (int k = 0; k < 4; ++k) {
        const double z = -2 * kPly + (k + 0.5) * kPly;
        const Eigen::Vector3d strain = state == 0 ? Eigen::Vector3d(eps, 0, 0) : Eigen::Vector3d(z * kappa, 0, 0);
        const Eigen::Vector3d ref = Q * reuterT(kAngles[k]) * strain;
        const Eigen::Vector3d got = f[0].segment<3>(3 * (4 * e + k));
        scale = std::max(scale, ref.cwiseAbs().maxCoeff());
        err = std::max(err, (got - ref).cwiseAbs().maxCoeff());
      }
    std::printf("state %d: skin ply stresses %.2e of %.3e Pa\n", state, err / scale, scale);
    EXPECT_LT(err, 1e-9 * scale) << "skin ply stresses, state " << state << ": " << err << " of " << scale;
    // The stringer: [N, V2, V3, T, M2, M3] at every midpoint.
    Eigen::Matrix<double, 6, 1> ref = Eigen::Matrix<double, 6, 1>::Zero();
    if (state == 0) ref(0) = E_ALU * A * eps;
    const double Mref = E_ALU * I * kappa;
    double berr = 0.0;
    for (long e = 0; e < nb; ++e) {
      Eigen::Matrix<double, 6, 1> got = f[3].segment<6>(6 * e);
      if (state == 1) {
        // Bending in the x-z plane: about the section's x2 (y) axis; its sign
        // follows the section's convention, the magnitude is E I kappa.
        EXPECT_NEAR(std::abs(got(4)), Mref, 1e-9 * Mref) << "beam " << e;
        got(4) = 0.0;
      }
      berr = std::max(berr, (got - ref).cwiseAbs().maxCoeff());
    }
    const double bscale = state == 0 ? E_ALU * A * eps : Mref;
    std::printf("state %d: stringer section forces %.2e of %.3e\n", state, berr / bscale, bscale);
    EXPECT_LT(berr, 1e-9 * bscale) << "stringer section forces, state " << state << ": " << berr;
  }
}

TEST(MixedBodyStress, BodyFileRoundTripsAndTheMixedRecoveryIsTheShellsAndTheBeams) {
  const std::string dir = scratchDir("mixed_stress_file");
  const BuildResult b = runYaml(mixedPanelYaml(writePanelGeo(dir)), "<mixed>");
  ASSERT_TRUE(b.body.stress.hasShell() && b.body.stress.hasBeam());
  const std::string path = dir + "/stiffened.h5";
  Provenance p;
  p.inputs_sha256 = std::string(64, '0');
  writeFlexBody(path, b.body, computeInertiaInvariants(b.body), p);
  const int nm = static_cast<int>(b.body.shapes.cols());
  const StressRecoveryData d = readStressData(path, nm);
  ASSERT_TRUE(d.hasShell() && d.hasBeam());
  EXPECT_EQ(d.centroids, b.body.stress.centroids);
  EXPECT_EQ(d.shell_strains, b.body.stress.shell_strains);
  EXPECT_EQ(d.beam_resultants, b.body.stress.beam_resultants);
  const auto mixed = mbs::loadStressRecovery(path, nm);

  // The parts on their own: the triangles as a shell body, the beams as a beam body.
  const auto [shells, beams] = splitMixed(d);
  const auto shell = mbs::shellStressRecovery(shells), beam = mbs::beamStressRecovery(beams);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(nm, 1.0, -0.5);
  std::vector<Eigen::VectorXd> fm, fs, fb;
  mixed->recover(q, fm);
  shell->recover(q, fs);
  beam->recover(q, fb);
  ASSERT_EQ(fm.size(), fs.size() + fb.size());
  for (std::size_t i = 0; i < fs.size(); ++i) EXPECT_EQ(fm[i], fs[i]) << mixed->outputs[i].name;
  for (std::size_t i = 0; i < fb.size(); ++i) EXPECT_EQ(fm[fs.size() + i], fb[i]) << mixed->outputs[fs.size() + i].name;
  EXPECT_GT(fm[0].cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(fm.back().cwiseAbs().maxCoeff(), 0.0);
}

TEST(MixedBodyStress, BeamEnvelopeAndPeakSectionMomentAreTheBeamBodys) {
  // The same rows folded by the mixed body's envelope and by the beam-only
  // body's (the same beam elements, the same modal coordinates): the beams'
  // section_forces_max/min and the peak section moment must be the beam body's
  // exactly (the same numbers through the same max/min), and the shells'
  // envelope the shell body's; nothing else may appear.
  const std::string dir = scratchDir("mixed_stress_envelope");
  const BuildResult b = runYaml(mixedPanelYaml(writePanelGeo(dir)), "<mixed>");
  const StressRecoveryData& d = b.body.stress;
  ASSERT_TRUE(d.hasShell() && d.hasBeam());
  const int nm = static_cast<int>(d.shell_strains.cols());
  const auto [shells, beams] = splitMixed(d);
  const auto mixed = mbs::stressRecovery(d, "<mixed>");
  const auto shell = mbs::shellStressRecovery(shells), beam = mbs::beamStressRecovery(beams);
  mbs::StressEnvelope em, es, eb;
  // Rows of different sign and mode mix, so that max and min come from different rows.
  double peak_mixed = 0, peak_beam = 0;
  long el_mixed = -1, el_beam = -1;
  for (int row = 0; row < 5; ++row) {
    Eigen::VectorXd q(nm);
    for (int i = 0; i < nm; ++i) q(i) = std::sin(1.3 * row + 0.7 * i) * (1.0 + 0.1 * i);
    std::vector<Eigen::VectorXd> fm, fs, fb;
    mixed->recover(q, fm);
    shell->recover(q, fs);
    beam->recover(q, fb);
    const double t = 0.1 * row;
    em.observe(*mixed, fm, t);
    es.observe(*shell, fs, t);
    eb.observe(*beam, fb, t);
    const Eigen::VectorXd* sm = mbs::sectionForcesField(*mixed, fm);
    const Eigen::VectorXd* sb = mbs::sectionForcesField(*beam, fb);
    ASSERT_NE(sm, nullptr);
    ASSERT_NE(sb, nullptr);
    EXPECT_EQ(mbs::sectionForcesField(*shell, fs), nullptr);
    const mbs::SectionForcePeak pm = mbs::largestSectionForces(*sm), pb = mbs::largestSectionForces(*sb);
    if (pm.bending > peak_mixed) peak_mixed = pm.bending, el_mixed = pm.bending_element;
    if (pb.bending > peak_beam) peak_beam = pb.bending, el_beam = pb.bending_element;
  }
  EXPECT_GT(peak_beam, 0.0);
  EXPECT_EQ(peak_mixed, peak_beam);
  EXPECT_EQ(el_mixed, el_beam);
  const auto dm = em.datasets(*mixed), ds = es.datasets(*shell), db = eb.datasets(*beam);
  ASSERT_EQ(dm.size(), ds.size() + db.size());
  for (std::size_t i = 0; i < ds.size(); ++i) {
    EXPECT_EQ(dm[i].name, ds[i].name);
    EXPECT_EQ(dm[i].values, ds[i].values) << ds[i].name;
  }
  ASSERT_EQ(db.size(), 2u);  // no section basis: section_forces_max, section_forces_min
  for (std::size_t i = 0; i < db.size(); ++i) {
    const mbs::EnvelopeDataset& m = dm[ds.size() + i];
    EXPECT_EQ(m.name, db[i].name);
    EXPECT_EQ(m.dims, db[i].dims);
    EXPECT_EQ(m.values, db[i].values) << db[i].name;
  }
  EXPECT_EQ(db[0].name, "section_forces_max");
  EXPECT_EQ(db[1].name, "section_forces_min");
  EXPECT_GT((db[0].values - db[1].values).maxCoeff(), 0.0);  // the rows differ: max and min are not one row
}

}  // namespace
}  // namespace fc::feprep::test
