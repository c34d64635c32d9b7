#pragma once
// The surface of an imported solid model, for the weights of distributing
// (RBE3) patches (docs/fe-prep.md, "Distributing patches on imported solids").
// A node's weight is its share of the patch's area as the element faces carry
// it: w_i = integral over the patch faces of N_i dA, N_i the face's own shape
// function (bilinear quad4, serendipity quad8, linear tri3, quadratic tri6).
// These are the consistent nodal loads of a uniform unit traction on the
// patch, and CalculiX's *COUPLING + *DISTRIBUTING takes the same weights: on
// the fitting of tests/data/import (C3D20R) its distributed loads and this
// fit give the same reference compliances to its 7 printed digits. For
// quadratic faces the corner weights are negative (quad8: -A/12 on a flat
// rectangle, mid-sides A/3) or zero (tri6 corners); the fit's A = sum w_i
// G_i^T G_i is still the exact integral of G^T G over flat faces, so positive
// definite. Other weights move the patch's centroid and second moments: with
// the nodes weighed equally the fitting's reference compliances move by up to
// 58 % (measured, docs/fe-prep.md).
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace fc::feprep {

// A solid element of the model: its type (C3D8, C3D20R, ...) and node labels
// in the CalculiX/Abaqus order.
struct SolidElement {
  std::string type;
  std::vector<long> nodes;
};

// A face of a solid element: corners (3 or 4) first, then the mid-side nodes
// of edges corner 0-1, 1-2, ... (quadratic elements); mesh node indices.
struct SolidFace {
  std::vector<long> nodes;
  int corners = 0;
};

// The faces of the elements that no other element shares (the model's
// surface); `index` maps a node label to its mesh index (-1: the node is not
// in the model, the face is skipped).
std::vector<SolidFace> boundaryFaces(const std::vector<SolidElement>& elements, const std::vector<long>& labels_sorted,
                                     const std::vector<long>& index_of_sorted);

// integral of N_i dA over one face (quadrature exact for flat faces).
Eigen::VectorXd faceNodalAreas(const Eigen::MatrixXd& nodes, const SolidFace& face);

// The weights of a patch (aligned with `patch`): the face integrals of every
// boundary face whose nodes all belong to the patch; nodes on none of them
// (interior nodes of a `within:` sphere, the rim of a box) weigh 0.
// `faces_used` and `area` receive how many faces and how much area.
Eigen::VectorXd patchFaceWeights(const Eigen::MatrixXd& nodes, const std::vector<SolidFace>& faces,
                                 const std::vector<long>& patch, long* faces_used = nullptr, double* area = nullptr);

}  // namespace fc::feprep
