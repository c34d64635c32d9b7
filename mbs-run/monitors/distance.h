#pragma once
// Contact monitor: the smallest distance between the geometry of two bodies
// (scene `outputs: {distances: [[B8, B3], ...]}`), reported per output row.
// Nothing pushes the bodies apart: it shows where the model lets parts pass
// through each other (the paper's Fig. 11, "trusses broke through the panel").
//
// Geometry, in body coordinates: points (vertices), segments (index pairs)
// and triangles (index triples). A rigid `rod` is its axis, a `plate` its
// mid-plane rectangle, a `rigid` body what its `geometry:` key gives; a
// flexible body is its mesh (beam elements as segments, shell triangles),
// each node moved by its modal displacement Phi_k w. Distances are between
// these idealisations (axes, mid-planes): two parts touch when the distance
// falls below the sum of their half-thicknesses (docs/mbs-run.md).
//
// Kernels: closest points of two segments and of a point and a triangle
// (Ericson, Real-Time Collision Detection, 2005, secs. 5.1.9 and 5.1.5);
// segment-triangle and triangle-triangle distances from those (zero when
// they intersect: a segment crossing a triangle is found by its plane test).
#include <Eigen/Dense>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace fc::mbs {

struct BodyGeometry {
  Eigen::Matrix3Xd vertices;  // body frame, undeformed
  std::vector<std::array<int, 2>> segments;
  std::vector<std::array<int, 3>> triangles;
  // Flexible bodies: modal displacement of each vertex, rows 3k..3k+2 (3 n, nm);
  // empty for rigid geometry.
  Eigen::MatrixXd modal_displacement;
  bool empty() const { return segments.empty() && triangles.empty() && vertices.cols() == 0; }
};

double segmentSegmentDistance(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                              const Eigen::Vector3d& q2);
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);
double segmentTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// Vertex k in the global frame for a body at (r, A) with modal coordinates w:
// A (x_k + sum_j Phi_kj w_j) + r, the sum in mode order (the broad phase,
// bounding_volume_tree.h, places single vertices with the same arithmetic).
Eigen::Vector3d placedVertex(const BodyGeometry& g, Eigen::Index k, const Eigen::Vector3d& r, const Eigen::Matrix3d& A,
                             const Eigen::VectorXd& w);
// Vertex k deformed, in the body frame: x_k + sum_j Phi_kj w_j (the first half of placedVertex).
Eigen::Vector3d deformedVertex(const BodyGeometry& g, Eigen::Index k, const Eigen::VectorXd& w);
// Every vertex placed (placedVertex).
Eigen::Matrix3Xd placedVertices(const BodyGeometry& g, const Eigen::Vector3d& r, const Eigen::Matrix3d& A,
                                const Eigen::VectorXd& w);
// Smallest distance between two placed geometries (isolated vertices count
// as points); infinity if either is empty. Every primitive against every
// other: the reference for treeDistance() (bounding_volume_tree.h), which the runs use.
double geometryDistance(const BodyGeometry& ga, const Eigen::Matrix3Xd& va, const BodyGeometry& gb,
                        const Eigen::Matrix3Xd& vb);

// Rod along body x (length L, centred) and plate in the body x-y plane
// (length along x, width along y, centred), as the scene's rod and plate bodies.
BodyGeometry rodGeometry(double length);
BodyGeometry rectangleGeometry(double length, double width);

}  // namespace fc::mbs
