// The results file holds the contract's layout ("results/1"), and a run
// stopped by a signal still writes a valid file whose status says why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>

#include "common/h5io.h"
#include "common/termination.h"
#include "helpers.h"
#include "mbs-run/output/results.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

const std::string kScene = testScene("ground_and_rod.yaml") + R"(joints:
  - {name: R, type: revolute, bodies: [ground, arm], points: [[0,0,0],[-0.5,0,0]], axes: [[0,1,0],[0,1,0]]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
  - {name: damper, type: rotational_spring_damper, joint: R, damping: 0.2}
simulation: {t_end: 1.0, output_step: 0.1, rtol: 1.0e-8}
)";

std::string tmpPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("mbs_test_" + std::to_string(::getpid()) + "_" + name)).string();
}

// A run writes its final state even when t_end is not a multiple of
// output_step (it used to stop at the last multiple: output_step 0.5 s with
// t_end 0.004 s wrote the initial row only), on both formulations.
TEST(ResultsFile, FinalStateIsWrittenWhenTEndIsNotAMultipleOfTheOutputStep) {
  for (const char* formulation : {"tree", "constrained"}) {
    auto run = [&](const char* step) {
      std::string scene = kScene;
      const std::string sim = "simulation: {t_end: 1.0, output_step: 0.1, rtol: 1.0e-8}";
      scene.replace(scene.find(sim), sim.size(),
                    std::string("simulation: {t_end: 1.0, output_step: ") + step +
                        ", rtol: 1.0e-8, formulation: " + formulation + "}");
      return simulate(sceneFromText(scene), {true});
    };
    const Results thirds = run("0.3"), halves = run("0.5"), beyond = run("2.0");
    for (const Results* r : {&thirds, &halves, &beyond}) ASSERT_EQ(r->status, "completed") << formulation;
    const std::vector<double> expect = {0.0, 0.3, 0.6, 0.9, 1.0};
    ASSERT_EQ(thirds.time.size(), expect.size()) << formulation;
    for (std::size_t k = 0; k < expect.size(); ++k) EXPECT_NEAR(thirds.time[k], expect[k], 1e-12);
    ASSERT_EQ(beyond.time.size(), 2u) << formulation;
    EXPECT_EQ(beyond.time.back(), 1.0);
    EXPECT_EQ(halves.time.back(), 1.0);
    // The same final state whatever the output step: the runs take other
    // steps (max_step is 10 output steps), each with local errors below rtol
    // 1e-8 of O(1) rad over < 200 steps: 1e-6 rad bounds their difference.
    for (const Results* r : {&thirds, &beyond}) {
      const double c = std::abs(r->orientation[1].back().dot(halves.orientation[1].back()));
      EXPECT_LT(2.0 * std::acos(std::min(c, 1.0)), 1e-6) << formulation;  // the rotation between them
    }
  }
}

// A run with thousands of events (a rigid-truss SAR run's resting stops)
// failed to write its results file: HDF5 keeps attributes in the object
// header (at most 64 kB). The logs are now cut below that and say so.
TEST(ResultsFile, LongEventLogStillWritesTheFile) {
  const Model m = sceneFromText(kScene);
  Results r = simulate(m, {true});
  for (int k = 0; k < 5000; ++k)
    r.event_log.push_back("t=" + std::to_string(k) + ": stop S on joint R rests (a long enough line of text)");
  const std::string path = tmpPath("long_log.h5");
  ASSERT_NO_THROW(writeResults(path, m, r, "deadbeef"));
  fc::H5File f(path, fc::H5File::Mode::Read);
  const std::string events = f.stringAttribute("/", "events");
  EXPECT_LT(events.size(), 64000u);
  EXPECT_EQ(events.rfind("t=0: stop S", 0), 0u) << events.substr(0, 80);  // the first events are kept
  EXPECT_NE(events.find(" more lines (the run's summary on stdout lists them all)"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(ResultsFile, ContractLayout) {
  const Model m = sceneFromText(kScene);
  const Results r = simulate(m, {true});
  const std::string path = tmpPath("layout.h5");
  writeResults(path, m, r, "deadbeef");
  fc::H5File f(path, fc::H5File::Mode::Read);
  EXPECT_EQ(f.checkFormat("results", 1), 1);
  const long n = 11;  // 0, 0.1, ..., 1.0
  EXPECT_EQ(f.shape("/time")[0], hsize_t(n));
  for (const char* b : {"ground", "arm"}) {
    const std::string p = std::string("/bodies/") + b;
    EXPECT_EQ(f.shape(p + "/position"), (std::vector<hsize_t>{hsize_t(n), 3}));
    EXPECT_EQ(f.shape(p + "/orientation"), (std::vector<hsize_t>{hsize_t(n), 4}));
    EXPECT_EQ(f.shape(p + "/velocity"), (std::vector<hsize_t>{hsize_t(n), 3}));
    EXPECT_EQ(f.shape(p + "/angular_velocity"), (std::vector<hsize_t>{hsize_t(n), 3}));
  }
  EXPECT_EQ(f.shape("/joints/R/angle")[0], hsize_t(n));
  EXPECT_EQ(f.shape("/joints/R/reaction_force"), (std::vector<hsize_t>{hsize_t(n), 3}));
  EXPECT_EQ(f.shape("/joints/R/reaction_torque"), (std::vector<hsize_t>{hsize_t(n), 3}));
  // The run's peaks are those of the rows in the file.
  EXPECT_EQ(f.stringAttribute("/", "peak_reaction_force_joint"), "R");
  EXPECT_DOUBLE_EQ(f.doubleAttribute("/", "peak_reaction_force"),
                   f.readMatrix("/joints/R/reaction_force").rowwise().norm().maxCoeff());
  EXPECT_DOUBLE_EQ(f.doubleAttribute("/", "max_constraint_violation"),
                   f.readVector("/diagnostics/constraint_violation").maxCoeff());
  EXPECT_EQ(f.stringAttribute("/", "warnings"), "");  // a rigid scene: nothing to alias
  for (const char* e : {"kinetic", "potential", "strain", "dissipated"})
    EXPECT_EQ(f.shape(std::string("/energy/") + e)[0], hsize_t(n));
  EXPECT_EQ(f.shape("/diagnostics/constraint_violation")[0], hsize_t(n));
  EXPECT_EQ(f.stringAttribute("/", "status"), "completed");
  EXPECT_GT(f.doubleAttribute("/", "cpu_seconds"), 0.0);
  EXPECT_DOUBLE_EQ(f.doubleAttribute("/", "rtol"), 1.0e-8);  // the scene's
  EXPECT_DOUBLE_EQ(f.doubleAttribute("/", "atol"), 1.0e-11);  // default: 1e-3 rtol
  EXPECT_EQ(f.stringAttribute("/time", "units"), "s");        // self-describing datasets
  // Energy balance from the file: T + V + dissipated is constant.
  const Eigen::VectorXd T = f.readVector("/energy/kinetic"), V = f.readVector("/energy/potential"),
                        D = f.readVector("/energy/dissipated");
  EXPECT_GT(D[n - 1], 0.1);
  EXPECT_LT(((T + V + D).array() - (T[0] + V[0] + D[0])).abs().maxCoeff(), 1e-6);
  // A uniform rod released horizontally from rest: its centre of mass starts
  // down at 3g/4, so the pivot carries m g / 4 (classical result). The file
  // holds the force on the first body (ground): m g / 4 downwards. 1e-3 covers
  // the rod's thickness (I_o larger by 2e-5 relative).
  const Eigen::MatrixXd Rf = f.readMatrix("/joints/R/reaction_force");
  EXPECT_NEAR(Rf(0, 2), -9.81 / 4, 1e-3);  // force on the first body (ground), downwards
  f.close();
  std::filesystem::remove(path);
}

TEST(ResultsFile, InterruptedRunIsValidAndSaysWhy) {
  const Model m = sceneFromText(kScene);
  fc::raiseTerminationForTests(SIGTERM);
  const Results r = simulate(m, {true});
  fc::resetTerminationForTests();
  EXPECT_EQ(r.status, "interrupted by SIGTERM");
  const std::string path = tmpPath("stopped.h5");
  writeResults(path, m, r, "deadbeef");
  fc::H5File f(path, fc::H5File::Mode::Read);
  EXPECT_EQ(f.stringAttribute("/", "status"), "interrupted by SIGTERM");
  EXPECT_EQ(f.shape("/time")[0], 1u);  // the initial state was computed, nothing more
  f.close();
  std::filesystem::remove(path);
}

TEST(ResultsFile, CsvOfChosenChannels) {
  const Model m = sceneFromText(kScene);
  const Results r = simulate(m, {true});
  const std::string path = tmpPath("chosen.csv");
  writeCsv(path, m, r, {"joints/R/angle", "bodies/arm/position"});
  std::FILE* fp = std::fopen(path.c_str(), "r");
  ASSERT_NE(fp, nullptr);
  char line[512];
  ASSERT_NE(std::fgets(line, sizeof line, fp), nullptr);
  EXPECT_STREQ(line, "time,joints/R/angle,bodies/arm/position_x,bodies/arm/position_y,bodies/arm/position_z\n");
  int rows = 0;
  while (std::fgets(line, sizeof line, fp)) ++rows;
  std::fclose(fp);
  EXPECT_EQ(rows, 11);
  std::filesystem::remove(path);
  EXPECT_THROW(writeCsv(path, m, r, {"joints/R/angel"}), std::invalid_argument);
}

}  // namespace
}  // namespace fc::mbs::test
