// The .msh structure check run before gmsh reads a mesh file (common/geo_script.h),
// with the defects the format fuzzer found (tests/fuzz/formatfuzz.py,
// docs/robustness.md "Format fuzzing"), and the out-of-memory message's stages
// (common/memory.h).
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "common/geo_script.h"
#include "common/input.h"
#include "common/memory.h"

namespace {

// Two triangles on four nodes and a line: MSH 2.2 and 4.1 as gmsh writes them.
const char* kMsh22 =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"root\"\n2 2 \"skin\"\n$EndPhysicalNames\n"
    "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n"
    "$Elements\n3\n1 1 2 1 1 1 4\n2 2 2 2 1 1 2 3\n3 2 2 2 1 1 3 4\n$EndElements\n";
const char* kMsh41 =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"root\"\n2 2 \"skin\"\n$EndPhysicalNames\n"
    "$Entities\n0 1 1 0\n1 0 0 0 0 1 0 1 1 0\n1 0 0 0 1 1 0 1 2 0\n$EndEntities\n"
    "$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n"
    "$Elements\n2 3 1 3\n1 1 1 1\n1 1 4\n2 1 2 2\n2 1 2 3\n3 1 3 4\n$EndElements\n";

std::string writeMsh(const std::string& name, const std::string& text) {
  static std::string dir;
  if (dir.empty()) {
    char tmpl[] = "/tmp/flexcomp_msh_XXXXXX";
    dir = mkdtemp(tmpl);
  }
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The message of the InputError the check throws, "" if none.
std::string checkError(const std::string& name, const std::string& text) {
  try {
    fc::checkMshStructure(writeMsh(name, text));
  } catch (const fc::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MshCheck, GmshFilesPass) {
  EXPECT_EQ(checkError("a22.msh", kMsh22), "");
  EXPECT_EQ(checkError("a41.msh", kMsh41), "");
  // CRLF line ends and blank lines are what other writers produce: accepted.
  std::string crlf;
  for (const char* p = kMsh41; *p; ++p) crlf += *p == '\n' ? std::string("\r\n") : std::string(1, *p);
  EXPECT_EQ(checkError("crlf.msh", crlf), "");
}

// Found by the format fuzzer (seed 2811): gmsh 4.8 read an element line given
// twice in MSH 2.2 by its count and dropped the last element without a word.
TEST(MshCheck, AnElementGivenTwiceIsLocated) {
  const std::string e = checkError("dup22.msh", replaced(kMsh22, "2 2 2 2 1 1 2 3\n", "2 2 2 2 1 1 2 3\n2 2 2 2 1 1 2 3\n"));
  EXPECT_NE(e.find("dup22.msh:20"), std::string::npos) << e;
  EXPECT_NE(e.find("element 2 given twice"), std::string::npos) << e;
  const std::string f = checkError("dup41.msh", replaced(kMsh41, "2 1 2 3\n", "2 1 2 3\n2 1 2 3\n"));
  EXPECT_NE(f.find("element 2 given twice"), std::string::npos) << f;
}

// Found by the format fuzzer (seed 2811): a MSH 4.1 file without its $Nodes
// header line crashed gmsh ("double free or corruption") and hung fe-prep.
TEST(MshCheck, AMissingNodesHeaderIsLocated) {
  const std::string e = checkError("nohead.msh", replaced(kMsh41, "$Nodes\n1 4 1 4\n", "$Nodes\n"));
  EXPECT_NE(e.find("nohead.msh:16"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a node block header"), std::string::npos) << e;
}

TEST(MshCheck, CountsNodesAndNumbersAreChecked) {
  struct Case {
    const char* name;
    std::string text;
    const char* want;
  };
  const Case cases[] = {
      {"count.msh", replaced(kMsh22, "$Nodes\n4\n", "$Nodes\n5\n"), "$Nodes declares 5 nodes, the section holds 4"},
      {"badnode.msh", replaced(kMsh22, "3 2 2 2 1 1 3 4", "3 2 2 2 1 1 3 9"), "names node 9, which $Nodes does not define"},
      {"nan.msh", replaced(kMsh22, "3 1 1 0", "3 nan 1 0"), "got 'nan'"},
      {"short.msh", replaced(kMsh41, "2 1 2 3\n", "2 1 2\n"), "needs 3 nodes, the line gives 2"},
      {"trunc.msh", std::string(kMsh41).substr(0, std::string(kMsh41).size() - 14), "the file ends early"},
      {"version.msh", replaced(kMsh22, "2.2 0 8", "3.0 0 8"), "version 3.0"},
      {"noend.msh", replaced(kMsh22, "$EndPhysicalNames\n", ""), "$PhysicalNames section"},
      {"blocks.msh", replaced(kMsh41, "$Elements\n2 3 1 3", "$Elements\n2 4 1 3"), "declares 4 elements, its blocks hold 3"},
  };
  for (const Case& c : cases) {
    const std::string e = checkError(c.name, c.text);
    EXPECT_NE(e.find(c.name), std::string::npos) << c.name << ": " << e;
    EXPECT_NE(e.find(c.want), std::string::npos) << c.name << ": " << e;
  }
}

// The out-of-memory message names the stages an exception left, after they are gone.
TEST(OutOfMemory, MessageNamesTheStageLeft) {
  std::string msg;
  try {
    fc::StageScope outer("building the body");
    {
      fc::StageScope done("meshing");
      done.end();  // a finished stage is not the one that failed
    }
    fc::StageScope inner("eigen-solve");
    throw fc::OutOfMemory("the factorisation of K needs about 2.0 GB");
  } catch (const std::bad_alloc& e) {
    msg = fc::outOfMemoryMessage(e, "fe-prep");
  }
  EXPECT_EQ(msg.rfind("out of memory in stage 'building the body / eigen-solve': the factorisation of K needs about 2.0 GB", 0), 0u)
      << msg;
  EXPECT_NE(msg.find("MemAvailable"), std::string::npos) << msg;
  // A new stage in normal flow: the failure was handled; the tool's own bar is left out.
  fc::StageScope next("fe-prep");
  fc::StageScope run("writing out.h5");
  EXPECT_EQ(fc::failedStage("fe-prep"), "writing out.h5");
}

TEST(OutOfMemory, TheFailedOperatorNewSizeIsKept) {
  std::string msg;
  try {
    fc::StageScope s("assembly");
    // More than any address space: operator new fails at once, without touching memory.
    volatile std::size_t n = static_cast<std::size_t>(1) << 61;
    void* p = ::operator new(n);
    ::operator delete(p);
  } catch (const std::bad_alloc& e) {
    msg = fc::outOfMemoryMessage(e);
  }
  EXPECT_EQ(fc::lastFailedAllocation(), static_cast<std::size_t>(1) << 61) << msg;
  EXPECT_NE(msg.find("in stage 'assembly': an allocation of"), std::string::npos) << msg;
}
