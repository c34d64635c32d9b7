#include "mbs-run/monitors/bounding_volume_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace fc::mbs {

using Eigen::Vector3d;

namespace {

constexpr int kLeafSize = 4;  // pieces per leaf: below ~4 the tree's own boxes cost more than the kernels
// Segments longer than 1/32 of the geometry's extent are bounded in pieces of
// about that length (at most 64 per segment).
constexpr double kPieceFraction = 1.0 / 32;
constexpr int kMaxPieces = 64;

// Vertex indices of primitive p (two for a segment, one repeated for a point, three for a triangle).
int primitiveVertices(const BodyGeometry& g, const BoundingTree& t, int p, std::array<int, 3>& v) {
  if (p < t.n_segments) {
    if (t.points_only) {
      v = {p, p, p};
      return 1;
    }
    v = {g.segments[p][0], g.segments[p][1], g.segments[p][1]};
    return 2;
  }
  const auto& tri = g.triangles[p - t.n_segments];
  v = {tri[0], tri[1], tri[2]};
  return 3;
}

// Undeformed corner points of a piece (its ends for a segment part).
int pieceCorners(const BodyGeometry& g, const BoundingTree& t, const BoundingTree::Piece& pc, std::array<Vector3d, 3>& x) {
  std::array<int, 3> v;
  const int nv = primitiveVertices(g, t, pc.primitive, v);
  if (nv == 2) {
    const Vector3d p = g.vertices.col(v[0]), q = g.vertices.col(v[1]);
    x[0] = p + pc.s0 * (q - p);
    x[1] = p + pc.s1 * (q - p);
    return 2;
  }
  for (int k = 0; k < nv; ++k) x[k] = g.vertices.col(v[k]);
  return nv;
}

struct Builder {
  const BodyGeometry& g;
  BoundingTree& t;
  std::vector<Vector3d> centre;

  int build(int first, int count) {
    const int n = int(t.nodes.size());
    t.nodes.emplace_back();
    Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    Vector3d clo = lo, chi = hi;
    for (int i = first; i < first + count; ++i) {
      std::array<Vector3d, 3> x;
      const int nx = pieceCorners(g, t, t.pieces[t.items[i]], x);
      for (int k = 0; k < nx; ++k) {
        lo = lo.cwiseMin(x[k]);
        hi = hi.cwiseMax(x[k]);
      }
      clo = clo.cwiseMin(centre[t.items[i]]);
      chi = chi.cwiseMax(centre[t.items[i]]);
    }
    t.nodes[n].lo = lo;
    t.nodes[n].hi = hi;
    if (count <= kLeafSize) {
      t.nodes[n].first = first;
      t.nodes[n].count = count;
      return n;
    }
    // Median split along the longest axis of the primitives' centres.
    int axis;
    (chi - clo).maxCoeff(&axis);
    const int half = count / 2;
    std::nth_element(t.items.begin() + first, t.items.begin() + first + half, t.items.begin() + first + count,
                     [&](int a, int b) { return centre[a][axis] < centre[b][axis]; });
    const int left = build(first, half);
    const int right = build(first + half, count - half);
    t.nodes[n].left = left;
    t.nodes[n].right = right;
    return n;
  }

  // c_j of node n and its subtree (children before parents).
  void bound(int n) {
    BoundingTree::Node& node = t.nodes[n];
    if (node.left >= 0) {
      bound(node.left);
      bound(node.right);
      t.mode_bound.col(n) = t.mode_bound.col(node.left).cwiseMax(t.mode_bound.col(node.right));
      return;
    }
    t.mode_bound.col(n).setZero();
    for (int i = node.first; i < node.first + node.count; ++i) {
      std::array<int, 3> v;
      const int nv = primitiveVertices(g, t, t.pieces[t.items[i]].primitive, v);
      for (int k = 0; k < nv; ++k)
        for (Eigen::Index j = 0; j < t.mode_bound.rows(); ++j)
          t.mode_bound(j, n) =
              std::max(t.mode_bound(j, n), g.modal_displacement.block<3, 1>(3 * Eigen::Index(v[k]), j).norm());
    }
  }
};

double boxDistance(const Vector3d& ca, const Vector3d& ha, const Vector3d& cb, const Vector3d& hb) {
  const Vector3d gap = ((cb - ca).cwiseAbs() - ha - hb).cwiseMax(0.0);
  return gap.norm();
}

struct Search {
  PlacedGeometry &a, &b;
  const BodyGeometry &ga, &gb;
  const BoundingTree &ta, &tb;
  double margin;
  // Boxes are compared in the frame of a (in_a) or of b; R, t carry the other
  // body's body-frame coordinates into it.
  bool in_a;
  Eigen::Matrix3d R, absR;
  Vector3d t;
  double best = std::numeric_limits<double>::infinity();

  Search(PlacedGeometry& pa, PlacedGeometry& pb)
      : a(pa), b(pb), ga(pa.geometry()), gb(pb.geometry()), ta(pa.tree()), tb(pb.tree()),
        // Rounding of the box arithmetic is ~1e-16 of the coordinates; 1e-12
        // of the bodies' extent and position keeps every skip safe.
        margin(1e-12 * (pa.extent() + pb.extent())), in_a(ta.nodes.size() >= tb.nodes.size()) {
    PlacedGeometry &f = in_a ? a : b, &o = in_a ? b : a;
    R = f.rotation().transpose() * o.rotation();
    absR = R.cwiseAbs();
    t = f.rotation().transpose() * (o.position() - f.position());
  }

  double nodeDistance(int na, int nb) {
    Vector3d ca, ha, cb, hb;
    a.localBox(na, ca, ha);
    b.localBox(nb, cb, hb);
    if (in_a) return boxDistance(ca, ha, R * cb + t, absR * hb);
    return boxDistance(R * ca + t, absR * ha, cb, hb);
  }

  // The primitive pairs of geometryDistance(): segments (points) against
  // segments, segments against triangles either way, and two triangles by
  // each one's edges against the other (same kernels, same argument order).
  void measure(int pa, int pb) {
    std::array<int, 3> va, vb;
    const int na = primitiveVertices(ga, ta, pa, va), nb = primitiveVertices(gb, tb, pb, vb);
    auto A = [&](int k) -> const Vector3d& { return a.vertex(va[k]); };
    auto B = [&](int k) -> const Vector3d& { return b.vertex(vb[k]); };
    double d = best;
    if (na < 3 && nb < 3) {
      d = std::min(d, segmentSegmentDistance(A(0), A(1), B(0), B(1)));
    } else if (na < 3) {
      d = std::min(d, segmentTriangleDistance(A(0), A(1), B(0), B(1), B(2)));
    } else if (nb < 3) {
      d = std::min(d, segmentTriangleDistance(B(0), B(1), A(0), A(1), A(2)));
    } else {
      for (int e = 0; e < 3; ++e) d = std::min(d, segmentTriangleDistance(A(e), A((e + 1) % 3), B(0), B(1), B(2)));
      for (int e = 0; e < 3; ++e) d = std::min(d, segmentTriangleDistance(B(e), B((e + 1) % 3), A(0), A(1), A(2)));
    }
    best = d;
  }

  void visit(int na, int nb, double lower) {
    if (lower > best + margin || best == 0.0) return;
    const BoundingTree::Node &x = ta.nodes[na], &y = tb.nodes[nb];
    const bool leaf_a = x.left < 0, leaf_b = y.left < 0;
    if (leaf_a && leaf_b) {
      Vector3d ca, ha, cb, hb;
      a.leafBox(na, ca, ha);
      b.leafBox(nb, cb, hb);
      const double exact = in_a ? boxDistance(ca, ha, R * cb + t, absR * hb) : boxDistance(R * ca + t, absR * ha, cb, hb);
      if (exact > best + margin) return;
      for (int i = x.first; i < x.first + x.count; ++i)
        for (int j = y.first; j < y.first + y.count; ++j)
          measure(ta.pieces[ta.items[i]].primitive, tb.pieces[tb.items[j]].primitive);
      return;
    }
    // Descend the node with more primitives' extent (the larger box), nearer child first.
    const bool split_a = !leaf_a && (leaf_b || (x.hi - x.lo).squaredNorm() >= (y.hi - y.lo).squaredNorm());
    const int c1 = split_a ? x.left : y.left, c2 = split_a ? x.right : y.right;
    const double d1 = split_a ? nodeDistance(c1, nb) : nodeDistance(na, c1);
    const double d2 = split_a ? nodeDistance(c2, nb) : nodeDistance(na, c2);
    const bool first1 = d1 <= d2;
    const int n1 = first1 ? c1 : c2, n2 = first1 ? c2 : c1;
    const double l1 = first1 ? d1 : d2, l2 = first1 ? d2 : d1;
    if (split_a) {
      visit(n1, nb, l1);
      visit(n2, nb, l2);
    } else {
      visit(na, n1, l1);
      visit(na, n2, l2);
    }
  }
};

}  // namespace

BoundingTree buildBoundingTree(const BodyGeometry& g) {
  BoundingTree t;
  t.points_only = g.segments.empty() && g.triangles.empty();
  t.n_segments = t.points_only ? int(g.vertices.cols()) : int(g.segments.size());
  const int n = t.n_segments + int(g.triangles.size());
  if (n == 0) return t;
  Eigen::Vector3d glo = g.vertices.rowwise().minCoeff(), ghi = g.vertices.rowwise().maxCoeff();
  const double piece = kPieceFraction * (ghi - glo).norm();
  for (int p = 0; p < n; ++p) {
    std::array<int, 3> v;
    int parts = 1;
    if (primitiveVertices(g, t, p, v) == 2 && piece > 0)
      parts = std::clamp(int(std::ceil((g.vertices.col(v[1]) - g.vertices.col(v[0])).norm() / piece)), 1, kMaxPieces);
    for (int k = 0; k < parts; ++k) t.pieces.push_back({p, double(k) / parts, double(k + 1) / parts});
  }
  const int np = int(t.pieces.size());
  t.items.resize(np);
  std::iota(t.items.begin(), t.items.end(), 0);
  Builder b{g, t, std::vector<Vector3d>(np)};
  for (int p = 0; p < np; ++p) {
    std::array<Vector3d, 3> x;
    const int nx = pieceCorners(g, t, t.pieces[p], x);
    Vector3d c = Vector3d::Zero();
    for (int k = 0; k < nx; ++k) c += x[k];
    b.centre[p] = c / nx;
  }
  b.build(0, np);
  if (g.modal_displacement.size()) {
    t.mode_bound.resize(g.modal_displacement.cols(), Eigen::Index(t.nodes.size()));
    b.bound(0);
  }
  return t;
}

PlacedGeometry::PlacedGeometry(const BodyGeometry& g, const BoundingTree& tree, const Vector3d& r,
                               const Eigen::Matrix3d& A, const Eigen::VectorXd& w)
    : g_(g), tree_(tree), r_(r), A_(A), w_(w), absw_(w.cwiseAbs()),
      modal_(g.modal_displacement.size() && w.size() == g.modal_displacement.cols() && tree.mode_bound.size()),
      v_(g.vertices.cols()), local_(g.vertices.cols()), centre_(3, tree.nodes.size()), half_(3, tree.nodes.size()),
      placed_(g.vertices.cols(), 0), boxed_(tree.nodes.size(), 0) {}

const Vector3d& PlacedGeometry::localVertex(int k) {
  if (!placed_[k]) {
    // placedVertex's arithmetic, its two halves kept.
    local_[k] = deformedVertex(g_, k, w_);
    v_[k] = A_ * local_[k] + r_;
    placed_[k] = 1;
  }
  return local_[k];
}

const Vector3d& PlacedGeometry::vertex(int k) {
  localVertex(k);
  return v_[k];
}

void PlacedGeometry::leafBox(int n, Vector3d& centre, Vector3d& half) {
  const BoundingTree::Node& node = tree_.nodes[n];
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = node.first; i < node.first + node.count; ++i) {
    const BoundingTree::Piece& pc = tree_.pieces[tree_.items[i]];
    std::array<int, 3> v;
    const int nv = primitiveVertices(g_, tree_, pc.primitive, v);
    if (nv == 2) {  // the piece s0..s1 of the deformed segment
      const Vector3d p = localVertex(v[0]), q = localVertex(v[1]);
      for (const double s : {pc.s0, pc.s1}) {
        const Vector3d x = p + s * (q - p);
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
    } else {
      for (int k = 0; k < nv; ++k) {
        lo = lo.cwiseMin(localVertex(v[k]));
        hi = hi.cwiseMax(localVertex(v[k]));
      }
    }
  }
  centre = 0.5 * (lo + hi);
  half = 0.5 * (hi - lo);
}

void PlacedGeometry::localBox(int n, Vector3d& centre, Vector3d& half) {
  if (!boxed_[n]) {
    const BoundingTree::Node& node = tree_.nodes[n];
    const double delta = modal_ ? tree_.mode_bound.col(n).dot(absw_) : 0.0;
    centre_.col(n) = 0.5 * (node.lo + node.hi);
    half_.col(n) = 0.5 * (node.hi - node.lo) + Vector3d::Constant(delta);
    boxed_[n] = 1;
  }
  centre = centre_.col(n);
  half = half_.col(n);
}

double PlacedGeometry::extent() const {
  if (tree_.nodes.empty()) return 0.0;
  const double delta = modal_ ? tree_.mode_bound.col(0).dot(absw_) : 0.0;
  return (tree_.nodes[0].hi - tree_.nodes[0].lo).norm() + 2 * delta + r_.norm();
}

double treeDistance(PlacedGeometry& a, PlacedGeometry& b) {
  const BoundingTree &ta = a.tree(), &tb = b.tree();
  if (ta.nodes.empty() || tb.nodes.empty()) return std::numeric_limits<double>::infinity();
  Search s(a, b);
  s.visit(0, 0, s.nodeDistance(0, 0));
  return s.best;
}

}  // namespace fc::mbs
