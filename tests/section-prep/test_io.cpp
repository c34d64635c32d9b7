// The edges of section-prep: the HDF5 file of the contract, located errors for
// bad YAML and bad VABS files, and the shipped SAR antenna examples.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "common/h5io.h"
#include "common/input.h"
#include "section-prep/cross_section.h"
#include "section-prep/section_mesher.h"
#include "section-prep/section_output.h"
#include "section-prep/section_spec.h"
#include "section-prep/vabs_reader.h"

namespace fc::section {
namespace {

const std::string kMaterials =
    "materials:\n"
    "  cfrp_iso: {type: isotropic, E: 159.0e9, nu: 0.38, rho: 1610}\n";

TEST(Output, WritesTheContractLayout) {
  const auto spec = readSectionSpec(InputNode::loadString(
      kMaterials + "section: {shape: solid_circle, diameter: 0.006, material: cfrp_iso}\n"));
  const SectionProperties p = analyzeSection(meshSection(spec));
  const std::string path =
      (std::filesystem::temp_directory_path() / "section_prep_test_output.h5").string();
  writeSectionFile(path, p, "abc123", "test");
  H5File f(path, H5File::Mode::Read);
  EXPECT_EQ(f.checkFormat("section", 1), 1);
  EXPECT_EQ(f.stringAttribute("/", "units"), "SI");
  EXPECT_EQ(f.stringAttribute("/", "inputs_sha256"), "abc123");
  const Eigen::MatrixXd K = f.readMatrix("/stiffness/timoshenko");
  ASSERT_EQ(K.rows(), 6);
  ASSERT_EQ(K.cols(), 6);
  EXPECT_EQ(K(3, 3), p.timoshenko(3, 3));
  EXPECT_EQ(f.readMatrix("/stiffness/classical").rows(), 4);
  EXPECT_EQ(f.readMatrix("/mass/matrix")(0, 0), p.mass_per_length);
  EXPECT_EQ(f.readScalar("/mass/per_length"), p.mass_per_length);
  for (const char* c : {"/centers/mass", "/centers/tension", "/centers/shear"})
    EXPECT_EQ(f.readVector(c).size(), 2) << c;
  f.close();
  std::filesystem::remove(path);
}

// Runs `body`, expects an fc::InputError, returns its message.
template <typename F>
std::string inputError(F body) {
  try {
    body();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(YamlErrors, NameTheFileLineAndKey) {
  const std::string unknown_shape = inputError([] {
    readSectionSpec(InputNode::loadString(kMaterials + "section:\n  shape: hexagon\n", "s.yaml"));
  });
  EXPECT_NE(unknown_shape.find("s.yaml:4"), std::string::npos) << unknown_shape;
  EXPECT_NE(unknown_shape.find("section.shape"), std::string::npos) << unknown_shape;
  EXPECT_NE(unknown_shape.find("solid_circle"), std::string::npos) << unknown_shape;

  const std::string typo = inputError([] {
    readSectionSpec(InputNode::loadString(
        kMaterials + "section: {shape: solid_circle, diameter: 0.006, material: cfrp_isq}\n", "s.yaml"));
  });
  EXPECT_NE(typo.find("cfrp_iso"), std::string::npos) << typo;  // did-you-mean

  const std::string negative = inputError([] {
    readSectionSpec(InputNode::loadString(
        kMaterials + "section: {shape: solid_circle, diameter: -1, material: cfrp_iso}\n", "s.yaml"));
  });
  EXPECT_NE(negative.find("diameter"), std::string::npos) << negative;

  const std::string thick = inputError([] {
    readSectionSpec(InputNode::loadString(
        kMaterials + "section:\n  shape: tube\n  outer_diameter: 0.01\n"
                     "  wall: {material: cfrp_iso, thickness: 0.006}\n", "s.yaml"));
  });
  EXPECT_NE(thick.find("section.wall"), std::string::npos) << thick;

  const std::string short_stack = inputError([] {
    readSectionSpec(InputNode::loadString(
        kMaterials + "section:\n  shape: rectangle\n  width: 0.02\n  height: 0.01\n"
                     "  plies: [{material: cfrp_iso, thickness: 0.004}]\n", "s.yaml"));
  });
  EXPECT_NE(short_stack.find("s.yaml:7"), std::string::npos) << short_stack;
  EXPECT_NE(short_stack.find("section.plies"), std::string::npos) << short_stack;
}

const char* kVabsHeader =
    "1 1\n1 0 0\n0 0 0 0\n"
    "4 1 1\n"
    "1 0 0\n2 1 0\n3 1 1\n4 0 1\n";

TEST(VabsErrors, NameTheFileLineAndItem) {
  const std::string undefined_node = inputError([] {
    parseVabs(std::string(kVabsHeader) + "1 1 2 3 7 0 0 0 0 0\n1 1 0\n1 1 0\n1 0\n1e9 0.3\n1\n", "c.sg");
  });
  EXPECT_NE(undefined_node.find("c.sg:9"), std::string::npos) << undefined_node;
  EXPECT_NE(undefined_node.find("node 7"), std::string::npos) << undefined_node;

  const std::string truncated = inputError([] {
    parseVabs(std::string(kVabsHeader) + "1 1 2 3 4 0 0 0 0 0\n1 1 0\n1 1 0\n1 0\n1e9\n", "c.sg");
  });
  EXPECT_NE(truncated.find("ends early"), std::string::npos) << truncated;

  const std::string bad_number = inputError([] {
    parseVabs(std::string(kVabsHeader) + "1 1 2 3 4 0 0 0 0 0\n1 1 0\n1 1 0\n1 0\n1e9 abc\n1\n", "c.sg");
  });
  EXPECT_NE(bad_number.find("c.sg:13"), std::string::npos) << bad_number;
  EXPECT_NE(bad_number.find("'abc'"), std::string::npos) << bad_number;
}

TEST(VabsReader, FortranExponentsAndOneSquare) {
  // A unit square of one 4-node element: EA = E, GJ = 0.1406 G (series).
  const VabsModel m = parseVabs(
      std::string(kVabsHeader) + "1 1 2 3 4 0 0 0 0 0\n1 1 0\n1 1 0\n1 0\n1.0d9 0.0\n2.0D0\n", "c.sg");
  const SectionProperties p = analyzeSection(m.mesh);
  EXPECT_DOUBLE_EQ(p.classical(0, 0), 1e9);
  EXPECT_DOUBLE_EQ(p.mass_per_length, 2.0);
}

TEST(VabsErrors, DisconnectedSectionIsRefused) {
  // Two separate unit squares: the warping problem has eight rigid modes, and
  // silently pinning four would give a wrong answer, so it must stop.
  const std::string text =
      "1 1\n1 0 0\n0 0 0 0\n8 2 1\n"
      "1 0 0\n2 1 0\n3 1 1\n4 0 1\n5 3 0\n6 4 0\n7 4 1\n8 3 1\n"
      "1 1 2 3 4 0 0 0 0 0\n2 5 6 7 8 0 0 0 0 0\n1 1 0\n2 1 0\n1 1 0\n1 0\n1e9 0.3\n1\n";
  const VabsModel m = parseVabs(text, "two.sg");
  try {
    analyzeSection(m.mesh);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not one connected body"), std::string::npos) << e.what();
  }
}

TEST(Examples, SarAntennaSectionsLoadAndSolve) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(FLEXCOMP_SOURCE_DIR) / "examples/sar-antenna/sections";
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    const auto spec = readSectionSpec(InputNode::loadFile(entry.path().string()));
    const SectionProperties p = analyzeSection(meshSection(spec));
    EXPECT_EQ(p.timoshenko.llt().info(), Eigen::Success) << entry.path();  // positive definite
    EXPECT_GT(p.mass_per_length, 0) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 4);
}

}  // namespace
}  // namespace fc::section
