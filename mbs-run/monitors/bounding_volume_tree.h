#pragma once
// Broad phase of the contact monitor (distance.h): the same smallest distance
// as geometryDistance(), without testing every primitive of one body against
// every primitive of the other and without placing every mesh node.
//
// A bounding-volume hierarchy over a body's primitives (segments, or points
// for a geometry of points only, and triangles) is built once, in the body
// frame on the undeformed vertices. Each tree node also stores, per mode j,
// c_j = max over its vertices k of |Phi_kj| (the 3-vector of mode j at k), so
// that at a sample every vertex of the node lies within the node's undeformed
// box grown by delta = sum_j c_j |w_j| >= |Phi_k w| on every side. Boxes are
// compared in the body frame of the pair's larger tree (a panel's boxes stay
// thin slabs there, however the panel is turned); the other body's box is
// carried over as centre R c + t, half-extents |R| h, which holds its
// primitives. Two trees are descended together,
// nearer box pairs first; a pair of nodes whose boxes are farther apart than
// the best distance found so far is skipped, and only the leaves' primitive
// pairs that survive are measured by the exact kernels, after a last test of
// the two leaves' boxes taken from their deformed vertices (no deflection
// bound: a panel's leaf is then a slab as thin as its actual bending, so a
// truss lying parallel above it is not measured against every triangle
// within the bound of the minimum). Vertices are placed
// on demand (placedVertex(), the arithmetic of placedVertices()), once per
// sample per body.
//
// Exactness: a skipped pair's distance is at least its boxes' distance, which
// exceeds the final minimum by more than a margin (1e-12 of the bodies'
// extent) covering the rounding of the box arithmetic, so the minimum is the
// same kernel evaluation on the same arguments as the brute force's: equal
// bit for bit (tests/mbs-run/monitors/test_distance.cpp). A pair at distance 0 (a
// segment through a triangle) ends the search: no distance is smaller.
#include <Eigen/Dense>

#include <vector>

#include "mbs-run/monitors/distance.h"

namespace fc::mbs {

struct BoundingTree {
  struct Node {
    Eigen::Vector3d lo, hi;  // undeformed body-frame box of the node's primitives
    int left = -1, right = -1;  // children; -1 for a leaf
    int first = 0, count = 0;   // a leaf's pieces: items[first, first + count)
  };
  // A primitive, or for a long segment the part s0..s1 of it: the tree bounds
  // pieces (a diagonal truss's single box would cover a whole panel), the
  // kernels measure whole primitives (a primitive in several surviving
  // leaves is measured more than once, which leaves the minimum unchanged).
  struct Piece {
    int primitive = 0;
    double s0 = 0, s1 = 1;
  };
  std::vector<Piece> pieces;
  std::vector<Node> nodes;  // nodes[0] is the root (none for an empty geometry)
  // Primitive p < n_segments: segment p (point p for a geometry of points only);
  // otherwise triangle p - n_segments.
  std::vector<int> items;  // piece indices, in leaf order
  int n_segments = 0;
  bool points_only = false;
  // (modes, nodes): c_j of every node (empty for rigid geometry).
  Eigen::MatrixXd mode_bound;
};

BoundingTree buildBoundingTree(const BodyGeometry& g);

// One body's geometry at one configuration (r, A, w): vertices and node boxes
// computed on demand and kept for the other pairs of the same sample.
class PlacedGeometry {
 public:
  PlacedGeometry(const BodyGeometry& g, const BoundingTree& tree, const Eigen::Vector3d& r, const Eigen::Matrix3d& A,
                 const Eigen::VectorXd& w);
  const BodyGeometry& geometry() const { return g_; }
  const BoundingTree& tree() const { return tree_; }
  const Eigen::Vector3d& vertex(int k);       // global frame
  const Eigen::Vector3d& localVertex(int k);  // deformed, body frame
  // Body-frame box of leaf n's deformed pieces, from their vertices (exact, no deflection bound).
  void leafBox(int n, Eigen::Vector3d& centre, Eigen::Vector3d& half);
  // Body-frame box holding node n's deformed primitives (undeformed box grown by delta).
  void localBox(int n, Eigen::Vector3d& centre, Eigen::Vector3d& half);
  const Eigen::Vector3d& position() const { return r_; }
  const Eigen::Matrix3d& rotation() const { return A_; }
  double extent() const;  // size of the root box (for the rounding margin)

 private:
  const BodyGeometry& g_;
  const BoundingTree& tree_;
  Eigen::Vector3d r_;
  Eigen::Matrix3d A_;
  Eigen::VectorXd w_, absw_;
  bool modal_;
  std::vector<Eigen::Vector3d> v_, local_;
  Eigen::Matrix3Xd centre_, half_;
  std::vector<char> placed_, boxed_;
};

// Smallest distance between two placed geometries; equal to
// geometryDistance() on placedVertices() of the same configurations.
double treeDistance(PlacedGeometry& a, PlacedGeometry& b);

}  // namespace fc::mbs
