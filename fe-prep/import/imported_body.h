#pragma once
// A body from another FE code's stiffness and mass matrices (contracts.md,
// "General bodies", body.matrices): the imported model as fe-prep's pipeline
// wants it. The matrices are spread onto 6 DOF per node (node-major, the body
// DOF order) in SI; nodes the DOF list gives translations only (solid nodes)
// have their rotations held (holdSolidRotations), so that the reference
// conditions, interfaces, reductions and the body file apply unchanged and
// /modes/shapes carries zero rotations there. Assembly treats each coupled node
// pair as an "element" (its 6x6 blocks), so the DOF map's transformations
// (couplings, held patches) reduce the imported matrices exactly as they reduce
// fe-prep's own elements.
#include <Eigen/Sparse>
#include <optional>
#include <string>
#include <vector>

#include "fe-prep/import/matrices_spec.h"
#include "fe-prep/import/solid_faces.h"
#include "fe-prep/element_kernel.h"
#include "fe-prep/body_inertia.h"
#include "fe-prep/mesh.h"
#include "fe-prep/reference_conditions.h"

namespace fc::feprep {

struct ImportedModel {
  Mesh mesh;                   // the nodes the DOF list names (SI), sets from the model's *NSET
  std::vector<long> labels;    // the source's label of each mesh node
  std::vector<char> solid;     // the node has translations only
  // (6 n, 6 n) SI, node-major body DOF: their lower triangles (column-major,
  // row >= column; read them through selfadjointView<Eigen::Lower>()), one copy
  // of each entry as a 1e6-DOF import needs.
  Eigen::SparseMatrix<double> K, M;
  std::vector<SolidFace> faces;  // the solid elements' boundary faces (mesh indices): distributing patch weights
  Mesh pairs;                  // mesh nodes with beams = the coupled node pairs (i <= j), for assemble()
  std::string storage_K, storage_M, indexing;  // what the readers found
  long source_dofs = 0;        // rows of the imported matrices
  // Rigid-body check: |K R| / (|K| |R|) for the six rigid motions (0 for a free model).
  double rigid_strain = 0.0;

  long pairCount() const { return static_cast<long>(pairs.beams.size()); }
  // The "element" e: a node pair's blocks (one node when i == j).
  void pairMatrices(long e, ElementResult& out) const;
};

// Reads, converts and checks the model; InputError (file, line, what) on any problem.
ImportedModel importMatrices(const MatricesSpec& spec);

// The rigid-body projection R^T M R of a mass matrix (6 n x 6 n, node-major):
// mass, first moment and the inertia about the origin (rotary terms included,
// exact for consistent and coupled masses); M's lower triangle is read (a
// full symmetric M gives the same). `misfit` receives the largest
// departure of the translational block from m I, relative to m.
struct MassProjection {
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_about_origin = Eigen::Matrix3d::Zero();
  double misfit = 0.0;
  Eigen::Vector3d centerOfMass() const { return first_moment / mass; }
};
MassProjection rigidMassProjection(const Eigen::MatrixXd& nodes, const Eigen::SparseMatrix<double>& M);

// Nodal masses for /mass/nodal (n, 4: mass, rotary x y z): the diagonal of M
// scaled to the body's mass (HRZ), then moved between nodes (mass_lumping.h) so
// that the mass, centre and inertia of the nodes equal the projection's.
// `applied` is false when no positive lumping reproduces them (the HRZ masses
// are kept; the body file then carries the exact values under /inertia/exact).
struct ImportedLumping {
  Eigen::MatrixXd nodal;  // (n, 4)
  bool applied = false;
  double min_ratio = 1.0;
};
ImportedLumping importedNodalMasses(const Eigen::MatrixXd& nodes, const Eigen::SparseMatrix<double>& M,
                                   const MassProjection& p);

// Removes from the map every reduced DOF that only moves rotations of solid
// nodes (they carry neither stiffness nor mass); DOF that also move a
// translation (a rigid patch's master) stay.
void holdSolidRotations(DofMap& map, const std::vector<char>& solid);

// The eigenvalues [(rad/time)^2] of CalculiX's *FREQUENCY table in a .dat file.
Eigen::VectorXd readCalculixEigenvalues(const std::string& path);

}  // namespace fc::feprep
