// The consistent start (mbs-run/constrained/consistent_start.h, System::assemble) on
// scenes whose initial positions do not satisfy their joints:
// - a flexible beam placed 1 mm or 0.5 m away from the revolute that holds
//   it is assembled by its frame: its modal coordinates and rates stay as
//   given (a projection in M's metric spreads the gap into the light modal
//   coordinates as elastic deformation: docs/mbs-run.md, "Consistent
//   start"), and it moves as the same scene placed assembled;
// - a rigid body placed the same way moves as the one placed assembled;
// - joints that contradict each other are still told so;
// - a start only a large deformation could assemble (a clamped beam whose
//   tip is placed 0.5 m from its support) is told in the scene's terms
//   (which body, which joint, how far), not as contradicting joints; 1 mm
//   is kept as a preload.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "beam_body.h"
#include "common/rotations.h"
#include "helpers.h"
#include "mbs-run/constrained/consistent_start.h"
#include "mbs-run/run/simulation.h"
#include "mbs-run/constrained/system.h"

namespace fc::mbs::test {
namespace {

// The body hangs from the ground at its `point` by a revolute about z (the
// beam bends in the body x-y plane, so the joint's axis rows hold whatever
// its modes); gravity along -y swings it in that plane.
std::string hung(const std::string& body_block, const std::string& point, const std::string& pose) {
  return R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    )" + body_block + R"(
)" + pose + R"(
joints:
  - {name: J, type: revolute, bodies: [ground, beam], points: [[0, 0, 0], )" +
         point + R"(], axes: [[0, 0, 1], [0, 0, 1]]}
forces:
  - {type: gravity, g: [0, -9.81, 0]}
simulation: {t_end: 0.5, output_step: 0.01, rtol: 1.0e-9}
)";
}

std::string placedAt(const Eigen::Vector3d& r, const Eigen::Vector4d& p = Eigen::Vector4d(1, 0, 0, 0)) {
  char s[256];
  std::snprintf(s, sizeof s, "    orientation: [%.17g, %.17g, %.17g, %.17g]\n", p[0], p[1], p[2], p[3]);
  return "    position: " + yamlVector(r) + "\n" + s;
}

// A 1 m Hermite cantilever (beam_body.h: rho A = 1 kg/m, EI = 80 N m^2,
// clamped-root modes) deformed at the start: 4 modes with given coordinates
// and rates.
struct Beam {
  Beam() {
    BeamSpec s;
    s.elements = 8;
    s.modes = 4;
    model = cantileverBeam(s);
    file = writeBeam(model, "consistent_start");
  }
  ~Beam() { std::filesystem::remove(file); }
  std::string block() const {
    return "flexible: {file: " + file +
           ", modes: 4}\n    modal_coordinates: [0.01, -0.002, 0.001, 0.0005]\n"
           "    modal_velocities: [0.2, 0.1, -0.05, 0.02]";
  }
  BeamModel model;
  std::string file;
};

double largest(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

TEST(ConsistentStart, FlexibleBodyPlacedAwayIsAssembledByItsFrame) {
  const Beam beam;
  // The root (frame origin, no mode moves it) and the tip (every mode moves
  // it): 1 mm and 0.5 m off, and off in all three directions with a turn.
  const Eigen::Vector4d turned = fc::eulerParametersFromAxisAngle(Eigen::Vector3d(1, 2, 3).normalized(), 0.4);
  struct Case {
    const char* point;
    Eigen::Vector3d placed;  // where the joint's body point sits as placed
    Eigen::Vector4d orientation;
  };
  const Case cases[] = {{"root", {0.001, 0, 0}, {1, 0, 0, 0}},
                        {"root", {0.5, 0, 0}, {1, 0, 0, 0}},
                        {"root", {0.3, -0.4, 0.2}, turned},
                        {"tip", {0.001, 0, 0}, {1, 0, 0, 0}},
                        {"tip", {0.5, 0, 0}, {1, 0, 0, 0}},
                        {"tip", {0.3, -0.4, 0.2}, turned}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.point) + " placed at " + yamlVector(c.placed));
    // The frame sits where it puts the joint's body point, deformed by the
    // given modes, at c.placed.
    const FlexInterface& it = beam.model.body.interface("tip");
    const Eigen::Vector4d q(0.01, -0.002, 0.001, 0.0005);
    const Eigen::Vector3d tip = it.position + it.shapes.leftCols<3>().topRows(4).transpose() * q;
    const Eigen::Vector3d lever = std::string(c.point) == "tip" ? tip : Eigen::Vector3d::Zero();
    const Eigen::Vector3d frame = c.placed - fc::rotationMatrix(c.orientation) * lever;
    const Model m = sceneFromText(hung(beam.block(), c.point, placedAt(frame, c.orientation)));
    System sys(m);
    const Eigen::VectorXd placed = sys.initialState();
    Eigen::VectorXd gap = sys.jointPointGap(0, 0.0, placed);
    ASSERT_EQ(gap.size(), 3);
    EXPECT_LT((gap - c.placed).norm(), 1e-15);
    const Eigen::VectorXd y = consistentStart(sys, 1e-10);
    // Assembled: the points meet and the velocities are tangent, to the
    // projection's tolerance (1e-12 of the scene's size).
    const System::Violations v = sys.violations(0.0, y);
    EXPECT_LT(v.position, 1e-12);
    EXPECT_LT(v.velocity, 1e-11);
    // The modes as given, exactly: the frames closed the gap and made the
    // velocities tangent, so nothing touched the modal coordinates and rates.
    const Body& b = m.bodies[1];
    EXPECT_EQ(y.segment(b.pos_index + 7, 4), placed.segment(b.pos_index + 7, 4));
    EXPECT_EQ(y.segment(m.nq + b.dof_index + 6, 4), placed.segment(m.nq + b.dof_index + 6, 4));
  }
}

// The flexible body placed 0.5 m off moves as the same scene placed where the
// assembly put it. Both runs start from states equal to rounding (the modes
// as given, the frame's pose written at 17 digits) and integrate the same
// equations with the same tolerances; each is within the integrator's global
// error of the exact motion (rtol 1e-9 on a ~1 m, ~5 rad/s swing: ~1e-8), so
// 1e-7 m and 1e-6 in modal coordinates allow twice that with a margin for
// the error control's choices (they take the same steps: equal to rounding).
TEST(ConsistentStart, FlexibleBodyPlacedAwayMovesAsPlacedAssembled) {
  const Beam beam;
  const Model away = sceneFromText(hung(beam.block(), "root", placedAt({0.5, 0, 0})));
  System sys(away);
  const Eigen::VectorXd y = consistentStart(sys, 1e-10);
  const Body& b = away.bodies[1];
  const Eigen::Vector3d r = y.segment<3>(b.pos_index);
  const Eigen::Vector4d p = y.segment<4>(b.pos_index + 3);
  EXPECT_LT(r.norm(), 1e-12);  // the joint is at the frame origin
  const Model assembled = sceneFromText(hung(beam.block(), "root", placedAt(r, p)));
  const Results a = simulate(away, {true}), o = simulate(assembled, {true});
  ASSERT_EQ(a.status, "completed");
  ASSERT_EQ(o.status, "completed");
  ASSERT_EQ(a.time.size(), o.time.size());
  double d_pos = 0, d_modal = 0, swing = 0;
  for (std::size_t k = 0; k < a.time.size(); ++k) {
    const Eigen::Vector3d tip_a = fc::rotationMatrix(a.orientation[1][k]) * Eigen::Vector3d(1, 0, 0);
    const Eigen::Vector3d tip_o = fc::rotationMatrix(o.orientation[1][k]) * Eigen::Vector3d(1, 0, 0);
    d_pos = std::max({d_pos, (a.position[1][k] - o.position[1][k]).norm(), (tip_a - tip_o).norm()});
    d_modal = std::max(d_modal, largest(a.modal[1][k] - o.modal[1][k]));
    swing = std::max(swing, (tip_a - Eigen::Vector3d(1, 0, 0)).norm());
  }
  EXPECT_GT(swing, 0.5);  // it swings (gravity across the beam): not a trivial comparison
  EXPECT_LT(d_pos, 1e-7);
  EXPECT_LT(d_modal, 1e-6);
  EXPECT_EQ(a.modal[1][0], o.modal[1][0]);  // the first row: the modes as given, in both
}

// A rigid body placed 0.5 m off along the line from its joint point through
// its centre of mass: the mass-orthogonal correction is a pure translation
// (an impulse through the centre of mass), so it moves exactly as the body
// placed at the joint (same tolerances as above). Asked for joint
// coordinates, the misplaced scene runs constrained, saying why (the tree
// starts from a placement that holds its joints: kinematic_tree.h), and still
// moves as the placed one, which runs in joint coordinates.
TEST(ConsistentStart, RigidBodyPlacedAwayMovesAsPlacedAssembled) {
  const std::string rigid =
      "rigid: {mass: 1, center_of_mass: [0.5, 0, 0], inertia: [[0.01,0,0],[0,0.08,0],[0,0,0.08]]}";
  for (const char* formulation : {"constrained", "tree"}) {
    SCOPED_TRACE(formulation);
    auto scene = [&](const Eigen::Vector3d& r) {
      std::string text = hung(rigid, "[0, 0, 0]", placedAt(r));
      const std::string sim = "rtol: 1.0e-9}";
      text.replace(text.find(sim), sim.size(), "rtol: 1.0e-9, formulation: " + std::string(formulation) + "}");
      return sceneFromText(text);
    };
    const Results a = simulate(scene({0.5, 0, 0}), {true}), o = simulate(scene({0, 0, 0}), {true});
    if (std::string(formulation) == "tree") {
      EXPECT_EQ(a.formulation.rfind("constrained (joint J does not hold as placed (misses by 0.5 m or rad", 0), 0u)
          << a.formulation;
      EXPECT_EQ(o.formulation, "tree");
    } else {
      EXPECT_EQ(a.formulation.rfind(formulation, 0), 0u) << a.formulation;
    }
    ASSERT_EQ(a.status, "completed");
    ASSERT_EQ(o.status, "completed");
    ASSERT_EQ(a.time.size(), o.time.size());
    double d = 0;
    for (std::size_t k = 0; k < a.time.size(); ++k)
      d = std::max({d, (a.position[1][k] - o.position[1][k]).norm(),
                    (a.orientation[1][k] - o.orientation[1][k]).lpNorm<Eigen::Infinity>()});
    EXPECT_LT(a.position[1][0].norm(), 1e-12);
    EXPECT_GT((a.orientation[1].back() - a.orientation[1][0]).norm(), 0.1);  // it swings
    EXPECT_LT(d, 1e-7);
  }
}

// The fuzz case of three revolutes with contradicting axes (also placed 1 m
// apart at J3): the joints pull against each other wherever the assembly
// goes, and the message says so.
TEST(ConsistentStart, ContradictingJointsAreToldSo) {
  const Model m = parseScene(
      fc::InputNode::loadFile(std::string(FLEXCOMP_DATA_DIR) + "/mbs-run/conflicting_constraints.yaml"));
  const Results r = simulate(m, {true});
  EXPECT_EQ(r.status.rfind("unsatisfiable constraints at t = 0", 0), 0u) << r.status;
  EXPECT_NE(r.status.find("the joints contradict each other"), std::string::npos) << r.status;
}

// A beam clamped to the ground as placed (a fixed joint holds its frame)
// with its tip on a spherical joint to a ground point across the beam: the
// frame cannot close that gap, only the modes can. 1 mm is a misfit the
// structure takes as a preload (kept: the run completes, tip assembled);
// 0.5 m would be a deflection of half the beam, which linear modes do not
// describe: the scene is refused as not placed assembled, saying which body,
// which joint, how far and what to do, not blaming contradicting joints.
TEST(ConsistentStart, FarStartOnlyTheModesCouldCloseIsToldInTheScenesTerms) {
  const Beam beam;
  auto scene = [&](double across) {
    return sceneFromText(R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: beam
    flexible: {file: )" + beam.file + R"(, modes: 4}
joints:
  - {name: clamp, type: fixed, bodies: [ground, beam], points: [[0, 0, 0], root]}
  - {name: prop, type: spherical, bodies: [ground, beam], points: [)" +
                         yamlVector(Eigen::Vector3d(1, across, 0)) + R"(, tip]}
simulation: {t_end: 0.05, output_step: 0.01}
)");
  };
  const Model near = scene(1e-3);
  System sys(near);
  const Eigen::VectorXd y = consistentStart(sys, 1e-10);
  EXPECT_LT(sys.violations(0.0, y).position, 1e-12);
  const Eigen::VectorXd q = y.segment(near.bodies[1].pos_index + 7, 4);
  const FlexInterface& tip = beam.model.body.interface("tip");
  EXPECT_NEAR((tip.shapes.leftCols<3>().topRows(4).transpose() * q).y(), 1e-3, 1e-12);  // the preload
  EXPECT_EQ(simulate(near, {true}).status, "completed");

  const Results r = simulate(scene(0.5), {true});
  EXPECT_EQ(r.status.rfind("unsatisfiable constraints at t = 0: body beam is not placed assembled: joint prop's "
                           "points are 0.5 m apart at t = 0",
                           0),
            0u)
      << r.status;
  EXPECT_NE(r.status.find("its modes would have to deflect interface tip by 0.5 m"), std::string::npos) << r.status;
  EXPECT_NE(r.status.find("place the body where its joints hold"), std::string::npos) << r.status;
  EXPECT_EQ(r.status.find("contradict"), std::string::npos) << r.status;
}

}  // namespace
}  // namespace fc::mbs::test
