#pragma once
// Readers of the matrices and models other FE codes write (docs/file-formats.md,
// "Imported matrices"): plain functions from a file to entries, DOF lists and
// node tables, and the checks that turn stored entries into one symmetric
// matrix. Every problem is an fc::InputError naming the file, the line and what
// was expected; nothing is guessed: the storage (one triangle or both), the
// indexing (one- or zero-based) and the size are read off the file and checked
// against the DOF list, and what cannot be decided is refused.
#include <Eigen/Sparse>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fe-prep/import/solid_faces.h"

namespace fc::feprep {

// One entry as stored, indices 0-based once the reader has decided the base.
// 16 bytes: a 1e6-DOF model holds ~4e7 of them while it is checked, so the
// line of each entry is not kept with it (StoredMatrix::lineOf gives it).
struct MatrixEntry {
  int row = 0, col = 0;
  double value = 0.0;
};

struct StoredMatrix {
  std::string file;
  long size = -1;  // dimension the file states (Matrix Market header), -1 when it states none
  std::vector<MatrixEntry> entries;  // in file order, one per data line
  std::string indexing;  // "one-based" or "zero-based" (what the reader found)
  bool declared_symmetric = false;  // Matrix Market "symmetric": one triangle by definition
  // The line of entries[k], for messages: entries follow each other one per
  // line except where comments or blank lines intervene, so only the entries
  // that start a new run of consecutive lines are recorded (entry, line).
  std::vector<std::pair<long, int>> line_runs;
  int lineOf(long k) const;
  void add(const MatrixEntry& e, int line);
};
// The DOF of a matrix row: a node label of the model and a component 1..6
// (1-3 translations, 4-6 rotations, as CalculiX, Abaqus and Nastran number them).
struct NodeDof {
  long node = 0;
  int dof = 0;
  int line = 0;
};

struct DofList {
  std::string file;
  std::vector<NodeDof> dofs;  // row i of the matrices is dofs[i]
};

// Nodes of a model with their labels, and what the model says about them.
struct NodeTable {
  std::string file;
  std::map<long, Eigen::Vector3d> coordinates;  // label -> x y z (file units)
  std::map<long, int> line;                     // label -> line of its definition
  std::map<std::string, std::vector<long>> sets; // *NSET name -> labels (upper case as written in the file)
  // Labels of nodes used by solid (continuum, 3-DOF) elements and by structural
  // (shell, beam: 6-DOF) elements, from the *ELEMENT TYPE=... blocks.
  std::vector<long> solid_nodes, structural_nodes;
  std::map<std::string, long> element_counts;    // element type -> count
  std::vector<SolidElement> solid_elements;      // the solid elements (their faces weigh distributing patches)
};

// Matrix Market coordinate real (general or symmetric) files, one-based by the format.
StoredMatrix readMatrixMarket(const std::string& path);

// "row col value" lines (CalculiX .sti/.mas, any triplet dump; blanks or commas
// between fields). `dof_count` (the DOF list's length) decides the base: an index
// 0 is zero-based, an index dof_count one-based; both, or neither with every
// diagonal required, is refused.
StoredMatrix readTripletMatrix(const std::string& path, long dof_count);

// Abaqus *MATRIX OUTPUT text (.mtx): lines "row node, row dof, column node,
// column dof, value" (the DOF come from the file; the list is returned in
// ascending node, dof order) or "row, column, value" (the DOF come from a dofs:
// file, `dof_count` rows, base decided as readTripletMatrix). Lines starting
// with '*' are comments or headings.
struct AbaqusMatrix {
  StoredMatrix matrix;
  DofList dofs;  // empty for the three-column form
};
AbaqusMatrix readAbaqusMatrix(const std::string& path, long dof_count);

// The DOF list: one line per matrix row, "node dof", "node, dof" or CalculiX's "node.dof".
DofList readDofList(const std::string& path);

// A node table: a CalculiX/Abaqus .inp (its *NODE, *NSET and *ELEMENT blocks; other
// keywords are skipped, *INCLUDE followed) or a plain table of "label x y z" lines.
NodeTable readNodeTable(const std::string& path);

// The lower triangle (column-major: row >= column) of the symmetric matrix `m`
// stores, `n` DOF, `name` "stiffness" or "mass" for messages. Refuses: a size
// that differs from n, indices outside 0..n-1, a duplicated entry, entries in
// both triangles that do not mirror each other (non-symmetric), and a DOF whose
// diagonal entry is missing (for the mass, missing diagonals are allowed on
// rotations whose whole row is absent: a massless rotation). `storage` receives
// "upper triangle", "lower triangle", "both triangles" or "diagonal". The
// matrix is built in place (12 bytes per kept entry beside the 16 of `m`'s
// entries): no per-entry maps, sorted copies or triplet lists.
Eigen::SparseMatrix<double> symmetricLowerTriangle(const StoredMatrix& m, long n, const std::string& name,
                                                   const DofList& dofs, std::string* storage = nullptr);

// The same matrix with both triangles (symmetricLowerTriangle, mirrored).
Eigen::SparseMatrix<double> symmetricMatrix(const StoredMatrix& m, long n, const std::string& name,
                                            const DofList& dofs, std::string* storage = nullptr);

}  // namespace fc::feprep
