// HDF5 round trips, format checks and atomic writes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "common/h5io.h"

namespace fs = std::filesystem;

namespace {
std::string tempPath(const std::string& name) {
  return (fs::path(::testing::TempDir()) / name).string();
}
}  // namespace

TEST(H5io, RoundTripRowMajor) {
  const std::string path = tempPath("rt.h5");
  Eigen::MatrixXd m(2, 3);
  m << 1, 2, 3, 4, 5, 6;
  Eigen::VectorXd v(4);
  v << 0.5, -1, 2, 1e-300;
  {
    fc::AtomicH5Writer w(path);
    w.file().writeMatrix("/stiffness/timoshenko", m);
    w.file().writeVector("/a/b/c", v);
    w.file().writeScalar("/mass/per_length", 0.0455);
    w.file().writeInt("/interfaces/S1/node", 17);
    w.file().writeIntVector("/ints", {3, 1, 4});
    w.file().writeString("/name", "panel2");
    std::vector<double> a3(2 * 3 * 4);
    for (std::size_t i = 0; i < a3.size(); ++i) a3[i] = static_cast<double>(i);
    w.file().writeArray3("/modes/shapes", a3, 2, 3, 4);
    fc::writeProvenance(w.file(), "section/1", "test", "abc");
    w.file().setAttribute("/stiffness", "order", std::string("VABS"));
    w.commit();
  }
  fc::H5File f(path, fc::H5File::Mode::Read);
  EXPECT_EQ(f.checkFormat("section", 1), 1);
  EXPECT_EQ(f.readMatrix("/stiffness/timoshenko"), m);
  EXPECT_EQ(f.readVector("/a/b/c"), v);
  EXPECT_DOUBLE_EQ(f.readScalar("/mass/per_length"), 0.0455);
  EXPECT_EQ(f.readInt("/interfaces/S1/node"), 17);
  EXPECT_EQ(f.readIntVector("/ints"), (std::vector<long>{3, 1, 4}));
  EXPECT_EQ(f.readString("/name"), "panel2");
  EXPECT_EQ(f.shape("/modes/shapes"), (std::vector<hsize_t>{2, 3, 4}));
  // C order: element (1, 2, 3) is at 1*12 + 2*4 + 3 = 23.
  EXPECT_DOUBLE_EQ(f.readArray("/modes/shapes")[23], 23.0);
  EXPECT_EQ(f.stringAttribute("/", "units"), "SI");
  EXPECT_EQ(f.stringAttribute("/stiffness", "order"), "VABS");
  // commit() annotates the datasets the format defines with units and meaning.
  EXPECT_EQ(f.stringAttribute("/mass/per_length", "units"), "kg/m");
  EXPECT_NE(f.stringAttribute("/stiffness/timoshenko", "description").find("VABS order"),
            std::string::npos);
  EXPECT_FALSE(f.hasAttribute("/a/b/c", "units"));  // unknown datasets are left alone
  EXPECT_TRUE(f.exists("/a/b"));
  EXPECT_FALSE(f.exists("/a/x/y"));
  EXPECT_EQ(f.children("/a"), std::vector<std::string>{"b"});
}

TEST(H5io, FormatChecks) {
  const std::string path = tempPath("fmt.h5");
  {
    fc::AtomicH5Writer w(path);
    fc::writeProvenance(w.file(), "flexbody/2", "test", "");
    w.commit();
  }
  fc::H5File f(path, fc::H5File::Mode::Read);
  EXPECT_EQ(f.checkFormat("flexbody", 2), 2);
  try {
    f.checkFormat("flexbody", 1);
    FAIL();
  } catch (const fc::H5Error& e) {
    EXPECT_NE(std::string(e.what()).find("newer"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
  EXPECT_THROW(f.checkFormat("results", 1), fc::H5Error);
}

TEST(H5io, MissingDatasetAndFileErrors) {
  EXPECT_THROW(fc::H5File("/nonexistent/none.h5", fc::H5File::Mode::Read), fc::H5Error);
  const std::string path = tempPath("missing.h5");
  {
    fc::AtomicH5Writer w(path);
    w.commit();
  }
  fc::H5File f(path, fc::H5File::Mode::Read);
  try {
    f.readMatrix("/modes/shapes");
    FAIL();
  } catch (const fc::H5Error& e) {
    EXPECT_NE(std::string(e.what()).find("/modes/shapes"), std::string::npos);
  }
}

TEST(H5io, AbandonedWriteLeavesNothing) {
  const std::string path = tempPath("abandoned.h5");
  std::remove(path.c_str());
  std::string tmp;
  try {
    fc::AtomicH5Writer w(path);
    tmp = w.temporaryPath();
    w.file().writeScalar("/x", 1.0);
    EXPECT_TRUE(fs::exists(tmp));
    throw std::runtime_error("solver failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(tmp));
}

TEST(H5io, KilledWriterNeverLeavesTheFinalName) {
  // A process killed mid-write (no destructors run) may leave its temporary file,
  // but never a half-written file under the final name, and an older complete
  // file stays intact.
  const std::string path = tempPath("killed.h5");
  {
    fc::AtomicH5Writer w(path);
    w.file().writeScalar("/old", 1.0);
    w.commit();
  }
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    fc::AtomicH5Writer w(path);
    w.file().writeScalar("/new", 2.0);
    _exit(0);  // dies without commit, without destructors
  }
  int status = 0;
  waitpid(pid, &status, 0);
  fc::H5File f(path, fc::H5File::Mode::Read);
  EXPECT_TRUE(f.exists("/old"));
  EXPECT_FALSE(f.exists("/new"));
  for (const auto& e : fs::directory_iterator(fs::path(path).parent_path()))
    if (e.path().filename().string().rfind("killed.h5.tmp-", 0) == 0) fs::remove(e.path());
}

#include "common/inspect.h"

TEST(Inspect, DescribesFormatSummaryAndDatasets) {
  const std::string path = tempPath("inspect.h5");
  {
    fc::AtomicH5Writer w(path);
    Eigen::MatrixXd K = Eigen::MatrixXd::Identity(6, 6) * 2.5;
    w.file().writeMatrix("/stiffness/timoshenko", K);
    w.file().writeScalar("/mass/per_length", 0.0455);
    fc::writeProvenance(w.file(), "section/1", "section-prep", "deadbeef");
    w.commit();
  }
  const std::string text = fc::inspectFile(path);
  EXPECT_NE(text.find("format: section/1"), std::string::npos) << text;
  EXPECT_NE(text.find("EA = 2.5"), std::string::npos) << text;
  EXPECT_NE(text.find("timoshenko  (6, 6)"), std::string::npos) << text;
  EXPECT_NE(text.find("per_length  () = 0.0455"), std::string::npos) << text;
  EXPECT_THROW(fc::inspectFile(tempPath("none.h5")), fc::H5Error);
}

#include "common/cli.h"

TEST(Inspect, CommandLineOptionPrintsAndExits) {
  const std::string path = tempPath("inspect_cli.h5");
  {
    fc::AtomicH5Writer w(path);
    w.file().writeVector("/time", Eigen::VectorXd::LinSpaced(11, 0.0, 1.0));
    fc::writeProvenance(w.file(), "results/1", "mbs-run", "");
    w.file().setAttribute("/", "status", std::string("completed"));
    w.commit();
  }
  CLI::App app{"t"};
  std::string input;
  app.add_option("input", input)->required();  // --inspect works without the required input
  fc::addInspectOption(app, "tool", fc::inspectFile);
  const std::string arg0 = "tool", arg1 = "--inspect", arg2 = path;
  const char* argv[] = {arg0.c_str(), arg1.c_str(), arg2.c_str()};
  testing::internal::CaptureStdout();
  EXPECT_THROW(app.parse(3, argv), CLI::Success);
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_NE(out.find("11 outputs, t = 0 .. 1 s, status: completed"), std::string::npos) << out;
  CLI::App app2{"t"};
  fc::addInspectOption(app2, "tool", fc::inspectFile);
  const std::string missing = tempPath("missing_inspect.h5");
  const char* argv2[] = {arg0.c_str(), arg1.c_str(), missing.c_str()};
  testing::internal::CaptureStderr();
  try {
    app2.parse(3, argv2);
    FAIL();
  } catch (const CLI::RuntimeError& e) {
    EXPECT_EQ(e.get_exit_code(), 2);
  }
  EXPECT_NE(testing::internal::GetCapturedStderr().find("tool: error:"), std::string::npos);
}

#include <fstream>
#include <sstream>

#include "common/dataset_docs.h"

TEST(DatasetDocs, PatternsMatchOneSegmentPerStar) {
  ASSERT_NE(fc::findDatasetDoc("results", "/bodies/B3/angular_velocity"), nullptr);
  EXPECT_EQ(fc::findDatasetDoc("results", "/bodies/B3/angular_velocity")->units, "rad/s");
  EXPECT_EQ(fc::findDatasetDoc("results", "/bodies/B3/x/angular_velocity"), nullptr);
  EXPECT_EQ(fc::findDatasetDoc("section", "/bodies/B3/angular_velocity"), nullptr);
}

TEST(DatasetDocs, FileFormatsDocumentListsEveryDataset) {
  // docs/file-formats.md is the users' reference: it must name every dataset
  // the tools annotate, so that it cannot fall behind the code.
  std::ifstream in(std::string(FLEXCOMP_SOURCE_DIR) + "/docs/file-formats.md");
  ASSERT_TRUE(in) << "docs/file-formats.md missing";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  for (const auto& d : fc::datasetDocs())
    EXPECT_NE(text.find("`" + d.pattern + "`"), std::string::npos) << d.pattern;
}
