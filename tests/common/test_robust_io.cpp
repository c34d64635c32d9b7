// Robust output: termination signals, write failures (a full disk), planted links,
// output paths that are inputs, non-finite numbers. Each fault is real: signals
// are raised in a forked child, write failures come from RLIMIT_FSIZE (the kernel
// refuses the write with EFBIG, exactly as a full disk refuses it with ENOSPC).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/files.h"
#include "common/h5io.h"
#include "common/input.h"
#include "common/termination.h"

namespace fs = std::filesystem;

namespace {

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("robust-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<std::string> listDir(const fs::path& d) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(d)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// Runs body in a child process; returns its wait status.
template <class F>
int inChild(F body) {
  fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    body();
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

// Runs write() in a child whose files may not exceed `limit` bytes (SIGXFSZ
// ignored, so the write fails with EFBIG): its wait status, exit 7 when an
// exception E names the OS reason "File too large", 8 when E says something
// else, 9 when nothing was thrown.
template <class E, class F>
int writeBeyondFileSizeLimit(rlim_t limit, F write) {
  return inChild([&] {
    ::signal(SIGXFSZ, SIG_IGN);
    struct rlimit lim {limit, limit};
    setrlimit(RLIMIT_FSIZE, &lim);
    try {
      write();
    } catch (const E& e) {
      _exit(std::string(e.what()).find("File too large") != std::string::npos ? 7 : 8);
    }
    _exit(9);
  });
}

void writeGood(const std::string& path, double value) {
  fc::AtomicH5Writer w(path);
  w.file().writeScalar("/value", value);
  w.commit();
}

}  // namespace

// --- termination signals --------------------------------------------------------

TEST(Termination, EverySignalRemovesRegisteredTemporariesAndExits128PlusSignal) {
  int n = 0;
  const int* sigs = fc::terminationSignals(&n);
  ASSERT_EQ(n, 7);  // INT, TERM, HUP, QUIT, ALRM, XCPU, PIPE
  for (int i = 0; i < n; ++i) {
    const int sig = sigs[i];
    const fs::path d = freshDir("sig" + std::to_string(sig));
    const std::string out = (d / "out.h5").string();
    const int status = inChild([&] {
      fc::installTerminationHandlers("test", fc::TerminationPolicy::ExitNow);
      fc::AtomicH5Writer w(out);  // registers its temporary
      w.file().writeScalar("/x", 1.0);
      ::raise(sig);
      _exit(0);  // not reached: the handler exits
    });
    ASSERT_TRUE(WIFEXITED(status)) << fc::signalName(sig);
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig) << fc::signalName(sig);
    EXPECT_TRUE(listDir(d).empty()) << fc::signalName(sig) << " left " << listDir(d).size()
                                    << " file(s)";
  }
}

TEST(Termination, RecordPolicyRecordsFirstSignalAndExitsOnSecond) {
  const fs::path d = freshDir("record");
  const std::string out = (d / "res.h5").string();
  const int status = inChild([&] {
    fc::installTerminationHandlers("test", fc::TerminationPolicy::Record);
    fc::AtomicH5Writer w(out);
    ::raise(SIGHUP);
    // The loop polls: the first signal is only recorded.
    if (fc::terminationSignal() != SIGHUP) _exit(3);
    try {
      fc::throwIfTerminated();
      _exit(4);
    } catch (const fc::Terminated& e) {
      if (e.signal() != SIGHUP || std::string(e.what()) != "interrupted by SIGHUP") _exit(5);
    }
    ::raise(SIGTERM);  // a second one stops at once
    _exit(6);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_TRUE(listDir(d).empty());
}

// timeout(1) sends SIGTERM to the child and then to its process group: one
// request, delivered twice. Under the Record policy the repeat within 1 s must
// not turn into "stop at once" (mbs-run would lose its results file); the same
// signal later, or a different one, still does.
TEST(Termination, RecordPolicyTakesAnImmediateRepeatOfTheSameSignalAsOneRequest) {
  const fs::path d = freshDir("record_twice");
  const std::string out = (d / "res.h5").string();
  const int status = inChild([&] {
    fc::installTerminationHandlers("test", fc::TerminationPolicy::Record);
    fc::AtomicH5Writer w(out);
    ::raise(SIGTERM);
    ::raise(SIGTERM);  // the group's copy
    if (fc::terminationSignal() != SIGTERM) _exit(3);
    ::usleep(1100000);  // past the 1 s window: a second request
    ::raise(SIGTERM);
    _exit(6);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << "6: the later SIGTERM was ignored; 3: none recorded";
  EXPECT_TRUE(listDir(d).empty());
}

TEST(Termination, RegistrationIsReleasedAfterCommit) {
  const fs::path d = freshDir("release");
  const std::string out = (d / "kept.h5").string();
  const int status = inChild([&] {
    fc::installTerminationHandlers("test", fc::TerminationPolicy::ExitNow);
    writeGood(out, 1.0);  // committed: no longer a temporary
    ::raise(SIGTERM);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_EQ(listDir(d), std::vector<std::string>{"kept.h5"});
}

// --- write failures -------------------------------------------------------------

TEST(AtomicWrite, FailedHdf5WriteKeepsPreviousFileAndRemovesTemporary) {
  const fs::path d = freshDir("efbig-h5");
  const std::string out = (d / "body.h5").string();
  writeGood(out, 42.0);
  const std::string before = fc::readTextFile(out);
  // The OS reason reaches the message.
  const int status = writeBeyondFileSizeLimit<fc::H5Error>(64 * 1024, [&] {
    fc::AtomicH5Writer w(out);
    w.file().writeMatrix("/big", Eigen::MatrixXd::Ones(200, 200));  // 320 kB
    w.commit();
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
  EXPECT_EQ(listDir(d), std::vector<std::string>{"body.h5"});
  EXPECT_EQ(fc::readTextFile(out), before);
  fc::H5File f(out, fc::H5File::Mode::Read);
  EXPECT_EQ(f.readScalar("/value"), 42.0);
}

TEST(AtomicWrite, FailedTextWriteKeepsPreviousFileAndRemovesTemporary) {
  const fs::path d = freshDir("efbig-txt");
  const std::string out = (d / "a.txt").string();
  fc::writeFileAtomic(out, "previous");
  const int status =
      writeBeyondFileSizeLimit<std::runtime_error>(1024, [&] { fc::writeFileAtomic(out, std::string(100000, 'x')); });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
  EXPECT_EQ(listDir(d), std::vector<std::string>{"a.txt"});
  EXPECT_EQ(fc::readTextFile(out), "previous");
}

// The two-step write fe-prep uses for its .xdmf beside the .h5: staged
// content reaches the file only on commit(); dropped, it leaves the previous
// file and no temporary; a failed staging leaves the previous file too.
TEST(AtomicWrite, StagedFileChangesThePathOnlyOnCommit) {
  const fs::path d = freshDir("staged");
  const std::string out = (d / "a.xdmf").string();
  fc::writeFileAtomic(out, "previous");
  {
    fc::StagedFile dropped(out, "new view");
    EXPECT_EQ(listDir(d).size(), 2u);  // the file and its temporary
    EXPECT_EQ(fc::readTextFile(out), "previous");
  }
  EXPECT_EQ(listDir(d), std::vector<std::string>{"a.xdmf"});
  EXPECT_EQ(fc::readTextFile(out), "previous");
  fc::StagedFile kept(out, "new view");
  kept.commit();
  EXPECT_EQ(listDir(d), std::vector<std::string>{"a.xdmf"});
  EXPECT_EQ(fc::readTextFile(out), "new view");
  const int status =
      writeBeyondFileSizeLimit<std::runtime_error>(1024, [&] { fc::StagedFile big(out, std::string(100000, 'x')); });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
  EXPECT_EQ(listDir(d), std::vector<std::string>{"a.xdmf"});
  EXPECT_EQ(fc::readTextFile(out), "new view");
}

TEST(AtomicWrite, TemporaryNamesAreUnpredictableAndNeverFollowALink) {
  const std::string a = fc::temporaryNameFor("x.h5"), b = fc::temporaryNameFor("x.h5");
  EXPECT_NE(a, b);
  EXPECT_EQ(a.size(), std::string("x.h5.tmp-").size() + 12);
  // Exclusive creation refuses a planted link and leaves its target alone.
  const fs::path d = freshDir("link");
  { std::ofstream(d / "victim") << "precious"; }
  fs::create_symlink(d / "victim", d / "planted.h5");
  EXPECT_THROW(fc::H5File((d / "planted.h5").string(), fc::H5File::Mode::CreateExclusive),
               fc::H5Error);
  EXPECT_EQ(fc::readTextFile((d / "victim").string()), "precious");
}

TEST(AtomicWrite, NonFiniteNumbersAreRefusedBeforeTheRename) {
  const fs::path d = freshDir("nan");
  const std::string out = (d / "s.h5").string();
  writeGood(out, 1.0);
  for (double bad : {std::nan(""), double(INFINITY), -double(INFINITY)}) {
    fc::AtomicH5Writer w(out);
    Eigen::MatrixXd m = Eigen::MatrixXd::Ones(3, 4);
    m(2, 1) = bad;
    w.file().writeMatrix("/stiffness/timoshenko", m);
    try {
      w.commit();
      ADD_FAILURE() << "non-finite value accepted";
    } catch (const fc::H5Error& e) {
      EXPECT_NE(std::string(e.what()).find("/stiffness/timoshenko"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("flat index 9"), std::string::npos) << e.what();
    }
  }
  {
    fc::AtomicH5Writer w(out);
    w.file().writeScalar("/ok", 1.0);
    w.file().setAttribute("/", "energy", std::nan(""));
    EXPECT_THROW(w.commit(), fc::H5Error);
  }
  EXPECT_EQ(listDir(d), std::vector<std::string>{"s.h5"});
  fc::H5File f(out, fc::H5File::Mode::Read);
  EXPECT_EQ(f.readScalar("/value"), 1.0);
}

// --- output path checks ---------------------------------------------------------

TEST(OutputPath, AnOutputThatIsAnInputIsRefused) {
  const fs::path d = freshDir("same");
  const std::string in = (d / "in.yaml").string();
  { std::ofstream(in) << "a: 1\n"; }
  EXPECT_THROW(fc::checkOutputIsNotAnInput(in, {in}), fc::InputError);
  // Another spelling, a symbolic link and a hard link all name the same file.
  EXPECT_THROW(fc::checkOutputIsNotAnInput((d / "." / "in.yaml").string(), {in}), fc::InputError);
  fs::create_symlink(in, d / "link.h5");
  EXPECT_THROW(fc::checkOutputIsNotAnInput((d / "link.h5").string(), {in}), fc::InputError);
  fs::create_hard_link(in, d / "hard.h5");
  EXPECT_THROW(fc::checkOutputIsNotAnInput((d / "hard.h5").string(), {in}), fc::InputError);
  EXPECT_NO_THROW(fc::checkOutputIsNotAnInput((d / "new.h5").string(), {in}));
  try {
    fc::checkOutputIsNotAnInput(in, {"missing.yaml", in});
  } catch (const fc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("would destroy that input"), std::string::npos);
  }
  EXPECT_EQ(fc::readTextFile(in), "a: 1\n");
}

TEST(OutputPath, FilesReadAreRecordedAsInputs) {
  const fs::path d = freshDir("recorded");
  const std::string in = (d / "m.yaml").string();
  { std::ofstream(in) << "a: 1\n"; }
  fc::InputNode::loadFile(in);
  const auto all = fc::inputFilesRead();
  EXPECT_NE(std::find(all.begin(), all.end(), in), all.end());
}

TEST(OutputPath, UnwritableLocationsAreReportedBeforeComputing) {
  const fs::path d = freshDir("unwritable");
  try {
    fc::checkOutputWritable((d / "no" / "such" / "x.h5").string());
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos) << e.what();
  }
  EXPECT_THROW(fc::checkOutputWritable(d.string()), std::runtime_error);  // a directory
  EXPECT_NO_THROW(fc::checkOutputWritable((d / "ok.h5").string()));
  EXPECT_TRUE(listDir(d).empty());  // the probe is removed
}

// --- HDF5 readers trust nothing -----------------------------------------------------

namespace {
// A variable-length UTF-8 string attribute, exactly as h5py writes `f.attrs[k] = "..."`.
void writeVlenAttribute(hid_t obj, const char* name, const char* value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, type, &value);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}
}  // namespace

TEST(H5Readers, VariableLengthUtf8StringsAsH5pyWritesThem) {
  const fs::path d = freshDir("vlen");
  const std::string path = (d / "py.h5").string();
  {
    const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    writeVlenAttribute(f, "format", "section/1");
    writeVlenAttribute(f, "note", "\u00e9t\u00e9 UTF-8");
    // A vlen string dataset too (h5py: f["name"] = "beam").
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t ds = H5Dcreate2(f, "name", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const char* v = "beam";
    H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v);
    H5Dclose(ds);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(f);
  }
  fc::H5File f(path, fc::H5File::Mode::Read);
  EXPECT_EQ(f.stringAttribute("/", "format"), "section/1");
  EXPECT_EQ(f.stringAttribute("/", "note"), "\u00e9t\u00e9 UTF-8");
  EXPECT_EQ(f.checkFormat("section", 1), 1);
  EXPECT_EQ(f.readString("/name"), "beam");
}

TEST(H5Readers, ShapesAndTypesAreCheckedBeforeReading) {
  const fs::path d = freshDir("shapes");
  const std::string path = (d / "bad.h5").string();
  {
    fc::AtomicH5Writer w(path);
    w.file().writeMatrix("/stiffness/timoshenko", Eigen::MatrixXd::Ones(5, 6));
    w.file().writeString("/mesh/nodes", "not a number");
    w.commit();
  }
  fc::H5File f(path, fc::H5File::Mode::Read);
  try {
    f.readMatrix("/stiffness/timoshenko", 6, 6);
    ADD_FAILURE();
  } catch (const fc::H5Error& e) {
    EXPECT_NE(std::string(e.what()).find("must be a 6 x 6 matrix, got 5 x 6"), std::string::npos) << e.what();
  }
  try {
    f.readMatrix("/mesh/nodes");
    ADD_FAILURE();
  } catch (const fc::H5Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds text, expected numbers"), std::string::npos) << e.what();
  }
  EXPECT_THROW(f.readString("/stiffness/timoshenko"), fc::H5Error);
  EXPECT_THROW(f.stringAttribute("/", "missing"), fc::H5Error);
}

#include "common/inspect.h"

TEST(H5Readers, InspectSurvivesStringsWhereNumbersBelong) {
  const fs::path d = freshDir("inspect");
  const std::string path = (d / "body.h5").string();
  {
    fc::AtomicH5Writer w(path);
    fc::writeProvenance(w.file(), "flexbody/1", "test", "x");
    w.file().writeString("/mesh/nodes", "not a number");
    w.file().writeString("/modes/frequencies_hz", "x");
    w.commit();
  }
  const std::string out = fc::inspectFile(path);
  EXPECT_NE(out.find("nodes  () = \"not a number\""), std::string::npos) << out;
  const std::string sec = (d / "sec.h5").string();
  {
    fc::AtomicH5Writer w(sec);
    fc::writeProvenance(w.file(), "section/1", "test", "x");
    w.file().writeMatrix("/stiffness/timoshenko", Eigen::MatrixXd::Ones(5, 6));
    w.commit();
  }
  EXPECT_NE(fc::inspectFile(sec).find("summary: not available"), std::string::npos);
}

namespace {

// A file whose groups link back into themselves, made with the HDF5 C API as a
// damaged or hostile input could be: /a/loop -> / and /a/b/up -> /a (hard links),
// /a/b/soft_loop -> /a and /s -> /a/b (soft links), a dangling soft link and an
// external link to a file that does not exist.
void writeCyclicFile(const std::string& path) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  {
    fc::H5File file = fc::H5File::adopt(f, path);
    fc::writeProvenance(file, "flexbody/1", "test", "x");
    file.writeScalar("/a/b/x", 2.5);
    file.writeScalar("/inertia/mass", 1.0);
    ASSERT_GE(H5Lcreate_hard(f, "/", f, "/a/loop", H5P_DEFAULT, H5P_DEFAULT), 0);
    ASSERT_GE(H5Lcreate_hard(f, "/a", f, "/a/b/up", H5P_DEFAULT, H5P_DEFAULT), 0);
    ASSERT_GE(H5Lcreate_soft("/a", f, "/a/b/soft_loop", H5P_DEFAULT, H5P_DEFAULT), 0);
    ASSERT_GE(H5Lcreate_soft("/a/b", f, "/s", H5P_DEFAULT, H5P_DEFAULT), 0);
    ASSERT_GE(H5Lcreate_soft("/nowhere", f, "/dangling", H5P_DEFAULT, H5P_DEFAULT), 0);
    ASSERT_GE(H5Lcreate_external("absent.h5", "/", f, "/ext", H5P_DEFAULT, H5P_DEFAULT), 0);
    file.closeChecked();
  }
}

// Runs body in a child that SIGALRM kills after `seconds`: a hang fails the test
// instead of hanging the suite. True when the child exited 0.
template <class F>
bool endsWithin(unsigned seconds, F body) {
  const int status = inChild([&] {
    alarm(seconds);
    body();
  });
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

// The listing used to recurse forever on /a/loop -> / (and was cut at 16 levels, after
// which annotateDatasets still hung): every tree walk now enters each group once.
TEST(H5Readers, TreeWalksEndOnLinkCycles) {
  const fs::path d = freshDir("cycles");
  const std::string path = (d / "cyclic.h5").string(), listing = (d / "listing.txt").string();
  writeCyclicFile(path);
  ASSERT_TRUE(endsWithin(20, [&] {
    std::ofstream(listing) << fc::inspectFile(path);
  })) << "inspectFile did not end on a file with link cycles";
  const std::string out = readAll(listing);
  const auto count = [&](const std::string& s) {
    std::size_t n = 0;
    for (auto p = out.find(s); p != std::string::npos; p = out.find(s, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("x  () = 2.5"), 1u) << out;  // listed once, not again through /s or the loops
  EXPECT_NE(out.find("loop/  (a group met above, through another link: not entered again)"), std::string::npos) << out;
  EXPECT_NE(out.find("up/  (a group met above"), std::string::npos) << out;
  EXPECT_NE(out.find("soft_loop/ -> /a  (a group met above"), std::string::npos) << out;
  EXPECT_NE(out.find("s/ -> /a/b  (a group met above"), std::string::npos) << out;
  EXPECT_NE(out.find("dangling -> /nowhere  (link to nothing)"), std::string::npos) << out;
  EXPECT_NE(out.find("ext -> absent.h5:/  (external link: not followed)"), std::string::npos) << out;
  EXPECT_EQ(out.find("nested deeper"), std::string::npos) << out;

  // The writer's commit walks the tree too (annotateDatasets, checkAllFinite).
  const std::string written = (d / "written.h5").string();
  ASSERT_TRUE(endsWithin(20, [&] {
    fc::AtomicH5Writer w(written);
    fc::writeProvenance(w.file(), "flexbody/1", "test", "x");
    w.file().writeScalar("/inertia/mass", 3.0);
    const hid_t id = w.file().id();
    if (H5Lcreate_hard(id, "/", id, "/inertia/loop", H5P_DEFAULT, H5P_DEFAULT) < 0) _exit(3);
    w.commit();
  })) << "AtomicH5Writer::commit did not end on a file with a link cycle";
  fc::H5File f(written, fc::H5File::Mode::Read);
  EXPECT_EQ(f.stringAttribute("/inertia/mass", "units"), "kg");
  EXPECT_EQ(f.readScalar("/inertia/loop/inertia/mass"), 3.0);
}

// A joint named with 5000 characters is a valid HDF5 link name; the writer's commit
// walks the file and used to refuse names over 4096 characters as "unreadable"
// (fuzz campaign, other seeds: an error naming the temporary, not the input).
TEST(H5Readers, LongLinkNamesAreListed) {
  const fs::path d = freshDir("longnames");
  const std::string path = (d / "results.h5").string(), name(5000, 'x');
  {
    fc::AtomicH5Writer w(path);
    fc::writeProvenance(w.file(), "results/1", "test", "x");
    w.file().writeVector("/joints/" + name + "/angle", Eigen::VectorXd::Ones(2));
    w.commit();
  }
  fc::H5File f(path, fc::H5File::Mode::Read);
  EXPECT_EQ(f.children("/joints"), std::vector<std::string>{name});
  EXPECT_EQ(f.stringAttribute("/joints/" + name + "/angle", "units"), "rad");
  EXPECT_NE(fc::inspectFile(path).find(name + "/"), std::string::npos);
}

// A chunked dataset declaring 2^36 numbers and storing none (fuzz campaign, other
// seeds: mbs-run ran out of memory reading a body file's /inertia/mass, an error
// naming neither file nor dataset). Refused as an H5Error naming both.
TEST(H5Readers, HugeDeclaredShapesAreRefusedBeforeAllocating) {
  const fs::path d = freshDir("huge");
  const std::string path = (d / "body.h5").string();
  {
    const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    const hsize_t dims[1] = {hsize_t(1) << 36}, chunk[1] = {1024};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, chunk);
    const hid_t ds = H5Dcreate2(f, "/mass", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    ASSERT_GE(ds, 0);
    H5Dclose(ds);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
  }
  fc::H5File f(path, fc::H5File::Mode::Read);
  try {
    f.readVector("/mass");
    ADD_FAILURE() << "no error";
  } catch (const fc::H5Error& e) {
    EXPECT_NE(std::string(e.what()).find("body.h5: dataset /mass declares 68719476736 numbers"), std::string::npos) << e.what();
  }
  EXPECT_NE(fc::inspectFile(path).find("mass  (68719476736)"), std::string::npos);
}
