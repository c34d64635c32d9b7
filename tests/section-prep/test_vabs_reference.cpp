// Acceptance test of on VABS's own inputs, section-prep reproduces the
// matrices and centres VABS wrote to the .K files (VABS 4.x, tests/data/vabs/).
// Same mesh, same element types, same theory: the only differences left are
// rounding and VABS's 11-digit printout, so 1e-6 relative to the diagonal is
// a strict test (tests/data/vabs/README.md reports ~1e-9 agreement).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <fstream>
#include <sstream>

#include "section-prep/cross_section.h"
#include "section-prep/material_frame.h"
#include "section-prep/vabs_reader.h"
#include "vabs_k_file.h"

namespace fc::section {
namespace {

const std::string kDir = std::string(FLEXCOMP_DATA_DIR) + "/vabs/";

// Largest |a_ij - b_ij| / sqrt(|b_ii b_jj|): errors measured against the
// diagonal, so that a tiny coupling term is not required to match relatively.
double diagonalRelativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  double worst = 0;
  for (int i = 0; i < b.rows(); ++i)
    for (int j = 0; j < b.cols(); ++j) {
      const double scale = std::sqrt(std::abs(b(i, i) * b(j, j)));
      worst = std::max(worst, std::abs(a(i, j) - b(i, j)) / scale);
    }
  return worst;
}

struct Case {
  const char* input;
};

class VabsReference : public ::testing::TestWithParam<Case> {};

TEST_P(VabsReference, MatchesVabsOutput) {
  const std::string input = kDir + GetParam().input;
  const testing::VabsOutput ref = testing::readVabsK(input + ".K");
  const VabsModel model = readVabsFile(input);
  const SectionProperties p = analyzeSection(model.mesh);

  const double tol = 1e-6;
  const double size0 = std::sqrt(ref.mass(3, 3) / ref.mass(0, 0));
  std::printf("%s: mass %.1e classical %.1e timoshenko %.1e centres %.1e %.1e %.1e (relative)\n",
              GetParam().input, diagonalRelativeError(p.mass, ref.mass),
              diagonalRelativeError(p.classical, ref.classical),
              diagonalRelativeError(p.timoshenko, ref.timoshenko),
              (p.mass_center - ref.mass_center).norm() / size0,
              (p.tension_center - ref.tension_center).norm() / size0,
              (p.shear_center - ref.shear_center).norm() / size0);
  EXPECT_LT(diagonalRelativeError(p.mass, ref.mass), tol) << "mass\n" << p.mass << "\nVABS\n" << ref.mass;
  EXPECT_LT(diagonalRelativeError(p.classical, ref.classical), tol)
      << "classical\n" << p.classical << "\nVABS\n" << ref.classical;
  ASSERT_TRUE(ref.has_timoshenko);
  EXPECT_LT(diagonalRelativeError(p.timoshenko, ref.timoshenko), tol)
      << "timoshenko\n" << p.timoshenko << "\nVABS\n" << ref.timoshenko;
  EXPECT_NEAR(p.area, ref.area, tol * ref.area);
  // Centres: relative to the section's size (radius of gyration of the area).
  const double size = std::sqrt(ref.mass(3, 3) / ref.mass(0, 0));
  EXPECT_LT((p.mass_center - ref.mass_center).norm(), tol * size) << p.mass_center.transpose();
  EXPECT_LT((p.tension_center - ref.tension_center).norm(), tol * size) << p.tension_center.transpose()
                                                                        << " VABS " << ref.tension_center.transpose();
  ASSERT_TRUE(ref.has_shear_center);
  EXPECT_LT((p.shear_center - ref.shear_center).norm(), tol * size) << p.shear_center.transpose()
                                                                    << " VABS " << ref.shear_center.transpose();
}

INSTANTIATE_TEST_SUITE_P(Simple, VabsReference,
                         ::testing::Values(Case{"3cells.sg"}, Case{"sg2_i_simple_eo1.dat"}),
                         [](const auto& info) {
                           std::string n = info.param.input;
                           for (char& c : n) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });
INSTANTIATE_TEST_SUITE_P(Composite, VabsReference,
                         ::testing::Values(Case{"cas1.sg"}, Case{"box_cus_comp.sg"},
                                           Case{"cs_box_t_vabs41.sg"}, Case{"mh104.sg"}),
                         [](const auto& info) {
                           std::string n = info.param.input;
                           for (char& c : n) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
}  // namespace fc::section

namespace fc::section {
namespace {

// Anisotropic materials (orth = 2, the 21 upper-triangle stiffnesses in the
// Voigt order [11, 22, 33, 23, 13, 12], as sgio and SwiftComp write them):
// an orthotropic ply at theta3 = 30 degrees must give the same section as the
// same ply entered as its rotated, fully populated stiffness at theta3 = 0.
// This exercises every coupling position (C16, C26, C36, C45) of the reader.
TEST(VabsAnisotropic, RotatedStiffnessEqualsRotatedPly) {
  std::ifstream in(kDir + "sg2_i_simple_eo1.dat");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string layer = "       3       2  0.000000000000e+00\n";
  const std::string mat2 =
      "       2       1  ! material id, anisotropy\n"
      "  3.760000000000e+10  9.584000000000e+09  9.584000000000e+09\n"
      "  4.081000000000e+09  4.081000000000e+09  4.081000000000e+09\n"
      "  2.600000000000e-01  2.600000000000e-01  1.742220044107e-01\n";
  ASSERT_NE(text.find(layer), std::string::npos);
  ASSERT_NE(text.find(mat2), std::string::npos);

  std::string rotated_ply = text;
  rotated_ply.replace(rotated_ply.find(layer), layer.size(), "       3       2  30.0\n");

  const Matrix6d C = orthotropicStiffness(3.76e10, 9.584e9, 9.584e9, 4.081e9, 4.081e9, 4.081e9,
                                          0.26, 0.26, 0.1742220044107);
  const double t = 30.0 * M_PI / 180;
  const Matrix6d Cr = rotateVoigtStiffness(C, materialAxes(0.0, t));
  std::ostringstream aniso;
  aniso.precision(17);
  aniso << "       2       2\n";
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) aniso << " " << Cr(i, j);
    aniso << "\n";
  }
  std::string rotated_stiffness = text;
  rotated_stiffness.replace(rotated_stiffness.find(mat2), mat2.size(), aniso.str());

  const auto a = analyzeSection(parseVabs(rotated_ply, "ply30").mesh);
  const auto b = analyzeSection(parseVabs(rotated_stiffness, "aniso").mesh);
  EXPECT_LT(diagonalRelativeError(b.timoshenko, a.timoshenko), 1e-12);
  EXPECT_LT(diagonalRelativeError(b.mass, a.mass), 1e-14);
  // The rotated ply really couples something the 0-degree ply does not.
  const auto c = analyzeSection(parseVabs(text, "ply0").mesh);
  EXPECT_GT(diagonalRelativeError(a.timoshenko, c.timoshenko), 1e-3);
}

}  // namespace
}  // namespace fc::section
