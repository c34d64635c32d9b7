#pragma once
// What stress recovery needs of a meshed body (docs/stresses.md), computed by
// fe-prep with the modes and written to the body file (common/flexbody.h).
#include <Eigen/Dense>

#include <string>

#include "common/stress_data.h"
#include "fe-prep/body_spec.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

// The stress recovery data of a body with nodal shapes (6 n_nodes, n_modes):
// shells' centroid strains and ply table, beams' midpoint resultants and
// section basis, both for a body of both (docs/stresses.md, "Mixed bodies":
// centroids then hold the triangles' centroids followed by the beams'
// midpoints, as the body file's /mesh/centroids). Empty, with `note` saying
// why, when the shell regions' ply tables differ.
StressRecoveryData stressRecoveryData(const Mesh& mesh, const BodySpec& spec, const Eigen::MatrixXd& shapes, std::string& note);

}  // namespace fc::feprep
