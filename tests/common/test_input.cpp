// YAML input errors must point at the user's text: file, line, key path.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "common/input.h"

using fc::InputError;
using fc::InputNode;

namespace {
InputError errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError thrown";
  return InputError("", 0, 0, "", "");
}
}  // namespace

TEST(Input, MissingKeyNamesParentLineAndPath) {
  auto root = InputNode::loadString("a: 1\nbody:\n  name: x\n  shell: {length: 2}\n", "b.yaml");
  auto e = errorOf([&] { root["body"]["shell"]["width"]; });
  EXPECT_EQ(e.file(), "b.yaml");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.keyPath(), "body.shell.width");
  EXPECT_NE(std::string(e.what()).find("b.yaml:4:"), std::string::npos) << e.what();
}

TEST(Input, BadNumberReportsItsOwnLine) {
  auto root = InputNode::loadString("x: 1\ny:\n  - 2\n  - abc\n", "n.yaml");
  auto e = errorOf([&] { root["y"].asVector(2); });
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.keyPath(), "y[1]");
  EXPECT_NE(e.message().find("expected a number"), std::string::npos);
}

TEST(Input, WrongVectorLength) {
  auto root = InputNode::loadString("p: [1, 2]\n");
  auto e = errorOf([&] { root["p"].asVector(3); });
  EXPECT_EQ(e.line(), 1);
  EXPECT_NE(e.message().find("3 numbers"), std::string::npos);
}

TEST(Input, PositiveCheck) {
  auto root = InputNode::loadString("m: -3\n");
  auto e = errorOf([&] { root["m"].asPositive(); });
  EXPECT_NE(e.message().find("positive"), std::string::npos);
}

TEST(Input, UnknownKeySuggestsClosest) {
  auto root = InputNode::loadString("sim:\n  t_end: 1\n  rtoll: 1e-6\n", "s.yaml");
  auto e = errorOf([&] { root["sim"].allowKeys({"t_end", "output_step", "rtol"}); });
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.keyPath(), "sim.rtoll");
  EXPECT_NE(e.message().find("did you mean 'rtol'"), std::string::npos) << e.what();
}

TEST(Input, SyntaxErrorCarriesLine) {
  auto e = errorOf([] { InputNode::loadString("a: 1\nb: [1, 2\nc: 3\n", "bad.yaml"); });
  EXPECT_EQ(e.file(), "bad.yaml");
  EXPECT_GE(e.line(), 2);
  EXPECT_NE(e.message().find("invalid YAML"), std::string::npos);
}

TEST(Input, MissingFileIsAnInputError) {
  auto e = errorOf([] { InputNode::loadFile("/nonexistent/x.yaml"); });
  EXPECT_EQ(e.file(), "/nonexistent/x.yaml");
}

TEST(Input, IncludeMergesAndInlineWins) {
  const std::string dir = ::testing::TempDir();
  {
    std::ofstream f(dir + "/mats.yaml");
    f << "materials:\n  a: {type: isotropic, E: 1, nu: 0.3, rho: 1}\n  b: {type: isotropic, E: 2, "
         "nu: 0.3, rho: 1}\n";
  }
  auto root = InputNode::loadString(
      "materials:\n  include: mats.yaml\n  b: {type: isotropic, E: 3, nu: 0.3, rho: 1}\n",
      dir + "/main.yaml");
  auto entries = fc::namedEntries(root["materials"]);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].first, "a");
  EXPECT_EQ(entries[1].first, "b");
  EXPECT_DOUBLE_EQ(entries[1].second["E"].asDouble(), 3.0);
  // Errors inside the included file point at that file.
  EXPECT_EQ(entries[0].second.file(), dir + "/mats.yaml");
  EXPECT_EQ(entries[0].second.line(), 2);
}

TEST(Input, ClosestMatch) {
  EXPECT_EQ(fc::closestMatch("orthotropc", {"isotropic", "orthotropic"}), "orthotropic");
  EXPECT_EQ(fc::closestMatch("zzz", {"isotropic", "orthotropic"}), "");
}
