#include "fe-prep/import/solid_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_set>

namespace fc::feprep {
namespace {

// Corner faces (1-based corner numbers, outward normal by the right-hand rule)
// and, for quadratic elements, the mid-side node of each corner edge; the
// numbering is CalculiX's and Abaqus's.
struct ElementFaces {
  std::vector<std::vector<int>> faces;
  std::map<std::pair<int, int>, int> mid;  // (a, b) with a < b -> mid-side node number
};

const ElementFaces* facesOf(const std::string& type) {
  static const ElementFaces hex8{{{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 8, 4}, {4, 8, 5, 1}}, {}};
  static const ElementFaces hex20{hex8.faces,
                                  {{{1, 2}, 9}, {{2, 3}, 10}, {{3, 4}, 11}, {{1, 4}, 12}, {{5, 6}, 13}, {{6, 7}, 14},
                                   {{7, 8}, 15}, {{5, 8}, 16}, {{1, 5}, 17}, {{2, 6}, 18}, {{3, 7}, 19}, {{4, 8}, 20}}};
  static const ElementFaces tet4{{{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}}, {}};
  static const ElementFaces tet10{tet4.faces, {{{1, 2}, 5}, {{2, 3}, 6}, {{1, 3}, 7}, {{1, 4}, 8}, {{2, 4}, 9}, {{3, 4}, 10}}};
  static const ElementFaces wedge6{{{1, 2, 3}, {4, 6, 5}, {1, 4, 5, 2}, {2, 5, 6, 3}, {3, 6, 4, 1}}, {}};
  static const ElementFaces wedge15{wedge6.faces,
                                    {{{1, 2}, 7}, {{2, 3}, 8}, {{1, 3}, 9}, {{4, 5}, 10}, {{5, 6}, 11}, {{4, 6}, 12},
                                     {{1, 4}, 13}, {{2, 5}, 14}, {{3, 6}, 15}}};
  static const std::map<std::string, const ElementFaces*> by_type = {
      {"C3D8", &hex8},    {"C3D8R", &hex8},    {"C3D8I", &hex8}, {"C3D20", &hex20}, {"C3D20R", &hex20},
      {"C3D4", &tet4},    {"C3D10", &tet10},   {"C3D10T", &tet10}, {"C3D6", &wedge6}, {"C3D15", &wedge15}};
  auto it = by_type.find(type);
  return it == by_type.end() ? nullptr : it->second;
}

// Shape functions of the face in its own coordinates: quad (xi, eta) in
// [-1, 1]^2, triangle area coordinates (r, s), t = 1 - r - s.
void faceShape(int corners, bool quadratic, double a, double b, Eigen::VectorXd& N, Eigen::MatrixXd& dN) {
  if (corners == 4) {
    static const double xs[4] = {-1, 1, 1, -1}, ys[4] = {-1, -1, 1, 1};
    N.resize(quadratic ? 8 : 4);
    dN.resize(N.size(), 2);
    for (int i = 0; i < 4; ++i) {
      const double x = xs[i], y = ys[i];
      if (!quadratic) {
        N(i) = 0.25 * (1 + x * a) * (1 + y * b);
        dN(i, 0) = 0.25 * x * (1 + y * b);
        dN(i, 1) = 0.25 * y * (1 + x * a);
      } else {
        N(i) = 0.25 * (1 + x * a) * (1 + y * b) * (x * a + y * b - 1);
        dN(i, 0) = 0.25 * x * (1 + y * b) * (2 * x * a + y * b);
        dN(i, 1) = 0.25 * y * (1 + x * a) * (x * a + 2 * y * b);
      }
    }
    if (quadratic) {
      // Mid-sides of edges 0-1 (eta = -1), 1-2 (xi = 1), 2-3 (eta = 1), 3-0 (xi = -1).
      const double ey[2] = {-1, 1}, ex[2] = {1, -1};
      for (int k = 0; k < 2; ++k) {
        const int i = 4 + 2 * k;  // edges 0-1 and 2-3
        N(i) = 0.5 * (1 - a * a) * (1 + ey[k] * b);
        dN(i, 0) = -a * (1 + ey[k] * b);
        dN(i, 1) = 0.5 * ey[k] * (1 - a * a);
        const int j = 5 + 2 * k;  // edges 1-2 and 3-0
        N(j) = 0.5 * (1 + ex[k] * a) * (1 - b * b);
        dN(j, 0) = 0.5 * ex[k] * (1 - b * b);
        dN(j, 1) = -b * (1 + ex[k] * a);
      }
    }
    return;
  }
  // Triangle: corners at (r, s) = (0, 0), (1, 0), (0, 1).
  const double L[3] = {1 - a - b, a, b};
  const double dL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
  N.resize(quadratic ? 6 : 3);
  dN.resize(N.size(), 2);
  for (int i = 0; i < 3; ++i)
    for (int d = 0; d < 2; ++d) {
      if (!quadratic) {
        N(i) = L[i];
        dN(i, d) = dL[i][d];
      } else {
        N(i) = L[i] * (2 * L[i] - 1);
        dN(i, d) = (4 * L[i] - 1) * dL[i][d];
      }
    }
  if (quadratic)
    for (int k = 0; k < 3; ++k) {  // mid-side of edge k-(k+1)
      const int p = k, q = (k + 1) % 3;
      N(3 + k) = 4 * L[p] * L[q];
      for (int d = 0; d < 2; ++d) dN(3 + k, d) = 4 * (dL[p][d] * L[q] + L[p] * dL[q][d]);
    }
}

}  // namespace

std::vector<SolidFace> boundaryFaces(const std::vector<SolidElement>& elements, const std::vector<long>& labels_sorted,
                                     const std::vector<long>& index_of_sorted) {
  auto index = [&](long label) {
    auto it = std::lower_bound(labels_sorted.begin(), labels_sorted.end(), label);
    return it != labels_sorted.end() && *it == label ? index_of_sorted[static_cast<std::size_t>(it - labels_sorted.begin())] : -1L;
  };
  std::map<std::vector<long>, std::pair<SolidFace, int>> seen;  // sorted corners -> face, count
  for (const SolidElement& e : elements) {
    const ElementFaces* ef = facesOf(e.type);
    if (!ef) continue;
    const bool quadratic = !ef->mid.empty();
    for (const auto& f : ef->faces) {
      SolidFace face;
      face.corners = static_cast<int>(f.size());
      bool ok = true;
      for (int c : f) face.nodes.push_back(index(e.nodes[static_cast<std::size_t>(c - 1)]));
      if (quadratic)
        for (std::size_t k = 0; k < f.size(); ++k) {
          const int a = f[k], b = f[(k + 1) % f.size()];
          face.nodes.push_back(index(e.nodes[static_cast<std::size_t>(ef->mid.at({std::min(a, b), std::max(a, b)}) - 1)]));
        }
      for (long n : face.nodes) ok = ok && n >= 0;
      if (!ok) continue;
      std::vector<long> key(face.nodes.begin(), face.nodes.begin() + face.corners);
      std::sort(key.begin(), key.end());
      auto& slot = seen[key];
      if (slot.second == 0) slot.first = face;
      ++slot.second;
    }
  }
  std::vector<SolidFace> out;
  for (auto& [key, v] : seen)
    if (v.second == 1) out.push_back(v.first);
  return out;
}

Eigen::VectorXd faceNodalAreas(const Eigen::MatrixXd& X, const SolidFace& face) {
  const bool quadratic = static_cast<int>(face.nodes.size()) > face.corners;
  // Quadrature: 3 x 3 Gauss on quads; Strang and Fix's 6-point degree-4 rule on
  // triangles (both exact for the shape functions times a flat face's constant
  // Jacobian; a curved quadratic face is integrated to the rule's accuracy).
  std::vector<std::array<double, 3>> q;
  if (face.corners == 4) {
    const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) q.push_back({g[i], g[j], w[i] * w[j]});
  } else {
    const double a = 0.445948490915965, wa = 0.223381589678011, b = 0.091576213509771, wb = 0.109951743655322;
    for (const auto& [x, w] : {std::pair{a, wa}, std::pair{b, wb}}) {
      q.push_back({x, x, 0.5 * w});
      q.push_back({1 - 2 * x, x, 0.5 * w});
      q.push_back({x, 1 - 2 * x, 0.5 * w});
    }
  }
  const long m = static_cast<long>(face.nodes.size());
  Eigen::MatrixXd P(3, m);
  for (long k = 0; k < m; ++k) P.col(k) = X.row(face.nodes[static_cast<std::size_t>(k)]).transpose();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(m), N;
  Eigen::MatrixXd dN;
  for (const auto& [a, b, w] : q) {
    faceShape(face.corners, quadratic, a, b, N, dN);
    const Eigen::Matrix<double, 3, 2> J = P * dN;
    out += N * (w * J.col(0).cross(J.col(1)).norm());
  }
  return out;
}

Eigen::VectorXd patchFaceWeights(const Eigen::MatrixXd& X, const std::vector<SolidFace>& faces, const std::vector<long>& patch,
                                 long* faces_used, double* area) {
  std::map<long, long> slot;
  for (std::size_t k = 0; k < patch.size(); ++k) slot[patch[k]] = static_cast<long>(k);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<long>(patch.size()));
  long used = 0;
  double total = 0.0;
  for (const SolidFace& f : faces) {
    if (!std::all_of(f.nodes.begin(), f.nodes.end(), [&](long n) { return slot.count(n) > 0; })) continue;
    const Eigen::VectorXd a = faceNodalAreas(X, f);
    for (std::size_t k = 0; k < f.nodes.size(); ++k) w(slot[f.nodes[k]]) += a(static_cast<long>(k));
    total += a.sum();
    ++used;
  }
  if (faces_used) *faces_used = used;
  if (area) *area = total;
  return w;
}

}  // namespace fc::feprep
