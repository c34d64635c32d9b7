#include "mbs-run/monitors/distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mbs-run/mechanics/force_elements.h"

namespace fc::mbs {

using Eigen::Vector3d;

double segmentSegmentDistance(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2, const Vector3d& q2) {
  // The contact elements' closest points (Ericson 5.1.9), one kernel for both.
  double s = 0.0, t = 0.0;
  closestSegmentPoints(p1, q1, p2, q2, s, t);
  return ((p1 + s * (q1 - p1)) - (p2 + t * (q2 - p2))).norm();
}

Vector3d closestPointOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  Vector3d bary;  // the contact element's kernel (Ericson 5.1.5)
  return closestTrianglePoint(p, a, b, c, bary);
}

double segmentTriangleDistance(const Vector3d& p, const Vector3d& q, const Vector3d& a, const Vector3d& b,
                               const Vector3d& c) {
  // The segment-against-surface contact's closest points (0 through the triangle).
  double s = 0.0;
  Vector3d bary;
  return closestSegmentTrianglePoints(p, q, a, b, c, s, bary);
}

Vector3d deformedVertex(const BodyGeometry& g, Eigen::Index k, const Eigen::VectorXd& w) {
  Vector3d x = g.vertices.col(k);
  if (g.modal_displacement.size() && w.size() == g.modal_displacement.cols())
    for (Eigen::Index j = 0; j < w.size(); ++j) x += g.modal_displacement.block<3, 1>(3 * k, j) * w[j];
  return x;
}

Vector3d placedVertex(const BodyGeometry& g, Eigen::Index k, const Vector3d& r, const Eigen::Matrix3d& A,
                      const Eigen::VectorXd& w) {
  return A * deformedVertex(g, k, w) + r;
}

Eigen::Matrix3Xd placedVertices(const BodyGeometry& g, const Vector3d& r, const Eigen::Matrix3d& A,
                                const Eigen::VectorXd& w) {
  Eigen::Matrix3Xd v(3, g.vertices.cols());
  for (Eigen::Index k = 0; k < v.cols(); ++k) v.col(k) = placedVertex(g, k, r, A, w);
  return v;
}

double geometryDistance(const BodyGeometry& ga, const Eigen::Matrix3Xd& va, const BodyGeometry& gb,
                        const Eigen::Matrix3Xd& vb) {
  double d = std::numeric_limits<double>::infinity();
  auto V = [](const Eigen::Matrix3Xd& v, int k) -> Vector3d { return v.col(k); };
  // Primitive lists; a geometry with neither segments nor triangles is its points.
  auto pointsOnly = [](const BodyGeometry& g) { return g.segments.empty() && g.triangles.empty(); };
  auto segOf = [&](const BodyGeometry& g, const Eigen::Matrix3Xd& v, std::vector<std::pair<Vector3d, Vector3d>>& out) {
    for (const auto& s : g.segments) out.emplace_back(V(v, s[0]), V(v, s[1]));
    if (pointsOnly(g))
      for (Eigen::Index k = 0; k < v.cols(); ++k) out.emplace_back(v.col(k), v.col(k));
  };
  std::vector<std::pair<Vector3d, Vector3d>> sa, sb;
  segOf(ga, va, sa);
  segOf(gb, vb, sb);
  for (const auto& x : sa)
    for (const auto& y : sb) d = std::min(d, segmentSegmentDistance(x.first, x.second, y.first, y.second));
  // Segments (and points) of one against the triangles of the other; the
  // triangles' edges as segments against the other's triangles (two
  // triangles' distance is attained on an edge of one of them).
  auto edgesOf = [&](const BodyGeometry& g, const Eigen::Matrix3Xd& v, std::vector<std::pair<Vector3d, Vector3d>>& out) {
    for (const auto& t : g.triangles)
      for (int e = 0; e < 3; ++e) out.emplace_back(V(v, t[e]), V(v, t[(e + 1) % 3]));
  };
  auto againstTriangles = [&](const std::vector<std::pair<Vector3d, Vector3d>>& segs, const BodyGeometry& g,
                              const Eigen::Matrix3Xd& v) {
    for (const auto& t : g.triangles)
      for (const auto& s : segs)
        d = std::min(d, segmentTriangleDistance(s.first, s.second, V(v, t[0]), V(v, t[1]), V(v, t[2])));
  };
  std::vector<std::pair<Vector3d, Vector3d>> ea = sa, eb = sb;
  edgesOf(ga, va, ea);
  edgesOf(gb, vb, eb);
  againstTriangles(ea, gb, vb);
  againstTriangles(eb, ga, va);
  return d;
}

BodyGeometry rodGeometry(double length) {
  BodyGeometry g;
  g.vertices.resize(3, 2);
  g.vertices.col(0) = Vector3d(-0.5 * length, 0, 0);
  g.vertices.col(1) = Vector3d(0.5 * length, 0, 0);
  g.segments.push_back({0, 1});
  return g;
}

BodyGeometry rectangleGeometry(double length, double width) {
  BodyGeometry g;
  g.vertices.resize(3, 4);
  const double a = 0.5 * length, b = 0.5 * width;
  g.vertices.col(0) = Vector3d(-a, -b, 0);
  g.vertices.col(1) = Vector3d(a, -b, 0);
  g.vertices.col(2) = Vector3d(a, b, 0);
  g.vertices.col(3) = Vector3d(-a, b, 0);
  g.triangles.push_back({0, 1, 2});
  g.triangles.push_back({0, 2, 3});
  return g;
}

}  // namespace fc::mbs
