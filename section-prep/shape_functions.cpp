#include "section-prep/shape_functions.h"

#include <cmath>
#include <vector>

namespace fc::section {

namespace {

ShapeValues quadShape(const std::array<bool, 9>& p, double r, double s) {
  ShapeValues v;
  auto& N = v.N;
  auto& Nr = v.dNdr;
  auto& Ns = v.dNds;
  // Bilinear corners first; mid-side and centre functions then subtract their
  // share so that every function is 1 at its own node and 0 at the others.
  const double cr[4] = {-1, 1, 1, -1}, cs[4] = {-1, -1, 1, 1};
  for (int k = 0; k < 4; ++k) {
    N[k] = 0.25 * (1 + cr[k] * r) * (1 + cs[k] * s);
    Nr[k] = 0.25 * cr[k] * (1 + cs[k] * s);
    Ns[k] = 0.25 * cs[k] * (1 + cr[k] * r);
  }
  if (p[8]) {
    N[8] = (1 - r * r) * (1 - s * s);
    Nr[8] = -2 * r * (1 - s * s);
    Ns[8] = -2 * s * (1 - r * r);
  }
  // Mid-sides: 4 at s=-1, 5 at r=+1, 6 at s=+1, 7 at r=-1.
  if (p[4]) { N[4] = 0.5 * (1 - r * r) * (1 - s); Nr[4] = -r * (1 - s); Ns[4] = -0.5 * (1 - r * r); }
  if (p[5]) { N[5] = 0.5 * (1 + r) * (1 - s * s); Nr[5] = 0.5 * (1 - s * s); Ns[5] = -(1 + r) * s; }
  if (p[6]) { N[6] = 0.5 * (1 - r * r) * (1 + s); Nr[6] = -r * (1 + s); Ns[6] = 0.5 * (1 - r * r); }
  if (p[7]) { N[7] = 0.5 * (1 - r) * (1 - s * s); Nr[7] = -0.5 * (1 - s * s); Ns[7] = -(1 - r) * s; }
  if (p[8]) {
    for (int k = 4; k < 8; ++k) {
      if (!p[k]) continue;
      N[k] -= 0.5 * N[8]; Nr[k] -= 0.5 * Nr[8]; Ns[k] -= 0.5 * Ns[8];
    }
  }
  // Corner k touches the mid-sides before and after it.
  const int side_a[4] = {4, 4, 5, 6}, side_b[4] = {7, 5, 6, 7};
  for (int k = 0; k < 4; ++k) {
    for (int m : {side_a[k], side_b[k]}) {
      if (!p[m]) continue;
      N[k] -= 0.5 * N[m]; Nr[k] -= 0.5 * Nr[m]; Ns[k] -= 0.5 * Ns[m];
    }
    if (p[8]) { N[k] -= 0.25 * N[8]; Nr[k] -= 0.25 * Nr[8]; Ns[k] -= 0.25 * Ns[8]; }
  }
  return v;
}

ShapeValues triShape(const std::array<bool, 9>& p, double r, double s) {
  ShapeValues v;
  auto& N = v.N;
  auto& Nr = v.dNdr;
  auto& Ns = v.dNds;
  const double L[3] = {1 - r - s, r, s};
  const double Lr[3] = {-1, 1, 0}, Ls[3] = {-1, 0, 1};
  for (int k = 0; k < 3; ++k) { N[k] = L[k]; Nr[k] = Lr[k]; Ns[k] = Ls[k]; }
  // Mid-side slot 4+k joins corners k and k+1.
  for (int k = 0; k < 3; ++k) {
    const int m = 4 + k, a = k, b = (k + 1) % 3;
    if (!p[m]) continue;
    N[m] = 4 * L[a] * L[b];
    Nr[m] = 4 * (Lr[a] * L[b] + L[a] * Lr[b]);
    Ns[m] = 4 * (Ls[a] * L[b] + L[a] * Ls[b]);
    for (int c : {a, b}) { N[c] -= 0.5 * N[m]; Nr[c] -= 0.5 * Nr[m]; Ns[c] -= 0.5 * Ns[m]; }
  }
  return v;
}

std::vector<QuadraturePoint> gaussSquare(int n) {
  std::vector<double> x, w;
  if (n == 2) {
    x = {-1 / std::sqrt(3.0), 1 / std::sqrt(3.0)};
    w = {1.0, 1.0};
  } else if (n == 3) {
    x = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    w = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  } else {
    const double a = std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(1.2));
    const double b = std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(1.2));
    const double wa = (18 + std::sqrt(30.0)) / 36, wb = (18 - std::sqrt(30.0)) / 36;
    x = {-b, -a, a, b};
    w = {wb, wa, wa, wb};
  }
  std::vector<QuadraturePoint> q;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) q.push_back({x[i], x[j], w[i] * w[j]});
  return q;
}

std::vector<QuadraturePoint> triangle7() {
  // Degree-5 rule (Strang & Fix 1973, table 4.1; Dunavant 1985), weights
  // summing to the reference area 1/2.
  const double a1 = 0.059715871789770, b1 = 0.470142064105115;
  const double a2 = 0.797426985353087, b2 = 0.101286507323456;
  const double w0 = 0.225, w1 = 0.132394152788506, w2 = 0.125939180544827;
  std::vector<QuadraturePoint> q;
  q.push_back({1.0 / 3, 1.0 / 3, 0.5 * w0});
  const double p1[3][2] = {{a1, b1}, {b1, a1}, {b1, b1}};
  const double p2[3][2] = {{a2, b2}, {b2, a2}, {b2, b2}};
  for (auto& p : p1) q.push_back({p[0], p[1], 0.5 * w1});
  for (auto& p : p2) q.push_back({p[0], p[1], 0.5 * w2});
  return q;
}

}  // namespace

ShapeValues shapeFunctions(ElementShape shape, const std::array<bool, 9>& present, double r,
                           double s) {
  return shape == ElementShape::Quadrilateral ? quadShape(present, r, s)
                                              : triShape(present, r, s);
}

const std::vector<QuadraturePoint>& quadratureRule(ElementShape shape, int node_count) {
  static const std::vector<QuadraturePoint> q2 = gaussSquare(2), q3 = gaussSquare(3), q4 = gaussSquare(4),
                                            t7 = triangle7();
  if (shape == ElementShape::Triangle) return t7;
  return node_count <= 4 ? q2 : q3;
}

}  // namespace fc::section
