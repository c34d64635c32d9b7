// Bodies from another FE code's matrices (fe-prep/import/): the readers' checks
// (every refusal located), and the fitting of tests/data/import/ whose matrices
// CalculiX 2.20 wrote (README there): the imported body's frequencies against
// CalculiX's own *FREQUENCY run, its /inertia/ against the rigid-body projection
// of M, and the same matrices through the Abaqus and Matrix Market readers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <tuple>

#include "common/flexbody.h"
#include "common/input.h"
#include "fe-prep/beam_mesher.h"
#include "fe-prep/build_body.h"
#include "fe-prep/elements/beam_element.h"
#include "fe-prep/import/import_stage.h"
#include "fe-prep/import/imported_body.h"
#include "fe-prep/import/matrix_files.h"
#include "fe-prep/import/solid_faces.h"
#include "fe-prep/reference_conditions.h"
#include "tests/fe-prep/feprep_test_support.h"

namespace fc::feprep {
namespace {

const std::string kData = std::string(FLEXCOMP_DATA_DIR) + "/import/";

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string p = dir + "/" + name;
  std::ofstream(p) << text;
  return p;
}

// The message of the InputError `f` throws ("" when it throws none).
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

BodySpec fittingSpec(const std::string& dir, const std::string& matrices, const std::string& extra = "") {
  const std::string yaml = write(dir, "fitting.yaml",
                                 "body:\n  name: fitting\n  matrices: " + matrices +
                                     "\n  units: mm-t-s\n  modes: 8\n" + extra);
  return readBodySpec(yaml);
}

std::string ccxMatrices() {
  return "{format: calculix, stiffness: " + kData + "fitting_matrices.sti, mass: " + kData +
         "fitting_matrices.mas, dofs: " + kData + "fitting_matrices.dof, model: " + kData + "fitting_mesh.inp}";
}

// ---- readers

TEST(MatrixImportReaders, CalculixStorageAndBaseAreDetected) {
  const DofList d = readDofList(kData + "fitting_matrices.dof");
  const StoredMatrix k = readTripletMatrix(kData + "fitting_matrices.sti", static_cast<long>(d.dofs.size()));
  EXPECT_EQ(k.indexing, "one-based");
  std::string storage;
  const auto K = symmetricMatrix(k, static_cast<long>(d.dofs.size()), "stiffness", d, &storage);
  EXPECT_EQ(storage, "upper triangle");
  EXPECT_EQ(K.rows(), static_cast<long>(d.dofs.size()));
  EXPECT_EQ((Eigen::MatrixXd(K) - Eigen::MatrixXd(K).transpose()).cwiseAbs().maxCoeff(), 0.0);
}

TEST(MatrixImportReaders, ZeroBasedLowerTriangleIsDetected) {
  const std::string dir = test::scratchDir("import_zero_based");
  const std::string dofs = write(dir, "d.txt", "1 1\n1 2\n");
  const std::string m = write(dir, "k.txt", "0 0 2.0\n1 0 -1.0\n1 1 2.0\n");
  const DofList d = readDofList(dofs);
  const StoredMatrix s = readTripletMatrix(m, 2);
  EXPECT_EQ(s.indexing, "zero-based");
  std::string storage;
  const Eigen::MatrixXd K = symmetricMatrix(s, 2, "stiffness", d, &storage);
  EXPECT_EQ(storage, "lower triangle");
  EXPECT_EQ(K(0, 1), -1.0);
  EXPECT_EQ(K(1, 0), -1.0);
}

TEST(MatrixImportReaders, LocatedRefusals) {
  const std::string dir = test::scratchDir("import_refusals");
  const std::string dofs = write(dir, "d.txt", "1 1\n1 2\n1 3\n");
  const DofList d = readDofList(dofs);
  // Neither index 0 nor index 3 present: the base cannot be told.
  EXPECT_NE(errorOf([&] { readTripletMatrix(write(dir, "a.txt", "1 1 1.0\n2 2 1.0\n"), 3); }).find("cannot be told"),
            std::string::npos);
  // Both 0 and 3: four rows for a three-DOF list.
  EXPECT_NE(errorOf([&] { readTripletMatrix(write(dir, "b.txt", "0 0 1\n3 3 1\n"), 3); }).find("DOF list has 3"),
            std::string::npos);
  // A duplicated entry names both lines.
  {
    const std::string p = write(dir, "c.txt", "1 1 1\n2 2 1\n3 3 1\n1 2 0.5\n1 2 0.5\n");
    const std::string e = errorOf([&] { symmetricMatrix(readTripletMatrix(p, 3), 3, "stiffness", d); });
    EXPECT_NE(e.find("c.txt:5"), std::string::npos) << e;
    EXPECT_NE(e.find("lines 4 and 5"), std::string::npos) << e;
  }
  // Both triangles that do not mirror: non-symmetric, at the entry's line.
  {
    const std::string p = write(dir, "e.txt", "1 1 4\n2 2 4\n3 3 4\n1 2 1\n2 1 1.5\n");
    const std::string e = errorOf([&] { symmetricMatrix(readTripletMatrix(p, 3), 3, "mass", d); });
    EXPECT_NE(e.find("e.txt:5"), std::string::npos) << e;
    EXPECT_NE(e.find("not symmetric"), std::string::npos) << e;
  }
  // A missing diagonal names the DOF.
  {
    const std::string p = write(dir, "f.txt", "1 1 4\n3 3 4\n1 2 1\n");
    const std::string e = errorOf([&] { symmetricMatrix(readTripletMatrix(p, 3), 3, "stiffness", d); });
    EXPECT_NE(e.find("no diagonal entry for row 2 (node 1 DOF 2)"), std::string::npos) << e;
  }
  // Matrix Market: its size against the DOF list, and its one-based indices.
  {
    const std::string p = write(dir, "g.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1\n2 2 1\n");
    const std::string e = errorOf([&] { symmetricMatrix(readMatrixMarket(p), 3, "stiffness", d); });
    EXPECT_NE(e.find("has 2 rows but the DOF list"), std::string::npos) << e;
    const std::string q = write(dir, "h.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n0 1 1\n");
    EXPECT_NE(errorOf([&] { readMatrixMarket(q); }).find("h.mtx:3"), std::string::npos);
  }
  // A DOF listed twice (found by fuzzing the fitting's .dof): both lines named.
  EXPECT_NE(errorOf([&] { readDofList(write(dir, "j.txt", "1 1\n1 2\n1 2\n")); }).find("j.txt:3: node 1 DOF 2 listed again (first at line 2)"),
            std::string::npos);
  // A truncated entry line (fuzzing): the line and the field count.
  EXPECT_NE(errorOf([&] { readTripletMatrix(write(dir, "k.txt", "1 1 1\n2 2\n3 3 1\n"), 3); }).find("k.txt:2: expected an entry 'row col value', got 2 fields"),
            std::string::npos);
  // A DOF list line that is no DOF.
  EXPECT_NE(errorOf([&] { readDofList(write(dir, "i.txt", "1 1\n1 7\n")); }).find("i.txt:2"), std::string::npos);
}

// The three storages of one symmetric matrix (upper, lower, both triangles;
// comments between entries) give the same lower triangle, exactly (no
// arithmetic on the values), and a duplicate after comment lines is reported
// at its own lines (found again from the entries' line runs).
TEST(MatrixImportReaders, StoragesGiveOneLowerTriangle) {
  const std::string dir = test::scratchDir("import_storages");
  const DofList d = readDofList(write(dir, "d.txt", "1 1\n1 2\n1 3\n2 1\n"));
  Eigen::Matrix4d A;
  A << 4, -1, 0, 0.5, -1, 5, 2, 0, 0, 2, 6, -3, 0.5, 0, -3, 7;
  std::string up, low, both;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      if (A(r, c) == 0.0) continue;
      const std::string e = std::to_string(r + 1) + " " + std::to_string(c + 1) + " " + std::to_string(A(r, c)) + "\n";
      if (c >= r) up += e;
      if (c <= r) low += e;
      both += e;
      if (r == 1 && c == 1) up += "# a comment\n\n", both += "** another\n";
    }
  for (const auto& [name, text, storage] : {std::tuple{"u.txt", up, "upper triangle"}, std::tuple{"l.txt", low, "lower triangle"},
                                            std::tuple{"b.txt", both, "both triangles"}}) {
    std::string found;
    const Eigen::SparseMatrix<double> L = symmetricLowerTriangle(readTripletMatrix(write(dir, name, text), 4), 4, "stiffness", d, &found);
    EXPECT_EQ(found, storage);
    const Eigen::Matrix4d lower = A.triangularView<Eigen::Lower>();
    EXPECT_EQ((Eigen::MatrixXd(L) - lower).cwiseAbs().maxCoeff(), 0.0) << name;
    EXPECT_EQ((Eigen::MatrixXd(symmetricMatrix(readTripletMatrix(write(dir, name, text), 4), 4, "stiffness", d)) - A).cwiseAbs().maxCoeff(), 0.0) << name;
  }
  // Lines 1-2 entries, 3-4 comment and blank, 5-6 entries, 7 comment, 8 the repeat of line 6.
  const std::string p = write(dir, "dup.txt", "1 1 4\n2 2 5\n# c\n\n3 3 6\n1 2 -1\n% c\n1 2 -1\n4 4 7\n");
  const std::string e = errorOf([&] { symmetricLowerTriangle(readTripletMatrix(p, 4), 4, "stiffness", d); });
  EXPECT_NE(e.find("dup.txt:8"), std::string::npos) << e;
  EXPECT_NE(e.find("lines 6 and 8"), std::string::npos) << e;
}

// ---- the model checks (files of a two-node spring written here)

struct Spring {
  std::string dir, dofs, k, m, model;
};
Spring spring(const std::string& name, const std::string& k, const std::string& m, const std::string& model,
              const std::string& dofs = "1 1\n1 2\n1 3\n2 1\n2 2\n2 3\n") {
  Spring s;
  s.dir = test::scratchDir(name);
  s.dofs = write(s.dir, "s.dof", dofs);
  s.k = write(s.dir, "s.sti", k);
  s.m = write(s.dir, "s.mas", m);
  s.model = write(s.dir, "s.inp", model);
  return s;
}
MatricesSpec specOf(const Spring& s) {
  MatricesSpec m;
  m.format = "calculix";
  m.stiffness = s.k, m.mass = s.m, m.dofs = s.dofs, m.model = s.model;
  m.units = unitSystem("m-kg-s");
  return m;
}
// A spring along x between nodes 1 and 2 (on the x axis): rigid motions leave it unstrained.
const char* kSpringK = "1 1 1\n1 4 -1\n4 4 1\n2 2 0\n3 3 0\n5 5 0\n6 6 0\n";
const char* kSpringM = "1 1 1\n2 2 1\n3 3 1\n4 4 1\n5 5 1\n6 6 1\n";
const char* kSpringNodes = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*ELEMENT, TYPE=C3D4, ELSET=E\n1, 1, 2, 3, 4\n*NODE\n3, 0, 1, 0\n4, 0, 0, 1\n";

// The DOF list in any order: reversed, the source's lower triangle lands in the
// body's upper one and is mirrored back (spreadLowerTriangle); the body's K and
// M equal those of the natural order exactly.
TEST(MatrixImportModel, DofOrderDoesNotChangeTheBody) {
  const ImportedModel natural = importMatrices(specOf(spring("import_order_a", kSpringK, kSpringM, kSpringNodes)));
  auto reversed = [](const std::string& text) {  // row i -> 7 - i
    std::istringstream in(text);
    std::string out;
    long r, c;
    double v;
    while (in >> r >> c >> v) out += std::to_string(7 - r) + " " + std::to_string(7 - c) + " " + std::to_string(v) + "\n";
    return out;
  };
  const ImportedModel rev = importMatrices(specOf(spring("import_order_b", reversed(kSpringK), reversed(kSpringM), kSpringNodes,
                                                         "2 3\n2 2\n2 1\n1 3\n1 2\n1 1\n")));
  // Nodes are numbered in the DOF list's order: node 2 first here.
  ASSERT_EQ(rev.labels, (std::vector<long>{2, 1}));
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(12, 12);  // natural body DOF -> reversed body DOF
  for (int k = 0; k < 6; ++k) P(6 + k, k) = 1.0, P(k, 6 + k) = 1.0;
  const Eigen::MatrixXd Kn = Eigen::MatrixXd(Eigen::SparseMatrix<double>(natural.K.selfadjointView<Eigen::Lower>()));
  const Eigen::MatrixXd Kr = Eigen::MatrixXd(Eigen::SparseMatrix<double>(rev.K.selfadjointView<Eigen::Lower>()));
  const Eigen::MatrixXd Mn = Eigen::MatrixXd(Eigen::SparseMatrix<double>(natural.M.selfadjointView<Eigen::Lower>()));
  const Eigen::MatrixXd Mr = Eigen::MatrixXd(Eigen::SparseMatrix<double>(rev.M.selfadjointView<Eigen::Lower>()));
  EXPECT_EQ((P * Kn * P.transpose() - Kr).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((P * Mn * P.transpose() - Mr).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(Kn(0, 6), -1.0);  // the spring couples the two nodes' x
  // Only the lower triangles are stored.
  for (const auto* A : {&rev.K, &rev.M})
    for (long c = 0; c < A->outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(*A, c); it; ++it) EXPECT_GE(it.row(), c);
}

TEST(MatrixImportModel, LocatedRefusals) {
  // The spring is fine.
  {
    const Spring s = spring("import_ok", kSpringK, kSpringM, kSpringNodes);
    EXPECT_EQ(errorOf([&] { importMatrices(specOf(s)); }), "");
  }
  // A node the DOF list names but the node table lacks: the DOF list's line.
  {
    const Spring s = spring("import_missing_node", kSpringK, kSpringM, kSpringNodes, "1 1\n1 2\n1 3\n9 1\n9 2\n9 3\n");
    const std::string e = errorOf([&] { importMatrices(specOf(s)); });
    EXPECT_NE(e.find("s.dof:4"), std::string::npos) << e;
    EXPECT_NE(e.find("node 9 is not in the model's node table"), std::string::npos) << e;
  }
  // Rotations on a node of solid elements only.
  {
    const Spring s = spring("import_solid_rotation", "1 1 1\n2 2 1\n3 3 1\n4 4 1\n", "1 1 1\n2 2 1\n3 3 1\n4 4 1\n",
                            kSpringNodes, "1 1\n1 2\n1 3\n1 4\n");
    const std::string e = errorOf([&] { importMatrices(specOf(s)); });
    EXPECT_NE(e.find("s.dof:4"), std::string::npos) << e;
    EXPECT_NE(e.find("solid elements"), std::string::npos) << e;
  }
  // An indefinite mass (a 2x2 minor negative).
  {
    const Spring s = spring("import_indefinite", kSpringK, "1 1 1\n1 4 2\n2 2 1\n3 3 1\n4 4 1\n5 5 1\n6 6 1\n", kSpringNodes);
    const std::string e = errorOf([&] { importMatrices(specOf(s)); });
    EXPECT_NE(e.find("indefinite: 1 of its eigenvalues"), std::string::npos) << e;
    EXPECT_NE(e.find("s.mas"), std::string::npos) << e;
  }
  // A node without its three translations (a plane model).
  {
    const Spring s = spring("import_plane", "1 1 1\n1 3 -1\n3 3 1\n2 2 0\n4 4 0\n", "1 1 1\n2 2 1\n3 3 1\n4 4 1\n",
                            kSpringNodes, "1 1\n1 2\n2 1\n2 2\n");
    const std::string e = errorOf([&] { importMatrices(specOf(s)); });
    EXPECT_NE(e.find("s.dof:1"), std::string::npos) << e;
    EXPECT_NE(e.find("node 1 lists DOF 1, 2: every node needs translations"), std::string::npos) << e;
  }
  // No mass at all.
  {
    const Spring s = spring("import_massless", kSpringK, "1 1 0\n2 2 0\n3 3 0\n4 4 0\n5 5 0\n6 6 0\n", kSpringNodes);
    const std::string e = errorOf([&] { importMatrices(specOf(s)); });
    EXPECT_NE(e.find("carries no mass"), std::string::npos) << e;
  }
  // A stiffness held to ground (a source model with boundary conditions).
  {
    const Spring s = spring("import_held", "1 1 2\n1 4 -1\n4 4 1\n2 2 0\n3 3 0\n5 5 0\n6 6 0\n", kSpringM, kSpringNodes);
    const std::string e = errorOf([&] { importMatrices(specOf(s)); });
    EXPECT_NE(e.find("strains rigid motions"), std::string::npos) << e;
    EXPECT_NE(e.find("most at node 1 DOF 1, " + s.dofs + ":1"), std::string::npos) << e;
  }
}

TEST(MatrixImportModel, UnitsAreRequiredAndConvert) {
  const std::string dir = test::scratchDir("import_units");
  const std::string yaml = write(dir, "b.yaml", "body:\n  matrices: " + ccxMatrices() + "\n  modes: 4\n");
  const std::string e = errorOf([&] { readBodySpec(yaml); });
  EXPECT_NE(e.find("b.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("missing units"), std::string::npos) << e;
  // mm-t-s: a 1 N/mm spring between nodes 1 mm apart is 1000 N/m between nodes 1e-3 m apart.
  const Spring s = spring("import_units_spring", kSpringK, kSpringM, kSpringNodes);
  MatricesSpec m = specOf(s);
  m.units = unitSystem("mm-t-s");
  const ImportedModel im = importMatrices(m);
  EXPECT_DOUBLE_EQ(im.K.coeff(0, 0), 1000.0);
  EXPECT_DOUBLE_EQ(im.M.coeff(0, 0), 1000.0);  // 1 t
  EXPECT_DOUBLE_EQ(im.mesh.nodes(1, 0), 1e-3);
}

// ---- the fitting: CalculiX's matrices against CalculiX's own frequencies

TEST(MatrixImportFitting, FrequenciesAndInertiaMatchCalculix) {
  const std::string dir = test::scratchDir("import_fitting");
  const BodySpec spec = fittingSpec(dir, ccxMatrices());
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult r = buildFlexBody(MPI_COMM_WORLD, spec, opt);
  // CalculiX's *FREQUENCY of the same free model (fitting_modes.dat): modes 1-6 rigid.
  const Eigen::VectorXd ccx = readCalculixEigenvalues(kData + "fitting_modes.dat");
  ASSERT_EQ(ccx.size(), 14);
  ASSERT_EQ(r.body.eigenvalues.size(), 8);
  for (long j = 0; j < 8; ++j)
    // 1e-6 (the figure): the .dat prints 7 significant digits (1e-7 of lambda) and
    // CalculiX's ARPACK stops at its own tolerance; measured 6.7e-7 at worst (mode 2).
    EXPECT_NEAR(r.body.eigenvalues(j) / ccx(6 + j), 1.0, 1e-6) << "elastic mode " << j + 1;
  // /inertia/ is the rigid-body projection of the imported M (through the fitted nodal masses).
  const ImportedModel im = importMatrices(*spec.matrices);
  const MassProjection p = rigidMassProjection(im.mesh.nodes, im.M);
  EXPECT_LT(p.misfit, 1e-12);
  // 1e-10: the moment fit solves its ten conditions to round-off (mass_lumping.h).
  EXPECT_NEAR(r.body.mass / p.mass, 1.0, 1e-10);
  EXPECT_LT((r.body.center_of_mass - p.centerOfMass()).norm(), 1e-10 * 0.03);
  EXPECT_LT((r.body.inertia_tensor - p.inertia_about_origin).cwiseAbs().maxCoeff(),
            1e-10 * p.inertia_about_origin.cwiseAbs().maxCoeff());
  EXPECT_FALSE(r.body.has_exact_inertia);
  // Steel 7.85 t/m^3 x the fitting's volume (40 x 20 x 5 + 5 x 20 x 20 mm^3): a consistent M's mass is exact.
  EXPECT_NEAR(p.mass, 7850.0 * (40e-3 * 20e-3 * 5e-3 + 5e-3 * 20e-3 * 20e-3), 1e-12);
  // Solid nodes: zero rotations in the shapes.
  EXPECT_EQ(r.body.shapes.rows(), 6 * im.mesh.nodeCount());
  double rot = 0.0;
  for (long k = 0; k < im.mesh.nodeCount(); ++k) rot = std::max(rot, r.body.shapes.middleRows(6 * k + 3, 3).cwiseAbs().maxCoeff());
  EXPECT_EQ(rot, 0.0);
  // The file passes mbs-run's on-read consistency check (inertia vs invariants).
  const std::string h5 = dir + "/fitting.h5";
  writeFlexBody(h5, r.body, computeInertiaInvariants(r.body), Provenance{});
  const FlexBodyFile f = readFlexBody(h5);
  EXPECT_NEAR(f.body.mass, r.body.mass, 1e-12 * r.body.mass);
}

// The same matrices written as Matrix Market and as Abaqus .mtx (node, dof, node,
// dof, value; lower triangle) by this test from the CalculiX files' values (%.17g:
// the doubles read back bit for bit): the same body.
TEST(MatrixImportFitting, AbaqusAndMatrixMarketGiveTheSameBody) {
  const std::string dir = test::scratchDir("import_formats");
  const DofList d = readDofList(kData + "fitting_matrices.dof");
  const long n = static_cast<long>(d.dofs.size());
  std::string mm_dofs;
  for (const auto& x : d.dofs) mm_dofs += std::to_string(x.node) + " " + std::to_string(x.dof) + "\n";
  write(dir, "fitting.dofs", mm_dofs);
  for (const char* which : {"sti", "mas"}) {
    const StoredMatrix s = readTripletMatrix(kData + "fitting_matrices." + which, n);
    std::string mm = "%%MatrixMarket matrix coordinate real symmetric\n% from fitting_matrices." + std::string(which) + "\n" +
                     std::to_string(n) + " " + std::to_string(n) + " " + std::to_string(s.entries.size()) + "\n";
    std::string abq = "** *MATRIX OUTPUT form: row node, row dof, column node, column dof, value (lower triangle)\n";
    char buf[128];
    for (const auto& e : s.entries) {
      const long r = std::max(e.row, e.col), c = std::min(e.row, e.col);  // the lower triangle
      std::snprintf(buf, sizeof buf, "%ld %ld %.17g\n", r + 1, c + 1, e.value);
      mm += buf;
      const NodeDof& a = d.dofs[static_cast<std::size_t>(r)];
      const NodeDof& b = d.dofs[static_cast<std::size_t>(c)];
      std::snprintf(buf, sizeof buf, "%ld,%d,%ld,%d,%.17g\n", a.node, a.dof, b.node, b.dof, e.value);
      abq += buf;
    }
    write(dir, std::string("fitting_") + which + ".mtx", mm);
    write(dir, std::string("fitting_") + which + "_abq.mtx", abq);
  }
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult ref = buildFlexBody(MPI_COMM_WORLD, fittingSpec(dir, ccxMatrices()), opt);
  const std::string model = kData + "fitting_mesh.inp";
  for (const std::string& m :
       {"{format: matrix_market, stiffness: fitting_sti.mtx, mass: fitting_mas.mtx, dofs: fitting.dofs, model: " + model + "}",
        "{format: abaqus, stiffness: fitting_sti_abq.mtx, mass: fitting_mas_abq.mtx, model: " + model + "}"}) {
    const BuildResult r = buildFlexBody(MPI_COMM_WORLD, fittingSpec(dir, m), opt);
    ASSERT_EQ(r.body.eigenvalues.size(), ref.body.eigenvalues.size()) << m;
    // 1e-12: the same doubles in the same DOF order; only the eigen-solver's round-off differs.
    for (long j = 0; j < ref.body.eigenvalues.size(); ++j)
      EXPECT_NEAR(r.body.eigenvalues(j) / ref.body.eigenvalues(j), 1.0, 1e-12) << m;
    EXPECT_NEAR(r.body.mass / ref.body.mass, 1.0, 1e-12) << m;
    EXPECT_LT((r.body.inertia_tensor - ref.body.inertia_tensor).cwiseAbs().maxCoeff(),
              1e-12 * ref.body.inertia_tensor.cwiseAbs().maxCoeff()) << m;
    EXPECT_LT((r.body.nodes - ref.body.nodes).cwiseAbs().maxCoeff(), 1e-15) << m;
  }
}

// CalculiX's static case (fitting_static.inp): pads held, 100 N along x, then
// along y, at a reference node 5 mm above the lug's top face coupled to it
// rigidly (*KINEMATIC). fe-prep's body of the same matrices with the same
// conditions (pads pinned, a rigid patch on LUGTOP) computes the exact static
// deflection of the interface point per unit load (/interfaces/*/static_compliance).
TEST(MatrixImportFitting, RigidPatchStaticDeflectionMatchesCalculix) {
  const std::string dir = test::scratchDir("import_static");
  const BodySpec spec = fittingSpec(dir, ccxMatrices(),
                                    "  interfaces:\n    lug: {point: [0, 0, 0.030], coupling: rigid, nodes: {edge: LUGTOP}}\n"
                                    "  reference: {clamp: [PADS]}\n");
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult r = buildFlexBody(MPI_COMM_WORLD, spec, opt);
  ASSERT_EQ(r.body.interfaces.size(), 1u);
  const Eigen::VectorXd& c = r.body.interfaces[0].static_compliance;
  ASSERT_EQ(c.size(), 6);
  // fitting_static.dat: U1 = 1.431469E-02 mm under 100 N (step 1), U2 = 3.988351E-03 mm (step 2).
  // 1e-5: the .dat prints 7 digits (5e-7); both are direct solutions of the same K.
  EXPECT_NEAR(c(0) / (1.431469e-5 / 100.0), 1.0, 1e-5);
  EXPECT_NEAR(c(1) / (3.988351e-6 / 100.0), 1.0, 1e-5);
}

// The two text layouts of Abaqus's *MATRIX OUTPUT (docs/file-formats.md gives
// the sources): FORMAT=COORDINATE ('row column  value', blanks, both triangles,
// global equation numbers; rows named by a dofs: list) and FORMAT=MATRIX INPUT
// ('node,dof,node,dof,value', commas, lower triangle; rows named by the file).
// tests/data/import/brick_*: one C3D20 brick's CalculiX matrices written in both
// layouts by make_abaqus_layouts.py; each reads back as CalculiX's matrix
// exactly (the same decimal strings, so the same doubles: difference 0).
TEST(MatrixImportReaders, BothAbaqusLayoutsReadAsTheSourceMatrix) {
  const DofList d = readDofList(kData + "brick_matrices.dof");
  const long n = static_cast<long>(d.dofs.size());
  ASSERT_EQ(n, 60);
  for (const auto& [ccx, abq, name] : {std::tuple{"sti", "STIF1", "stiffness"}, std::tuple{"mas", "MASS1", "mass"}}) {
    const Eigen::SparseMatrix<double> ref =
        symmetricMatrix(readTripletMatrix(kData + "brick_matrices." + ccx, n), n, name, d);
    const AbaqusMatrix coord = readAbaqusMatrix(kData + "brick_coordinate_" + abq + ".mtx", n);
    EXPECT_TRUE(coord.dofs.dofs.empty());
    EXPECT_EQ(coord.matrix.indexing, "one-based");
    std::string storage;
    const Eigen::SparseMatrix<double> a = symmetricMatrix(coord.matrix, n, name, d, &storage);
    EXPECT_EQ(storage, "both triangles");
    EXPECT_EQ((a - ref).norm(), 0.0) << abq;
    const AbaqusMatrix input = readAbaqusMatrix(kData + "brick_matrix_input_" + abq + ".mtx", 0);
    ASSERT_EQ(input.dofs.dofs.size(), d.dofs.size());
    for (long i = 0; i < n; ++i) {
      EXPECT_EQ(input.dofs.dofs[static_cast<std::size_t>(i)].node, d.dofs[static_cast<std::size_t>(i)].node);
      EXPECT_EQ(input.dofs.dofs[static_cast<std::size_t>(i)].dof, d.dofs[static_cast<std::size_t>(i)].dof);
    }
    const Eigen::SparseMatrix<double> b = symmetricMatrix(input.matrix, n, name, input.dofs, &storage);
    EXPECT_EQ(storage, "lower triangle");
    EXPECT_EQ((b - ref).norm(), 0.0) << abq;
  }
  // Abaqus's internal nodes (Lagrange multipliers) carry labels below 1: refused, located.
  const std::string dir = test::scratchDir("import_abaqus_internal");
  const std::string bad = write(dir, "internal.mtx", "1,1,1,1,2.0\n-3,1,1,1,0.5\n");
  const std::string msg = errorOf([&] { readAbaqusMatrix(bad, 0); });
  EXPECT_NE(msg.find("internal.mtx:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("node label -3"), std::string::npos) << msg;
}

// CalculiX's matrix storage of a beam (B32R, expanded by ccx into a C3D20R
// brick) names each brick node by its parent beam node: refused with the
// reason (tests/data/import/beam_b32_matrices.inp, the .dof ccx 2.20 wrote).
TEST(MatrixImportReaders, CalculixExpandedBeamDofListIsRefusedWithTheReason) {
  const std::string msg = errorOf([] { readDofList(kData + "beam_b32_matrices.dof"); });
  EXPECT_NE(msg.find("beam_b32_matrices.dof:4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("node 1 DOF 1 listed again (first at line 1)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expands into bricks"), std::string::npos) << msg;
}

// One generator (examples/imported-fitting/make_fitting.py) for the example's
// mesh and the fixtures': the two files are its output, byte for byte.
TEST(MatrixImportFitting, FixtureMeshIsTheExamplesMesh) {
  auto text = [](const std::string& p) {
    std::ifstream in(p);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string fixture = text(kData + "fitting_mesh.inp");
  ASSERT_FALSE(fixture.empty());
  EXPECT_EQ(fixture, text(std::string(FLEXCOMP_SOURCE_DIR) + "/examples/imported-fitting/fitting_mesh.inp"));
}

// ---- distributing (RBE3) patches on imported solids

// Face integrals of the shape functions on flat faces, by hand: bilinear
// quad A/4 each; serendipity quad8 -A/12 at corners, A/3 at mid-sides; linear
// triangle A/3; quadratic triangle 0 at corners, A/3 at mid-sides. The
// quadrature is exact for these (round-off only).
TEST(MatrixImportFaces, FaceIntegralsOfTheShapeFunctions) {
  Eigen::MatrixXd X(8, 3);
  X << 0, 0, 0, 2, 0, 0, 2, 3, 0, 0, 3, 0, 1, 0, 0, 2, 1.5, 0, 1, 3, 0, 0, 1.5, 0;  // 2 x 3 rectangle, corners then mid-sides
  const double A = 6.0;
  const Eigen::VectorXd q4 = faceNodalAreas(X, SolidFace{{0, 1, 2, 3}, 4});
  const Eigen::VectorXd q8 = faceNodalAreas(X, SolidFace{{0, 1, 2, 3, 4, 5, 6, 7}, 4});
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(q4(i), A / 4, 1e-14);
    EXPECT_NEAR(q8(i), -A / 12, 1e-14);
    EXPECT_NEAR(q8(4 + i), A / 3, 1e-14);
  }
  Eigen::MatrixXd T(6, 3);  // a triangle of area 3 out of the x-y plane, corners then mid-sides
  T << 0, 0, 0, 2, 0, 0, 0, 3, 0, 1, 0, 0, 1, 1.5, 0, 0, 1.5, 0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T = (T * R.transpose()).eval();
  const Eigen::VectorXd t3 = faceNodalAreas(T, SolidFace{{0, 1, 2}, 3});
  const Eigen::VectorXd t6 = faceNodalAreas(T, SolidFace{{0, 1, 2, 3, 4, 5}, 3});
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(t3(i), 1.0, 1e-14);
    EXPECT_NEAR(t6(i), 0.0, 1e-14);
    EXPECT_NEAR(t6(3 + i), 1.0, 1e-14);
  }
}

// The fitting's surface: every boundary face of its 14 bricks once, total area
// the L-shape's (bottom 40 x 20, base top 40 x 20 - 5 x 20, base sides 2 (40 + 20) 5,
// lug sides 2 (20 + 5) 20, lug top 5 x 20: 3200 mm^2);
// the LUGTOP patch's weights sum to its 100 mm^2 and centre on (0, 0, 25).
TEST(MatrixImportFaces, FittingSurfaceAndPatchWeights) {
  const std::string dir = test::scratchDir("import_faces");
  const ImportedModel im = importMatrices(*fittingSpec(dir, ccxMatrices()).matrices);
  double total = 0.0;
  for (const SolidFace& f : im.faces) total += faceNodalAreas(im.mesh.nodes, f).sum();
  const double expect = 1e-6 * (40 * 20 + (40 * 20 - 5 * 20) + 2 * (40 + 20) * 5 + 2 * (20 + 5) * 20 + 5 * 20);
  EXPECT_NEAR(total / expect, 1.0, 1e-13);
  const std::vector<long>& top = im.mesh.sets.at("LUGTOP");
  long used = 0;
  double area = 0.0;
  const Eigen::VectorXd w = patchFaceWeights(im.mesh.nodes, im.faces, top, &used, &area);
  EXPECT_EQ(used, 2);
  EXPECT_NEAR(w.sum(), 1e-4, 1e-18);
  EXPECT_NEAR(area, 1e-4, 1e-18);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < top.size(); ++k) c += w(static_cast<long>(k)) * im.mesh.nodes.row(top[k]).transpose();
  EXPECT_LT((c / w.sum() - Eigen::Vector3d(0, 0, 0.025)).norm(), 1e-15);
  // The corner of both faces (two -A/12) and the mid-side between them (two A/3), A = 50 mm^2.
  EXPECT_NEAR(w.minCoeff(), -2 * 50e-6 / 12, 1e-18);
}

// CalculiX's total strain energies of the six unit-direction load steps (100 N, 100 N mm).
std::vector<double> calculixEnergies(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<double> u;
  while (std::getline(in, line))
    if (line.find("total internal energy") != std::string::npos) {
      std::string value;
      while (std::getline(in, value) && value.find_first_not_of(' ') == std::string::npos) {
      }
      u.push_back(std::stod(value));
    }
  return u;
}

// The fitting as a Craig-Bampton body with two distributing patches: PADS
// (the bolt pads' bottom faces, reference at the origin) and LUGTOP (the lug's
// top faces, reference 5 mm above). CalculiX (fitting_rbe3_static.inp, README
// in tests/data/import): the PADS reference held by the six RBE3 equations,
// 100 N / 100 N mm at the LUG reference distributed by CalculiX's own
// *COUPLING + *DISTRIBUTING; the compliance along each load is 2 U / P^2 from
// its strain energy U. fe-prep: the body's shapes with the PADS reference held,
// C = B Lambda^-1 B^T, B = S_lug^T - G_lug G_pads^-1 S_pads^T (S the interface
// shapes, G the rigid transfers from the body origin; the rigid motion is what
// holds the PADS point still). And the same with the roles swapped
// (fitting_rbe3_swap.inp). Tolerance 1e-5: both sides solve the same K with
// the same constraint (CalculiX's weights are the face integrals, see
// solid_faces.h), the constraint modes hold the static response exactly, and
// the .dat prints U to 7 digits (5e-7); measured 1.3e-7 at worst. (The goal
// was 0.5 %; with the nodes weighed equally instead, as before, the
// compliances differ from CalculiX's by up to 58 %, about y.)
TEST(MatrixImportFitting, TwoDistributingPatchesCraigBamptonMatchCalculixStatically) {
  const std::string dir = test::scratchDir("import_rbe3");
  const BodySpec spec = fittingSpec(dir, ccxMatrices(),
                                    "  interfaces:\n    pads: {point: [0, 0, 0], coupling: distributing, nodes: {edge: PADS}}\n"
                                    "    lug: {point: [0, 0, 0.030], coupling: distributing, nodes: {edge: LUGTOP}}\n"
                                    "  reference: {clamp: [pads, lug]}\n  reduction: craig_bampton\n");
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult r = buildFlexBody(MPI_COMM_WORLD, spec, opt);
  ASSERT_EQ(r.body.interfaces.size(), 2u);
  const Eigen::VectorXd lambda = r.body.eigenvalues;
  auto held = [&](int loaded, int fixed) {
    const FlexInterface& a = r.body.interfaces[static_cast<std::size_t>(loaded)];
    const FlexInterface& b = r.body.interfaces[static_cast<std::size_t>(fixed)];
    const Eigen::MatrixXd B = a.shapes.transpose() - rigidTransfer(a.position) * rigidTransfer(b.position).inverse() * b.shapes.transpose();
    return Eigen::MatrixXd(B * lambda.cwiseInverse().asDiagonal() * B.transpose());
  };
  const char* dir_names[6] = {"Fx", "Fy", "Fz", "Mx", "My", "Mz"};
  for (const auto& [file, loaded, fixed] : {std::tuple{"fitting_rbe3_static.dat", 1, 0}, std::tuple{"fitting_rbe3_swap.dat", 0, 1}}) {
    const std::vector<double> U = calculixEnergies(kData + file);
    ASSERT_EQ(U.size(), 6u) << file;
    const Eigen::MatrixXd C = held(loaded, fixed);
    for (int k = 0; k < 6; ++k) {
      // 100 N or 100 N mm in mm-t-s: compliance [mm/N, rad/(N mm)] to SI [m/N, rad/(N m)].
      const double ccx = 2 * U[static_cast<std::size_t>(k)] / 1e4 * (k < 3 ? 1e-3 : 1e3);
      std::printf("[   info   ] %s %s: fe-prep %.7e, CalculiX %.7e (%+.1e)\n", file, dir_names[k], C(k, k), ccx, C(k, k) / ccx - 1);
      EXPECT_NEAR(C(k, k) / ccx, 1.0, 1e-5) << file << " " << dir_names[k];
    }
  }
}

// The fitting with the PADS reference held, free-interface modes: fe-prep's
// constrained modes (reference: {clamp: [pads]}) against CalculiX's *FREQUENCY
// with the same six RBE3 equations (fitting_rbe3_modes.dat). 1e-6: the same
// K, M and constraint; the .dat prints 7 digits and ARPACK stops at its own
// tolerance (as the free-free comparison above).
TEST(MatrixImportFitting, HeldDistributingPatchFrequenciesMatchCalculix) {
  const std::string dir = test::scratchDir("import_rbe3_modes");
  const BodySpec spec = fittingSpec(dir, ccxMatrices(),
                                    "  interfaces:\n    pads: {point: [0, 0, 0], coupling: distributing, nodes: {edge: PADS}}\n"
                                    "  reference: {clamp: [pads]}\n");
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult r = buildFlexBody(MPI_COMM_WORLD, spec, opt);
  const Eigen::VectorXd ccx = readCalculixEigenvalues(kData + "fitting_rbe3_modes.dat");
  ASSERT_EQ(ccx.size(), 10);
  ASSERT_EQ(r.body.eigenvalues.size(), 8);
  for (long j = 0; j < 8; ++j) {
    std::printf("[   info   ] mode %ld: fe-prep %.7e, CalculiX %.7e (%+.1e)\n", j + 1, r.body.eigenvalues(j), ccx(j), r.body.eigenvalues(j) / ccx(j) - 1);
    EXPECT_NEAR(r.body.eigenvalues(j) / ccx(j), 1.0, 1e-6) << "mode " << j + 1;
  }
}

// A beam from CalculiX against fe-prep's own Timoshenko beam: a free steel bar
// 240 x 20 x 10 mm in 12 x 1 x 1 C3D20 bricks (tests/data/import/bar_*, what
// ccx's B32 expansion is; its beam matrices themselves cannot be imported,
// docs/file-formats.md), imported, against the same bar built by fe-prep from
// YAML (48 Timoshenko elements, consistent mass). The first five elastic modes
// are bending (z1, y1, z2, z3, y2). Measured (imported / fe-prep - 1): +0.15,
// +0.18, +0.58, +0.64, +1.26 %. The gap is CalculiX's coarse mesh (one brick
// across the section, 20 mm bricks along): its own run on 24 x 4 x 2 bricks is
// 0.12, 0.16, 0.47, 0.57, 1.03 % lower, and then within 0.03, 0.02, 0.11, 0.07,
// 0.22 % of fe-prep (beam theory's own difference from 3-D elasticity: plane
// sections, the shear factor, growing with the mode number as h / wavelength).
// Tolerance 1.5 %: the larger of the two meshes' measured differences (1.26 %
// at mode 5) with room for neither more. The imported eigenvalues also equal
// CalculiX's *FREQUENCY of the same model to 1e-6 (as the fitting's). The
// torsion mode (6) is not compared: one brick across the section restrains
// its warping (CalculiX 5348 Hz here, 4965 Hz on 4 x 2 bricks; fe-prep 4954 Hz,
// Saint-Venant's J of the rectangle).
TEST(MatrixImportBeam, CalculixSolidBarMatchesTheTimoshenkoBeamInBending) {
  const std::string dir = test::scratchDir("import_bar");
  const std::string yaml = write(dir, "bar.yaml",
                                 "body:\n  name: bar\n  matrices: {format: calculix, stiffness: " + kData + "bar_matrices.sti, mass: " +
                                     kData + "bar_matrices.mas, dofs: " + kData + "bar_matrices.dof, model: " + kData +
                                     "bar_mesh.inp}\n  units: mm-t-s\n  modes: 6\n");
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult im = buildFlexBody(MPI_COMM_WORLD, readBodySpec(yaml), opt);
  const std::string native =
      "materials:\n  steel: {type: isotropic, E: 2.1e11, nu: 0.3, rho: 7850}\n"
      "body:\n  name: bar\n  beam: {length: 0.24, elements: 48, section: {shape: rectangle, width: 0.02, height: 0.01, material: steel}}\n"
      "  reference: free\n  modes: 6\n  mass: consistent\n";
  const BuildResult fe = buildFlexBody(MPI_COMM_WORLD, parseBodySpec(InputNode::loadString(native, "bar.yaml")), opt);
  const Eigen::VectorXd ccx = readCalculixEigenvalues(kData + "bar_modes.dat");
  ASSERT_EQ(ccx.size(), 16);
  ASSERT_EQ(im.body.frequencies_hz.size(), 6);
  ASSERT_EQ(fe.body.frequencies_hz.size(), 6);
  for (long j = 0; j < 6; ++j) EXPECT_NEAR(im.body.eigenvalues(j) / ccx(6 + j), 1.0, 1e-6) << "mode " << j + 1;
  for (long j = 0; j < 5; ++j) {
    const double gap = im.body.frequencies_hz(j) / fe.body.frequencies_hz(j) - 1;
    std::printf("[   info   ] bending mode %ld: imported %.2f Hz, fe-prep beam %.2f Hz (%+.2f %%)\n", j + 1,
                im.body.frequencies_hz(j), fe.body.frequencies_hz(j), 100 * gap);
    EXPECT_NEAR(gap, 0.0, 0.015) << "mode " << j + 1;
  }
}

// A plate from CalculiX against fe-prep's own shell: a free steel plate
// 200 x 100 x 2 mm in 20 x 10 x 1 C3D20 bricks (tests/data/import/plate_*;
// what ccx's S8 expansion is, whose own matrices cannot be imported,
// docs/file-formats.md) against the plate from YAML (DST, h = 5 mm,
// consistent mass). Measured (fe-prep / CalculiX - 1), modes 1-8: -0.06,
// +0.18, +0.20, -0.22, -0.21, +0.19, -0.07, -0.45 %. Both converge to within
// 0.16 % of each other (CalculiX 40 x 20 bricks: 267.24, 329.50, 724.92,
// 741.71, 1095.0, 1257.9, 1291.2, 1476.3 Hz; fe-prep h = 2.5 mm: 267.24,
// 329.99, 726.06, 741.68, 1094.9, 1260.0, 1292.1, 1476.1 Hz: what remains is
// plate theory against 3-D elasticity in the twisting modes 2, 3, 6); each
// side's own refinement moves them by up to 0.69 % (CalculiX, mode 8) and
// 0.42 % (fe-prep, mode 6). Tolerance 1 %: the converged difference plus the
// larger refinement change. The matrices (9 MB each) are not committed: where
// ccx is installed the test runs the matrix-storage deck in a scratch folder
// and checks the imported eigenvalues against the committed *FREQUENCY table
// to 1e-6, and the imported body against the shell as above; without ccx it
// says so and checks the shell against the table only.
TEST(MatrixImportPlate, CalculixSolidPlateMatchesTheShell) {
  const std::string native =
      "materials:\n  steel: {type: isotropic, E: 2.1e11, nu: 0.3, rho: 7850}\n"
      "body:\n  name: plate\n  shell: {rectangle: {length: 0.2, width: 0.1}, material: steel, thickness: 0.002, "
      "element: dst, mesh: {size: 0.005}}\n  reference: free\n  modes: 8\n  mass: consistent\n";
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult fe = buildFlexBody(MPI_COMM_WORLD, parseBodySpec(InputNode::loadString(native, "plate.yaml")), opt);
  const Eigen::VectorXd ccx = readCalculixEigenvalues(kData + "plate_modes.dat");
  ASSERT_EQ(ccx.size(), 14);
  ASSERT_EQ(fe.body.frequencies_hz.size(), 8);
  for (long j = 0; j < 8; ++j) {
    const double f = std::sqrt(ccx(6 + j)) / (2 * M_PI);
    std::printf("[   info   ] mode %ld: fe-prep shell %.2f Hz, CalculiX C3D20 %.2f Hz (%+.2f %%)\n", j + 1, fe.body.frequencies_hz(j), f,
                100 * (fe.body.frequencies_hz(j) / f - 1));
    EXPECT_NEAR(fe.body.frequencies_hz(j) / f, 1.0, 0.01) << "mode " << j + 1;
  }
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) {
    std::printf("[   info   ] ccx not installed: the plate's matrices were not produced, the import half not run\n");
    return;
  }
  const std::string dir = test::scratchDir("import_plate");
  for (const char* f : {"plate_matrices.inp", "plate_mesh.inp"})
    std::filesystem::copy_file(kData + f, dir + "/" + f, std::filesystem::copy_options::overwrite_existing);
  ASSERT_EQ(std::system(("cd '" + dir + "' && ccx -i plate_matrices > plate_matrices.log 2>&1").c_str()), 0);
  const std::string yaml = write(dir, "plate.yaml",
                                 "body:\n  name: plate\n  matrices: {format: calculix, stiffness: plate_matrices.sti, mass: "
                                 "plate_matrices.mas, dofs: plate_matrices.dof, model: plate_mesh.inp}\n  units: mm-t-s\n  modes: 8\n");
  const BuildResult im = buildFlexBody(MPI_COMM_WORLD, readBodySpec(yaml), opt);
  ASSERT_EQ(im.body.eigenvalues.size(), 8);
  for (long j = 0; j < 8; ++j) {
    // As the fitting's: the .dat's 7 digits and ARPACK's own tolerance.
    EXPECT_NEAR(im.body.eigenvalues(j) / ccx(6 + j), 1.0, 1e-6) << "mode " << j + 1;
    EXPECT_NEAR(fe.body.frequencies_hz(j) / im.body.frequencies_hz(j), 1.0, 0.01) << "mode " << j + 1;
  }
}

// Six-DOF nodes: a free steel tube's Timoshenko matrices, assembled here from
// fe-prep's own beam element and written as Matrix Market with a "node dof"
// list and a "label x y z" table, imported; the same beam built natively
// (mass: consistent, the same M in the eigenproblem) must have the same
// frequencies, and /inertia/ equal to M's projection (rotary inertias included).
TEST(MatrixImportBeam, SixDofNodesGiveTheNativeBeamsFrequencies) {
  const std::string dir = test::scratchDir("import_beam");
  const std::string native =
      "materials:\n  steel: {type: isotropic, E: 2.1e11, nu: 0.3, rho: 7850}\n"
      "body:\n  name: tube\n  beam: {length: 1.0, elements: 12, section: {shape: tube, outer_diameter: 0.04, wall: {thickness: 0.004}, material: steel}}\n"
      "  reference: free\n  modes: 6\n  mass: consistent\n";
  const BodySpec ns = parseBodySpec(InputNode::loadString(native, "tube.yaml"));
  BuildOptions opt;
  opt.quiet = true;
  const BuildResult ref = buildFlexBody(MPI_COMM_WORLD, ns, opt);
  const Mesh mesh = meshBeam(1.0, 12, {});
  const long n = mesh.nodeCount();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * n, 6 * n), M = K;
  for (const auto& b : mesh.beams) {
    const fe::BeamMatrices e = fe::timoshenkoBeam(mesh.nodes.row(b[0]).transpose(), mesh.nodes.row(b[1]).transpose(),
                                                  Eigen::Vector3d::UnitY(), ns.beam->Ks, ns.beam->Ms);
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        K.block<6, 6>(6 * b[a], 6 * b[c]) += e.K.block<6, 6>(6 * a, 6 * c);
        M.block<6, 6>(6 * b[a], 6 * b[c]) += e.M.block<6, 6>(6 * a, 6 * c);
      }
  }
  std::string dofs, nodes;
  char buf[160];
  for (long k = 0; k < n; ++k) {
    for (int d = 1; d <= 6; ++d) dofs += std::to_string(101 + k) + " " + std::to_string(d) + "\n";
    std::snprintf(buf, sizeof buf, "%ld %.17g %.17g %.17g\n", 101 + k, mesh.nodes(k, 0), mesh.nodes(k, 1), mesh.nodes(k, 2));
    nodes += buf;
  }
  write(dir, "tube.dofs", dofs);
  write(dir, "tube_nodes.txt", nodes);
  for (const auto& [name, A] : {std::make_pair(std::string("k"), &K), std::make_pair(std::string("m"), &M)}) {
    std::string body;
    long count = 0;
    for (long j = 0; j < 6 * n; ++j)
      for (long i = j; i < 6 * n; ++i)
        if ((*A)(i, j) != 0.0) {
          std::snprintf(buf, sizeof buf, "%ld %ld %.17g\n", i + 1, j + 1, (*A)(i, j));
          body += buf;
          ++count;
        }
    write(dir, "tube_" + name + ".mtx", "%%MatrixMarket matrix coordinate real symmetric\n" + std::to_string(6 * n) + " " +
                                            std::to_string(6 * n) + " " + std::to_string(count) + "\n" + body);
  }
  const std::string yaml = write(dir, "tube.yaml",
                                 "body:\n  name: tube\n  matrices: {format: matrix_market, stiffness: tube_k.mtx, mass: tube_m.mtx, "
                                 "dofs: tube.dofs, model: tube_nodes.txt}\n  units: m-kg-s\n  modes: 6\n");
  const BuildResult r = buildFlexBody(MPI_COMM_WORLD, readBodySpec(yaml), opt);
  ASSERT_EQ(r.body.eigenvalues.size(), 6);
  // The same matrices and the same solver: round-off (SLEPc tolerance 1e-10).
  for (long j = 0; j < 6; ++j) EXPECT_NEAR(r.body.eigenvalues(j) / ref.body.eigenvalues(j), 1.0, 1e-9) << j;
  const ImportedModel im = importMatrices(*readBodySpec(yaml).matrices);
  const MassProjection p = rigidMassProjection(im.mesh.nodes, im.M);
  EXPECT_NEAR(r.body.mass / p.mass, 1.0, 1e-10);
  EXPECT_LT((r.body.inertia_tensor - p.inertia_about_origin).cwiseAbs().maxCoeff(),
            1e-10 * p.inertia_about_origin.cwiseAbs().maxCoeff());
  // And M's projection is the tube's exact mass and inertia (the native body's exact values).
  EXPECT_NEAR(p.mass / ref.body.exact_mass, 1.0, 1e-12);
  EXPECT_LT((p.inertia_about_origin - ref.body.exact_inertia_tensor).cwiseAbs().maxCoeff(),
            1e-10 * ref.body.exact_inertia_tensor.cwiseAbs().maxCoeff());
}

// The check against the source: CalculiX's own table agrees (no warning); the
// same table with elastic mode 3 moved by 1e-4 draws a warning naming it.
TEST(MatrixImportFitting, SourceFrequencyMismatchIsAWarningNamingTheMode) {
  const std::string dir = test::scratchDir("import_source_check");
  std::ifstream in(kData + "fitting_modes.dat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string good = write(dir, "good.dat", text);
  const std::string mode9 = "      9   0.1353873E+11";
  const auto at = text.find(mode9);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, mode9.size(), "      9   0.1354008E+11");  // x 1.0001
  const std::string bad = write(dir, "bad.dat", text);
  for (const auto& [dat, warns] : {std::make_pair(good, false), std::make_pair(bad, true)}) {
    const BodySpec spec = fittingSpec(dir, "{format: calculix, stiffness: " + kData + "fitting_matrices.sti, mass: " + kData +
                                               "fitting_matrices.mas, dofs: " + kData + "fitting_matrices.dof, model: " +
                                               kData + "fitting_mesh.inp, reference_frequencies: " + dat + "}");
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    importStage(MPI_COMM_WORLD, spec, false);
    const std::string out = testing::internal::GetCapturedStdout();
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(out.find("mass 0.0471 kg"), std::string::npos) << out;
    EXPECT_EQ(err.find("warning: elastic mode 3 of the imported matrices") != std::string::npos, warns) << err;
    if (!warns) {
      EXPECT_EQ(err.find("warning"), std::string::npos) << err;
    }
  }
}

}  // namespace
}  // namespace fc::feprep
