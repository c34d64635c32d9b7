// shape: mesh — a gmsh .geo whose physical surfaces name MATERIAL/PLY/WALL —
// against the same section built as shape: rectangle with plies.
#include <gtest/gtest.h>

#include <gmsh.h>

#include <cmath>
#include <filesystem>

#include "common/input.h"
#include "section-prep/cross_section.h"
#include "section-prep/section_mesher.h"
#include "section-prep/section_spec.h"

namespace fc::section {
namespace {

const std::string kMaterials =
    "materials:\n"
    "  ud: {type: orthotropic, E1: 140e9, E2: 9e9, E3: 9e9, G12: 5e9, G13: 5e9, G23: 3e9,\n"
    "       nu12: 0.3, nu13: 0.3, nu23: 0.5, rho: 1550}\n";

TEST(MeshFile, GeoWithPhysicalNamesEqualsParametricPlies) {
  const std::string dir = std::string(FLEXCOMP_SOURCE_DIR) + "/tests/section-prep/data/";
  const auto from_geo = analyzeSection(meshSection(readSectionSpec(InputNode::loadString(
      kMaterials + "section: {shape: mesh, file: " + dir + "two_ply_strip.geo, mesh_size: 0.0008}\n"))));
  const auto from_plies = analyzeSection(meshSection(readSectionSpec(InputNode::loadString(
      kMaterials +
      "section:\n  shape: rectangle\n  width: 0.02\n  height: 0.01\n  mesh_size: 0.0008\n"
      "  plies: [{material: ud, thickness: 0.005, angle_deg: 30},\n"
      "          {material: ud, thickness: 0.005, angle_deg: -30}]\n"))));
  // Two gmsh meshes of the same geometry at the same size: not node for node
  // identical, so agreement is to the discretisation error of quadratic
  // triangles at h = 0.8 mm (~1e-5 on torsion, see test_closed_forms).
  double worst = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      worst = std::max(worst, std::abs(from_geo.timoshenko(i, j) - from_plies.timoshenko(i, j)) /
                                  std::sqrt(from_plies.timoshenko(i, i) * from_plies.timoshenko(j, j)));
  EXPECT_LT(worst, 1e-4);
  // The antisymmetric +30/-30 stack couples extension and twist (the beam
  // counterpart of the laminate's B16): the check is not vacuous.
  EXPECT_GT(std::abs(from_plies.timoshenko(0, 3)),
            1e-2 * std::sqrt(from_plies.timoshenko(0, 0) * from_plies.timoshenko(3, 3)));
  EXPECT_NEAR(from_geo.mass_per_length, 1550 * 2e-4, 1e-9);
}

TEST(MeshFile, MshIsUsedAsItIs) {
  // Mesh the .geo with gmsh (quadratic, 0.8 mm) and save a .msh; reading that
  // .msh must give exactly the section of meshing the .geo the same way, since
  // the elements are the same.
  const std::string dir = std::string(FLEXCOMP_SOURCE_DIR) + "/tests/section-prep/data/";
  const std::string msh =
      (std::filesystem::temp_directory_path() / "section_prep_two_ply_strip.msh").string();
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(dir + "two_ply_strip.geo");
  gmsh::vectorpair points;
  gmsh::model::getEntities(points, 0);
  gmsh::model::mesh::setSize(points, 0.0008);
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.0008);
  gmsh::option::setNumber("Mesh.ElementOrder", 2);
  gmsh::model::mesh::generate(2);
  gmsh::write(msh);
  gmsh::finalize();
  const auto from_msh = analyzeSection(meshSection(readSectionSpec(
      InputNode::loadString(kMaterials + "section: {shape: mesh, file: " + msh + "}\n"))));
  const auto from_geo = analyzeSection(meshSection(readSectionSpec(InputNode::loadString(
      kMaterials + "section: {shape: mesh, file: " + dir + "two_ply_strip.geo, mesh_size: 0.0008}\n"))));
  EXPECT_EQ(from_msh.n_elements, from_geo.n_elements);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR(from_msh.timoshenko(i, j), from_geo.timoshenko(i, j),
                  1e-9 * std::sqrt(from_geo.timoshenko(i, i) * from_geo.timoshenko(j, j)));
  std::filesystem::remove(msh);
}

TEST(MeshFile, UnknownMaterialInAPhysicalNameIsReported) {
  const std::string dir = std::string(FLEXCOMP_SOURCE_DIR) + "/tests/section-prep/data/";
  const std::string other =
      "materials:\n  steel: {type: isotropic, E: 210e9, nu: 0.3, rho: 7850}\n";
  try {
    meshSection(readSectionSpec(
        InputNode::loadString(other + "section: {shape: mesh, file: " + dir + "two_ply_strip.geo}\n")));
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("ud/30/0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fc::section
