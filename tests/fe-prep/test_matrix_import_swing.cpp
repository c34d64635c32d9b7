// The honesty test of /inertia/ for an imported body: the CalculiX fitting of
// tests/data/import/ (11 kHz first mode: stiff), hung at a rigid patch on its
// lug's top face on a revolute and swinging under gravity in mbs-run, must move
// as a rigid pendulum built from the file's own /inertia/ (which is M's
// rigid-body projection, test_matrix_import.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "common/flexbody.h"
#include "common/input.h"
#include "fe-prep/build_body.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/scene/scene.h"
#include "tests/fe-prep/feprep_test_support.h"

namespace fc::feprep {
namespace {

std::vector<double> swing(const std::string& body_block) {
  // Pivot 30 mm above the base (the lug patch's point), axis y; gravity along -x
  // so that the fitting starts 90 degrees from hanging.
  const std::string scene = R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: fitting
)" + body_block + R"(
joints:
  - {name: pivot, type: revolute, bodies: [ground, fitting], points: [[0, 0, 0.030], [0, 0, 0.030]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {type: gravity, g: [-9.81, 0, 0]}
simulation: {t_end: 2.0, output_step: 0.01, rtol: 1.0e-9}
)";
  const mbs::Results r = mbs::simulate(mbs::parseScene(InputNode::loadString(scene, "swing.yaml")), {true});
  EXPECT_EQ(r.status, "completed");
  return r.joint_angle.at(0);
}

TEST(MatrixImportSwing, StiffImportedFittingSwingsAsTheRigidBodyOfItsInertia) {
  const std::string dir = test::scratchDir("import_swing");
  const std::string data = std::string(FLEXCOMP_DATA_DIR) + "/import/";
  const std::string yaml = dir + "/fitting.yaml";
  std::ofstream(yaml) << "body:\n  name: fitting\n  matrices: {format: calculix, stiffness: " << data
                      << "fitting_matrices.sti, mass: " << data << "fitting_matrices.mas, dofs: " << data
                      << "fitting_matrices.dof, model: " << data << "fitting_mesh.inp}\n  units: mm-t-s\n"
                      << "  interfaces:\n    lug: {point: [0, 0, 0.030], coupling: rigid, nodes: {edge: LUGTOP}}\n"
                      << "  modes: 2\n";
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult built = buildFlexBody(MPI_COMM_WORLD, readBodySpec(yaml), opt);
  const std::string h5 = dir + "/fitting.h5";
  Provenance p;
  p.inputs_sha256 = std::string(64, '0');
  writeFlexBody(h5, built.body, computeInertiaInvariants(built.body), p);
  const FlexBody b = readFlexBody(h5).body;
  const Eigen::Vector3d c = b.center_of_mass;
  const Eigen::Matrix3d J = b.inertia_tensor - b.mass * (c.dot(c) * Eigen::Matrix3d::Identity() - c * c.transpose());
  char rigid[1024];
  std::snprintf(rigid, sizeof rigid,
                "    rigid: {mass: %.17g, center_of_mass: [%.17g, %.17g, %.17g], inertia: [[%.17g, %.17g, %.17g], "
                "[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g]]}\n",
                b.mass, c.x(), c.y(), c.z(), J(0, 0), J(0, 1), J(0, 2), J(1, 0), J(1, 1), J(1, 2), J(2, 0), J(2, 1), J(2, 2));
  const std::vector<double> a_rigid = swing(rigid);
  const std::vector<double> a_flex = swing("    flexible: {file: " + h5 + ", modes: 2, damping_ratio: 0.01}\n");
  ASSERT_EQ(a_rigid.size(), a_flex.size());
  double diff = 0.0, amplitude = 0.0;
  for (std::size_t k = 0; k < a_rigid.size(); ++k) {
    diff = std::max(diff, std::abs(a_rigid[k] - a_flex[k]));
    amplitude = std::max(amplitude, std::abs(a_rigid[k] - a_rigid[0]));
  }
  std::printf("[   info   ] imported fitting: swing amplitude %.3f rad, max |flexible - rigid from /inertia/| = %.2e rad\n",
              amplitude, diff);
  EXPECT_GT(amplitude, 1.0);  // it swings (starts 90 degrees from hanging)
  // 1e-4 rad over 2 s (the issue's figure): the integrators agree far better at
  // rtol 1e-9, and an 11 kHz fitting deflects by ~1e-9 of its size under g
  // (measured 5.8e-8 rad over a swing of pi).
  EXPECT_LT(diff, 1e-4);
}

}  // namespace
}  // namespace fc::feprep
