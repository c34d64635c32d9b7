#pragma once
// The whole fe-prep pipeline on one body: mesh (gmsh on rank 0, or a deck,
// a beam, imported matrices), reference conditions, assembly, modes,
// interface shapes and exact rigid properties, over the backend's linear
// algebra (la_backend.h: PETSc ranks, or one serial process). Every rank
// returns the same FlexBody; rank 0 writes.
#include <string>
#include <vector>

#include "common/flexbody.h"
#include "fe-prep/body_spec.h"
#include "fe-prep/mesh.h"
#include "fe-prep/reference_conditions.h"
#include "la_backend.h"

namespace fc::feprep {

struct StageStats {
  std::string stage;     // meshing, assembly, eigensolve
  double seconds = 0.0;  // wall time
  double cpu_seconds = 0.0;  // this process's CPU time (user + system, all threads)
  double peak_rss_mb = 0.0;  // this process's peak resident memory after the stage
  // MUMPS's own account of the stage's factorisation on this process (INFOG(21),
  // MiB; 0: none): the share of the peak that is the factor and its work space.
  double factorisation_mb = 0.0;
  std::string factor_library = "MUMPS";  // whose figure that is (the serial backend: MUMPS or CHOLMOD)
};

struct BuildResult {
  FlexBody body;
  long dofs = 0;          // unconstrained: 6 n_nodes
  long reduced_dofs = 0;  // after the reference conditions
  long rigid_removed = 0;
  long constraint_modes = 0, normal_modes = 0;  // reduction: craig_bampton
  long attachment_modes = 0;  // modes: {static_correction}: residual vectors kept (residual_flexibility.h)
  Eigen::VectorXd rigid_eigenvalues;
  double rigid_share_removed_min = 1.0, rigid_share_kept_max = 0.0;
  // The rigid motions were deflated from the eigen-solve (modal_solver.h), and
  // how near to null vectors of K they are (rigidNullResidual).
  bool rigid_deflated = false;
  double rigid_null_residual = 0.0;
  // Moment-consistent lumping (fe-prep/mass_lumping.h): applied, and the smallest
  // ratio of a corrected nodal mass to its row-sum value.
  bool moment_lumping = false;
  double lumping_min_ratio = 1.0;
  std::vector<StageStats> stages;
  // One line per shell or beam property: region, element count, mass, section
  // and material axis (printed by fe-prep).
  std::vector<std::string> regions;
};

struct BuildOptions {
  bool quiet = false;    // no progress lines
  double tolerance = 1e-10;
  // Held distributing patches as multipliers (the default) or eliminated
  // (reference_conditions.h); the same body to rounding, the elimination's K
  // carries a dense block per patch. Kept for the comparison test.
  PatchHold patch_hold = PatchHold::Multipliers;
  // Deflate the rigid motions from the eigen-solve where they are null
  // vectors of K (modal_solver.h); off solves for them as before. The same
  // body to the solver's tolerance; kept for the comparison test.
  bool deflate_rigid = true;
};

// This process's peak resident memory so far, MiB (getrusage).
double peakRssMb();

BuildResult buildFlexBody(Comm comm, const BodySpec& spec, const BuildOptions& options = {});

// The mesh of a body (rank 0 runs gmsh; the others receive it).
Mesh meshBody(Comm comm, const BodySpec& spec, bool quiet);

// Shapes of a point P rigidly attached to a node X: u_P = u + theta x (P - X), theta_P = theta.
// node_shapes (6 n_nodes, n_modes) node-major; returns (n_modes, 6).
Eigen::MatrixXd interfaceShapes(const Eigen::MatrixXd& node_shapes, long node, const Eigen::Vector3d& offset);

}  // namespace fc::feprep
