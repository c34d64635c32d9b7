// Flexible body files: invariants against closed forms (a lumped plate), the
// write/read round trip, partial reads of the first modes, and bad files.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdio>
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "common/flexbody.h"
#include "common/h5io.h"
#include "tests/mbs-run/flexible/random_body.h"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("flexcomp_test_flexbody_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

// A rectangular plate a x b x t, density rho, mid-surface centred at c, as nx x ny
// cells with lumped masses at the (nx+1)(ny+1) grid nodes by the trapezoidal rule
// (corner 1/4, edge 1/2, inner 1 of a cell's mass) and rotary inertias m t^2/12
// about the in-plane axes (the through-thickness part of a shell's lumped mass).
fc::FlexBody lumpedPlate(double a, double b, double t, double rho, const Vector3d& c, int nx, int ny) {
  fc::FlexBody p;
  p.name = "plate";
  const long n = static_cast<long>(nx + 1) * (ny + 1);
  p.nodes.resize(n, 3);
  p.nodal_mass.resize(n, 4);
  const double cell = rho * t * (a / nx) * (b / ny);
  long k = 0;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i, ++k) {
      p.nodes.row(k) << c.x() - a / 2 + a * i / nx, c.y() - b / 2 + b * j / ny, c.z();
      const double m = cell * ((i == 0 || i == nx) ? 0.5 : 1.0) * ((j == 0 || j == ny) ? 0.5 : 1.0);
      p.nodal_mass.row(k) << m, m * t * t / 12, m * t * t / 12, 0.0;
    }
  p.shapes.resize(6 * n, 0);
  return p;
}

TEST(FlexBodyInvariants, LumpedPlateReproducesTheClosedForms) {
  const double a = 2.0, b = 1.3, t = 0.002, rho = 1610.0;
  const Vector3d c(0.3, -0.2, 0.05);
  const int nx = 8, ny = 5;
  fc::FlexBody plate = lumpedPlate(a, b, t, rho, c, nx, ny);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(plate);
  const double M = rho * a * b * t;
  // The trapezoidal rule integrates linear functions exactly and x^2 with the
  // Euler-Maclaurin error h^2/12 [f']: sum m (x - cx)^2 = M a^2/12 (1 + 2/nx^2),
  // exactly. So the lumped sums have closed forms (to round-off, 1e-12), and tend
  // to the continuous plate's (a^2 + t^2) M / 12 etc. as 2/n^2.
  const double xx = a * a / 12 * (1 + 2.0 / (nx * nx)), yy = b * b / 12 * (1 + 2.0 / (ny * ny));
  const double zz = t * t / 12;  // from the rotary inertias
  Matrix3d I;
  I << M * (c.y() * c.y() + yy + c.z() * c.z() + zz), -M * c.x() * c.y(), -M * c.x() * c.z(),
      -M * c.x() * c.y(), M * (c.x() * c.x() + xx + c.z() * c.z() + zz), -M * c.y() * c.z(),
      -M * c.x() * c.z(), -M * c.y() * c.z(), M * (c.x() * c.x() + c.y() * c.y() + xx + yy);
  EXPECT_NEAR(inv.mass, M, 1e-12 * M);
  EXPECT_LT((inv.centerOfMass() - c).norm(), 1e-12);
  EXPECT_LT((inv.inertiaAboutOrigin() - I).norm(), 1e-12 * I.norm());

  // The continuous plate (parallel-axis theorem on M (b^2 + t^2)/12, ...): within
  // the trapezoidal rule's 2/n^2 relative error, and closer on a finer grid.
  auto exact = [&]() {
    Matrix3d E = I;
    E(0, 0) -= M * (yy - b * b / 12);
    E(1, 1) -= M * (xx - a * a / 12);
    E(2, 2) -= M * (xx - a * a / 12 + yy - b * b / 12);
    return E;
  }();
  const double coarse = (inv.inertiaAboutOrigin() - exact).norm() / exact.norm();
  EXPECT_LT(coarse, 2.0 / (ny * ny));
  const fc::InertiaInvariants fine = fc::computeInertiaInvariants(lumpedPlate(a, b, t, rho, c, 4 * nx, 4 * ny));
  EXPECT_LT((fine.inertiaAboutOrigin() - exact).norm() / exact.norm(), coarse / 10);

  fc::setRigidPropertiesFromLumpedMasses(plate);
  EXPECT_NEAR(plate.mass, M, 1e-12 * M);
  EXPECT_LT((plate.inertia_tensor - I).norm(), 1e-12 * I.norm());
}

TEST(FlexBodyInvariants, ModalInvariantsMatchTheMatrixForm) {
  // The invariants, computed node by node, against the same quantities written as
  // products of global matrices (Shabana's volume integrals with a lumped mass):
  // E_a picks component a of every node, Mn = diag(m_k), Jr = blockdiag(J_k).
  const int nm = 3;
  const fc::FlexBody body = fc::testing::randomBody(6, nm, 14);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  const long n = body.nodeCount();
  MatrixXd Xt(3 * n, nm), Xr(3 * n, nm), Jr = MatrixXd::Zero(3 * n, 3 * n);
  MatrixXd sumRows = MatrixXd::Zero(3, 3 * n);  // sum over nodes of a 3-vector field
  for (long k = 0; k < n; ++k) {
    Jr.block(3 * k, 3 * k, 3, 3) = body.nodal_mass.row(k).tail<3>().asDiagonal();
    Xt.middleRows(3 * k, 3) = body.shapes.middleRows(6 * k, 3);
    Xr.middleRows(3 * k, 3) = body.shapes.middleRows(6 * k + 3, 3);
    sumRows.middleCols(3 * k, 3).setIdentity();
  }
  const MatrixXd Mn = body.nodal_mass.col(0).asDiagonal();
  std::array<MatrixXd, 3> E;
  for (int a = 0; a < 3; ++a) {
    E[a] = MatrixXd::Zero(n, 3 * n);
    for (long k = 0; k < n; ++k) E[a](k, 3 * k + a) = 1.0;
  }
  // Round-off only (entries ~1, a few dozen terms): 1e-12.
  const double tol = 1e-12;
  EXPECT_LT((inv.modalMass() - MatrixXd::Identity(nm, nm)).norm(), tol);  // mass-normalised modes
  for (int a = 0; a < 3; ++a) {
    const Eigen::VectorXd s0a = body.nodes.col(a);
    EXPECT_LT((inv.modal_first_moment.row(a) - Eigen::RowVectorXd::Ones(n) * Mn * E[a] * Xt).norm(), tol);
    for (int b = 0; b < 3; ++b) {
      EXPECT_LT((inv.modal_products[3 * a + b] - (E[a] * Xt).transpose() * Mn * (E[b] * Xt)).norm(), tol);
      EXPECT_LT((inv.modal_second_moment.row(3 * a + b) - s0a.transpose() * Mn * E[b] * Xt).norm(), tol);
      EXPECT_NEAR(inv.second_moment(a, b), s0a.dot(Mn * body.nodes.col(b)), tol);
    }
  }
  EXPECT_LT((inv.rotary_modal - sumRows * Jr * Xr).norm(), tol);
  EXPECT_LT((inv.rotary_modal_mass - Xr.transpose() * Jr * Xr).norm(), tol);
}

void expectSameInvariants(const fc::InertiaInvariants& a, const fc::InertiaInvariants& b, double tol) {
  ASSERT_EQ(a.n_modes, b.n_modes);
  EXPECT_NEAR(a.mass, b.mass, tol);
  EXPECT_LE((a.first_moment - b.first_moment).norm(), tol);
  EXPECT_LE((a.second_moment - b.second_moment).norm(), tol);
  EXPECT_LE((a.rotary_inertia - b.rotary_inertia).norm(), tol);
  EXPECT_LE((a.modal_first_moment - b.modal_first_moment).norm(), tol);
  EXPECT_LE((a.modal_second_moment - b.modal_second_moment).norm(), tol);
  for (int i = 0; i < 9; ++i) EXPECT_LE((a.modal_products[i] - b.modal_products[i]).norm(), tol);
  EXPECT_LE((a.rotary_modal - b.rotary_modal).norm(), tol);
  EXPECT_LE((a.rotary_modal_mass - b.rotary_modal_mass).norm(), tol);
}

class FlexBodyFile : public ::testing::Test {
 protected:
  void SetUp() override {
    body = fc::testing::randomBody(9, 5, 42);
    invariants = fc::computeInertiaInvariants(body);
    path = tempPath(::testing::UnitTest::GetInstance()->current_test_info()->name() + std::string(".h5"));
    fc::Provenance prov;
    prov.inputs_sha256 = std::string(64, 'a');
    fc::writeFlexBody(path, body, invariants, prov);
  }
  void TearDown() override { std::remove(path.c_str()); }
  fc::FlexBody body;
  fc::InertiaInvariants invariants;
  std::string path;
};

TEST_F(FlexBodyFile, RoundTripIsExact) {
  const fc::FlexBodyFile f = fc::readFlexBody(path, -1, fc::FlexBodyParts::All);
  const fc::FlexBody& r = f.body;
  EXPECT_EQ(f.modes_in_file, 5);
  EXPECT_EQ(f.provenance.format, "flexbody/1");
  EXPECT_EQ(f.provenance.tool, "fe-prep");
  EXPECT_EQ(f.provenance.inputs_sha256, std::string(64, 'a'));
  EXPECT_EQ(r.name, body.name);
  EXPECT_EQ(r.nodes, body.nodes);
  EXPECT_EQ(r.nodal_mass, body.nodal_mass);
  EXPECT_EQ(r.shapes, body.shapes);
  EXPECT_EQ(r.eigenvalues, body.eigenvalues);
  EXPECT_EQ(r.frequencies_hz, body.frequencies_hz);
  EXPECT_EQ(r.mass, body.mass);
  EXPECT_EQ(r.center_of_mass, body.center_of_mass);
  EXPECT_EQ(r.inertia_tensor, body.inertia_tensor);
  ASSERT_EQ(r.elements.count("triangles"), 1u);
  EXPECT_EQ(r.elements.at("triangles"), body.elements.at("triangles"));
  ASSERT_EQ(r.interfaces.size(), body.interfaces.size());
  for (const auto& it : body.interfaces) {
    const fc::FlexInterface& ri = r.interface(it.name);
    EXPECT_EQ(ri.node, it.node);
    EXPECT_EQ(ri.position, it.position);
    EXPECT_EQ(ri.shapes, it.shapes);
  }
  expectSameInvariants(f.invariants, invariants, 0.0);
}

TEST_F(FlexBodyFile, ReadsOnlyTheFirstModes) {
  const fc::FlexBodyFile dyn = fc::readFlexBody(path, 2);
  EXPECT_EQ(dyn.modes_in_file, 5);
  EXPECT_EQ(dyn.body.modeCount(), 2);
  EXPECT_EQ(dyn.body.nodes.size(), 0);  // mbs-run's read leaves the mesh alone
  EXPECT_EQ(dyn.body.eigenvalues, body.eigenvalues.head(2));
  for (const auto& it : body.interfaces) EXPECT_EQ(dyn.body.interface(it.name).shapes, it.shapes.topRows(2));
  expectSameInvariants(dyn.invariants, invariants.truncated(2), 0.0);
  // Truncating the invariants is the same as computing them with fewer modes.
  expectSameInvariants(dyn.invariants, fc::computeInertiaInvariants(body, 2), 1e-13);

  const fc::FlexBodyFile all = fc::readFlexBody(path, 2, fc::FlexBodyParts::All);
  EXPECT_EQ(all.body.shapes, body.shapes.leftCols(2));

  const fc::FlexBodyFile rigid = fc::readFlexBody(path, 0);
  EXPECT_EQ(rigid.invariants.n_modes, 0);
  EXPECT_EQ(rigid.invariants.inertiaAboutOrigin(), invariants.inertiaAboutOrigin());
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST_F(FlexBodyFile, MoreModesThanTheFileHoldsIsAClearError) {
  const std::string e = errorOf([&] { fc::readFlexBody(path, 6); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("holds 5 modes, 6 asked"), std::string::npos) << e;
}

TEST_F(FlexBodyFile, MissingDatasetIsNamed) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  H5Ldelete(f, "/invariants/modal_products", H5P_DEFAULT);
  H5Fclose(f);
  const std::string e = errorOf([&] { fc::readFlexBody(path, 3); });
  EXPECT_NE(e.find("/invariants/modal_products"), std::string::npos) << e;
}

TEST(FlexBodyFormat, NewerOrForeignFormatsAreRejected) {
  const std::string path = tempPath("format.h5");
  for (const std::string format : {"flexbody/2", "section/1"}) {
    {
      fc::H5File f(path, fc::H5File::Mode::Create);
      f.setAttribute("/", "format", format);
    }
    const std::string e = errorOf([&] { fc::readFlexBody(path, 1); });
    EXPECT_NE(e.find(path), std::string::npos) << e;
    EXPECT_NE(e.find(format == "flexbody/2" ? "newer" : "expected a flexbody file"), std::string::npos) << e;
  }
  std::remove(path.c_str());
}

TEST(FlexBodyFormat, InconsistentBodyIsRejectedAndNothingIsWritten) {
  fc::FlexBody body = fc::testing::randomBody(5, 2, 7);
  const fc::InertiaInvariants inv = fc::computeInertiaInvariants(body);
  body.nodal_mass.conservativeResize(4, 4);
  const std::string path = tempPath("bad.h5");
  EXPECT_THROW(fc::writeFlexBody(path, body, inv, fc::Provenance{}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(FlexBodyFormat, RigidBodyFileWithoutModes) {
  fc::FlexBody plate = lumpedPlate(1.0, 0.5, 0.01, 2700.0, Vector3d::Zero(), 4, 2);
  fc::setRigidPropertiesFromLumpedMasses(plate);
  const std::string path = tempPath("rigid.h5");
  fc::writeFlexBody(path, plate, fc::computeInertiaInvariants(plate), fc::Provenance{});
  const fc::FlexBodyFile f = fc::readFlexBody(path, -1, fc::FlexBodyParts::All);
  EXPECT_EQ(f.modes_in_file, 0);
  EXPECT_EQ(f.body.nodes, plate.nodes);
  EXPECT_EQ(f.invariants.inertiaAboutOrigin(), plate.inertia_tensor);
  std::remove(path.c_str());
}

}  // namespace

// --- hardening -------------------------------------------------

TEST(FlexBodyHardening, SingularInertiaIsRefusedNamingTheBodyAndTheCause) {
  // Point masses on a line, no rotary inertia: nothing resists a spin about it.
  fc::FlexBody line = lumpedPlate(1.0, 0.0, 0.0, 1000.0, Vector3d::Zero(), 6, 1);
  line.name = "rod";
  line.nodes.col(1).setZero();
  line.nodal_mass.rightCols(3).setZero();
  for (long k = 0; k < line.nodeCount(); ++k) line.nodal_mass(k, 0) = 0.1;
  fc::setRigidPropertiesFromLumpedMasses(line);
  const std::string why = fc::flexBodyPhysicalProblem(line);
  EXPECT_NE(why.find("singular"), std::string::npos) << why;
  EXPECT_NE(why.find("rotary"), std::string::npos) << why;
  try {
    fc::writeFlexBody(tempPath("rod.h5"), line, fc::computeInertiaInvariants(line), {});
    ADD_FAILURE() << "a singular inertia was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 'rod'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(tempPath("rod.h5")));
  // The plate itself is fine.
  fc::FlexBody plate = lumpedPlate(2.0, 1.3, 0.002, 1610.0, Vector3d::Zero(), 4, 3);
  fc::setRigidPropertiesFromLumpedMasses(plate);
  EXPECT_EQ(fc::flexBodyPhysicalProblem(plate), "");
}

TEST(FlexBodyHardening, NonFiniteOrWrongShapedDatasetsAreNamedOnRead) {
  fc::FlexBody plate = lumpedPlate(2.0, 1.3, 0.002, 1610.0, Vector3d::Zero(), 4, 3);
  fc::setRigidPropertiesFromLumpedMasses(plate);
  const std::string path = tempPath("nan.h5");
  fc::writeFlexBody(path, plate, fc::computeInertiaInvariants(plate), {});
  ASSERT_NO_THROW(fc::readFlexBody(path));
  {
    // Corrupt one value in place, as a damaged or hand-edited file would be.
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/inertia/tensor", H5P_DEFAULT);
    double t[9];
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t);
    t[4] = INFINITY;
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t);
    H5Dclose(d);
    H5Fclose(f);
  }
  try {
    fc::readFlexBody(path);
    ADD_FAILURE() << "an infinite inertia was read";
  } catch (const fc::H5Error& e) {
    EXPECT_NE(std::string(e.what()).find("/inertia/tensor"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
  }
}

// Finite but absurd numbers (1e300 in an interface position or in the stress
// recovery strains, fuzz campaign on the new datasets) were read, and the run
// failed only writing an infinite peak reaction or failure index, naming its
// temporary file. The reader refuses them, naming the body file and the dataset.
// Rewrites a dataset of a written body file in place (what a damaged or
// foreign file would hold); fails the test if the dataset is missing or empty.
static void editDataset(const std::string& path, const char* set, const std::function<void(std::vector<double>&)>& edit) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, set, H5P_DEFAULT);
  ASSERT_GE(d, 0) << set;
  const hid_t space = H5Dget_space(d);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  ASSERT_GE(n, 1) << set;
  std::vector<double> v(static_cast<std::size_t>(n));
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  edit(v);
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

TEST(FlexBodyHardening, AbsurdlyLargeNumbersAreNamedOnRead) {
  fc::FlexBody plate = lumpedPlate(2.0, 1.3, 0.002, 1610.0, Vector3d::Zero(), 4, 3);
  fc::setRigidPropertiesFromLumpedMasses(plate);
  const std::string path = tempPath("huge.h5");
  fc::writeFlexBody(path, plate, fc::computeInertiaInvariants(plate), {});
  ASSERT_NO_THROW(fc::readFlexBody(path));
  for (const char* set : {"/inertia/center_of_mass", "/invariants/mass"}) {
    fc::writeFlexBody(path, plate, fc::computeInertiaInvariants(plate), {});
    editDataset(path, set, [](std::vector<double>& v) { v[0] = 1e300; });
    try {
      fc::readFlexBody(path);
      ADD_FAILURE() << "1e300 in " << set << " was read";
    } catch (const fc::H5Error& e) {
      EXPECT_NE(std::string(e.what()).find(set), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("beyond 1e30"), std::string::npos) << e.what();
    }
  }
}

// /inertia/ is what the invariants imply (honest inertia): a file in
// which they disagree is refused on read, naming what disagrees. Each of the
// rigid invariants scaled within the 1e30 bound (x 1e3, and a rotary inertia
// doubled) used to run as a different body from the one /inertia/ reports.
TEST(FlexBodyHardening, InvariantsThatDisagreeWithInertiaAreRefused) {
  fc::FlexBody plate = lumpedPlate(2.0, 1.3, 0.002, 1610.0, Vector3d(0.3, -0.2, 0.1), 4, 3);
  fc::setRigidPropertiesFromLumpedMasses(plate);
  const std::string path = tempPath("disagree.h5");
  fc::writeFlexBody(path, plate, fc::computeInertiaInvariants(plate), {});
  ASSERT_NO_THROW(fc::readFlexBody(path));
  for (const auto& [set, factor, named] :
       {std::tuple<const char*, double, const char*>{"/invariants/mass", 1e3, "/invariants/mass"},
        {"/invariants/first_moment", 1e3, "/invariants/first_moment"},
        {"/invariants/second_moment", 1e3, "/inertia/tensor"},
        {"/invariants/rotary_inertia", 2.0, "/inertia/tensor"},
        {"/inertia/mass", 1.0 + 1e-6, "/inertia/mass"}}) {
    fc::writeFlexBody(path, plate, fc::computeInertiaInvariants(plate), {});
    editDataset(path, set, [f = factor](std::vector<double>& v) {
      for (double& x : v) x *= f;
    });
    try {
      fc::readFlexBody(path);
      ADD_FAILURE() << set << " x " << factor << " was read";
    } catch (const fc::H5Error& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("must agree"), std::string::npos) << e.what();
    }
  }
}
