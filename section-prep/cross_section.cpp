#include "section-prep/cross_section.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#ifdef FLEXCOMP_SECTION_CHOLMOD
#include <Eigen/CholmodSupport>
#endif
#include <algorithm>
#include <ctime>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/input.h"
#include "section-prep/material_frame.h"
#ifdef FLEXCOMP_SECTION_EIGEN_BLAS
#include "section-prep/dense_kernels.h"
#endif
#include "section-prep/shape_functions.h"
#include "section-prep/sparse_pattern.h"

namespace fc::section {

namespace {

constexpr double kDegree = M_PI / 180.0;
using MatE = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 27, 27>;
using Mat4 = Eigen::Matrix<double, Eigen::Dynamic, 4, 0, 27, 4>;
using Matrix64d = Eigen::Matrix<double, 6, 4>;
using DenseN4 = Eigen::Matrix<double, Eigen::Dynamic, 4>;

// The discretised energy of Hodges (2006), ch. 4, with the warping w = S V:
//   2U = V'E V + 2 V'Dhe e + e'Dee e + 2 V'Dhl V' + 2 V''Dle e + V''Dll V'
// (primes on V: d/dx1), e = [gamma11, kappa1, kappa2, kappa3].
struct Assembled {
  Eigen::SparseMatrix<double> E;
  DenseN4 Dhe, Dle, HPsi, Psi;
  Eigen::Matrix4d Dee = Eigen::Matrix4d::Zero();
  double area = 0, mu = 0;
  Eigen::Vector2d first_area = Eigen::Vector2d::Zero(), first_mass = Eigen::Vector2d::Zero();
  Eigen::Matrix2d second_mass = Eigen::Matrix2d::Zero();
};

struct ElementNodes {
  int count = 0;
  std::array<int, 9> slot{}, node{};
  std::array<bool, 9> present{};
};

ElementNodes elementNodes(const SectionElement& e) {
  ElementNodes en;
  for (int k = 0; k < 9; ++k) {
    en.present[k] = e.nodes[k] >= 0;
    if (en.present[k]) {
      en.slot[en.count] = k;
      en.node[en.count] = e.nodes[k];
      ++en.count;
    }
  }
  return en;
}

// An error about one element: located at its line when it came from a file.
[[noreturn]] void elementError(const SectionMesh& mesh, const SectionElement& e, const std::string& msg) {
  if (!mesh.source_file.empty() && e.source_line > 0)
    throw InputError(mesh.source_file, e.source_line, 0, "element " + std::to_string(e.user_id), msg);
  throw std::runtime_error("element " + std::to_string(e.user_id) + ": " + msg);
}

void checkMesh(const SectionMesh& mesh) {
  const long nn = static_cast<long>(mesh.nodes.size());
  if (mesh.elements.empty()) throw std::runtime_error("the section mesh has no elements");
  for (const auto& m : mesh.materials) {
    const std::string why = materialProblem(m);
    if (!why.empty()) {
      if (!mesh.source_file.empty()) throw InputError(mesh.source_file, 0, 0, m.name, why);
      throw std::runtime_error("material '" + m.name + "': " + why);
    }
  }
  for (const auto& e : mesh.elements) {
    for (int n : e.nodes)
      if (n >= nn) elementError(mesh, e, "node index out of range");
    const int corners = e.shape == ElementShape::Triangle ? 3 : 4;
    for (int k = 0; k < corners; ++k)
      if (e.nodes[k] < 0) elementError(mesh, e, "a corner node is missing");
    if (e.shape == ElementShape::Triangle && (e.nodes[3] >= 0 || e.nodes[7] >= 0 || e.nodes[8] >= 0))
      elementError(mesh, e, "a triangle uses node slots 1-3 and 5-7 only");
    if (e.material < 0 || e.material >= static_cast<int>(mesh.materials.size()))
      elementError(mesh, e, "material index out of range");
  }
}

// Geometry every element must have, whatever mesh it came from. Each defect below
// leaves the warping problem solvable and the answer silently wrong:
// - a positive area (corners at one place or on one line);
// - a Jacobian of one sign over the element: a misplaced mid-side node or corners
//   given in bow-tie order fold the element over itself;
// - neighbours on opposite sides of each shared corner edge: a node moved across an
//   edge, or an element given twice, makes two elements overlap.
// A whole element numbered clockwise is not a defect: the integrals use |det J|.
void checkElementGeometry(const SectionMesh& mesh) {
  const auto located = [&](const SectionElement& e) {
    return "element " + std::to_string(e.user_id) +
           (e.source_line > 0 ? " (line " + std::to_string(e.source_line) + ")" : std::string());
  };
  // Corner edge (lower node, higher node) -> the element on it and the side its interior is on.
  std::map<std::pair<int, int>, std::pair<const SectionElement*, int>> edges;
  for (const SectionElement& e : mesh.elements) {
    const int corners = e.shape == ElementShape::Triangle ? 3 : 4;
    double size = 0, twice_area = 0;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (int k = 0; k < corners; ++k) {
      const Eigen::Vector2d& a = mesh.nodes[e.nodes[k]];
      const Eigen::Vector2d& b = mesh.nodes[e.nodes[(k + 1) % corners]];
      size = std::max(size, (b - a).norm());
      twice_area += a.x() * b.y() - b.x() * a.y();
      centroid += a / corners;
    }
    if (!(std::abs(twice_area) > 1e-12 * size * size))
      elementError(mesh, e, "has zero area (its corners are at one place or on one line); expected "
                            "corners around a positive area, in order");
    const double orientation = twice_area > 0 ? 1.0 : -1.0;

    const ElementNodes en = elementNodes(e);
    std::vector<std::pair<double, double>> points;
    for (const auto& q : quadratureRule(e.shape, en.count)) points.emplace_back(q.r, q.s);
    const std::size_t n_inner = points.size();
    if (e.shape == ElementShape::Triangle)
      points.insert(points.end(), {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}});
    else
      points.insert(points.end(), {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}});
    for (std::size_t i = 0; i < points.size(); ++i) {
      const ShapeValues sv = shapeFunctions(e.shape, en.present, points[i].first, points[i].second);
      Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
      for (int a = 0; a < en.count; ++a) {
        const int k = en.slot[a];
        J.row(0) += sv.dNdr[k] * mesh.nodes[en.node[a]].transpose();
        J.row(1) += sv.dNds[k] * mesh.nodes[en.node[a]].transpose();
      }
      // Inside: strictly the corner polygon's sign. At a corner, 0 is allowed (a
      // quadrilateral with a straight angle there, or collapsed to a triangle).
      const double det = orientation * J.determinant();
      const double floor = i < n_inner ? 0.0 : -1e-12 * size * size;
      if (!(det > floor))
        elementError(mesh, e, "is folded over itself (its Jacobian changes sign inside it): expected "
                              "the corners in order around the element and each mid-side node "
                              "between its two corners");
    }

    for (int k = 0; k < corners; ++k) {
      const int a = e.nodes[k], b = e.nodes[(k + 1) % corners];
      if (a == b) continue;  // a quadrilateral collapsed to a triangle
      const Eigen::Vector2d d = mesh.nodes[b] - mesh.nodes[a], c = centroid - mesh.nodes[a];
      const int side = (d.x() * c.y() - d.y() * c.x() > 0) == (a < b) ? 1 : -1;
      const auto [it, first] = edges.emplace(std::make_pair(std::min(a, b), std::max(a, b)), std::make_pair(&e, side));
      if (first) continue;
      if (it->second.second == side)
        elementError(mesh, e, "overlaps " + located(*it->second.first) +
                                  ": both lie on the same side of their common edge (a node "
                                  "across an edge, or one element given twice); expected "
                                  "neighbours on opposite sides of a shared edge");
      if (it->second.second == 0)
        elementError(mesh, e, "shares an edge with two other elements; expected at most two "
                              "elements on an edge");
      it->second.second = 0;  // both sides taken
    }
  }
}

// One connected body, else E has more than the four rigid modes in its kernel.
void checkConnected(const SparsePattern& p, long n_nodes, const std::vector<char>& used) {
  std::vector<char> seen(n_nodes, 0);
  long start = -1, n_used = 0;
  for (long i = 0; i < n_nodes; ++i)
    if (used[i]) { ++n_used; if (start < 0) start = i; }
  std::vector<long> stack{start};
  seen[start] = 1;
  long reached = 1;
  while (!stack.empty()) {
    const long a = stack.back();
    stack.pop_back();
    for (int b : p.neighbours(a))
      if (!seen[b]) { seen[b] = 1; ++reached; stack.push_back(b); }
  }
  if (reached != n_used)
    throw std::runtime_error("the section is not one connected body (" +
                             std::to_string(n_used - reached) +
                             " nodes are not connected to the rest); "
                             "join the parts or analyse them separately");
}

// Strains in Voigt order [11, 22, 33, 23, 13, 12] (Hodges 2006, ch. 4):
//   Gamma = Gamma_h w + Gamma_e e + Gamma_l w',   w = sum_a N_a V_a,
// Gamma_h w at node a = (dN_a/dx2) P2 V_a + (dN_a/dx3) P3 V_a,  Gamma_l w' = N_a PL V_a',
// Gamma_e = G0 + x2 G2 + x3 G3, with the constant selection matrices below:
//   2Gamma12 = dw1/dx2 - x3 k1 + w2',  2Gamma13 = dw1/dx3 + x2 k1 + w3',
//   Gamma22 = dw2/dx2, Gamma33 = dw3/dx3, 2Gamma23 = dw2/dx3 + dw3/dx2,
//   Gamma11 = g11 + x3 k2 - x2 k3 + w1'.
// Writing the element matrices through these keeps the per-point work to
// scalar products of shape functions (the 27x27 products would cost 10x more).
struct Selections {
  Eigen::Matrix<double, 6, 3> P2, P3, PL;
  Matrix64d G0, G2, G3;
  Selections() {
    P2.setZero(); P3.setZero(); PL.setZero(); G0.setZero(); G2.setZero(); G3.setZero();
    P2(5, 0) = 1; P2(1, 1) = 1; P2(3, 2) = 1;
    P3(4, 0) = 1; P3(3, 1) = 1; P3(2, 2) = 1;
    PL(0, 0) = 1; PL(5, 1) = 1; PL(4, 2) = 1;
    G0(0, 0) = 1;
    G2(0, 3) = -1; G2(4, 1) = 1;
    G3(0, 2) = 1; G3(5, 1) = -1;
  }
};
const Selections kSel;

// Integrals over (part of) an element of products of shape functions N and
// their derivatives N2 = dN/dx2, N3 = dN/dx3, with 1, x2, x3.
struct ElementIntegrals {
  using M9 = Eigen::Matrix<double, 9, 9>;
  using V93 = Eigen::Matrix<double, 9, 3>;
  M9 S22, S23, S33, S2N, S3N, SNN;
  V93 v2, v3, vN;                    // columns: int N', int N' x2, int N' x3
  Eigen::Matrix<double, 6, 1> m;     // int {1, x2, x3, x2^2, x3^2, x2 x3}
  void setZero() {
    S22.setZero(); S23.setZero(); S33.setZero(); S2N.setZero(); S3N.setZero(); SNN.setZero();
    v2.setZero(); v3.setZero(); vN.setZero(); m.setZero();
  }
  void add(int ne, double w, const Eigen::Matrix<double, 9, 1>& N,
           const Eigen::Matrix<double, 9, 1>& N2, const Eigen::Matrix<double, 9, 1>& N3,
           double x2, double x3) {
    for (int b = 0; b < ne; ++b) {
      const double wN2 = w * N2[b], wN3 = w * N3[b], wN = w * N[b];
      for (int a = 0; a < ne; ++a) {
        S22(a, b) += N2[a] * wN2;
        S23(a, b) += N2[a] * wN3;
        S33(a, b) += N3[a] * wN3;
        S2N(a, b) += N2[a] * wN;
        S3N(a, b) += N3[a] * wN;
        SNN(a, b) += N[a] * wN;
      }
      v2.row(b) += wN2 * Eigen::RowVector3d(1, x2, x3);
      v3.row(b) += wN3 * Eigen::RowVector3d(1, x2, x3);
      vN.row(b) += wN * Eigen::RowVector3d(1, x2, x3);
    }
    m += w * (Eigen::Matrix<double, 6, 1>() << 1, x2, x3, x2 * x2, x3 * x3, x2 * x3).finished();
  }
};

// Adds the element matrices of the energy for a constant material matrix D.
void combine(int ne, const Matrix6d& D, const ElementIntegrals& I, MatE& Ee, MatE& Hl, MatE& Ll,
             Mat4& He, Mat4& Le, Eigen::Matrix4d& Dee) {
  const auto& s = kSel;
  const Eigen::Matrix<double, 6, 3> DP2 = D * s.P2, DP3 = D * s.P3, DPL = D * s.PL;
  const Eigen::Matrix3d D22 = s.P2.transpose() * DP2, D23 = s.P2.transpose() * DP3,
                        D32 = s.P3.transpose() * DP2, D33 = s.P3.transpose() * DP3,
                        D2L = s.P2.transpose() * DPL, D3L = s.P3.transpose() * DPL,
                        DLL = s.PL.transpose() * DPL;
  const Matrix64d DG0 = D * s.G0, DG2 = D * s.G2, DG3 = D * s.G3;
  for (int b = 0; b < ne; ++b)
    for (int a = 0; a < ne; ++a) {
      Ee.block<3, 3>(3 * a, 3 * b) +=
          I.S22(a, b) * D22 + I.S23(a, b) * D23 + I.S23(b, a) * D32 + I.S33(a, b) * D33;
      Hl.block<3, 3>(3 * a, 3 * b) += I.S2N(a, b) * D2L + I.S3N(a, b) * D3L;
      Ll.block<3, 3>(3 * a, 3 * b) += I.SNN(a, b) * DLL;
    }
  for (int a = 0; a < ne; ++a) {
    He.block<3, 4>(3 * a, 0) +=
        s.P2.transpose() * (DG0 * I.v2(a, 0) + DG2 * I.v2(a, 1) + DG3 * I.v2(a, 2)) +
        s.P3.transpose() * (DG0 * I.v3(a, 0) + DG2 * I.v3(a, 1) + DG3 * I.v3(a, 2));
    Le.block<3, 4>(3 * a, 0) +=
        s.PL.transpose() * (DG0 * I.vN(a, 0) + DG2 * I.vN(a, 1) + DG3 * I.vN(a, 2));
  }
  Dee += I.m[0] * s.G0.transpose() * DG0 +
         I.m[1] * (s.G0.transpose() * DG2 + s.G2.transpose() * DG0) +
         I.m[2] * (s.G0.transpose() * DG3 + s.G3.transpose() * DG0) +
         I.m[3] * s.G2.transpose() * DG2 + I.m[4] * s.G3.transpose() * DG3 +
         I.m[5] * (s.G2.transpose() * DG3 + s.G3.transpose() * DG2);
}

// Products of the first-order energy matrices with the classical warping V0:
// Dhl V0, Dhl^T V0 and V0^T Dll V0, formed element by element so that Dhl and
// Dll are never stored (at 10^5 elements each would take ~150 MB).
struct FirstOrderProducts {
  DenseN4 HV, HtV;
  Eigen::Matrix4d VLV = Eigen::Matrix4d::Zero();
};

// The four rigid warping modes Psi (three translations, the rotation about x1), node by node.
DenseN4 rigidWarpingModes(const SectionMesh& mesh) {
  const long nn = static_cast<long>(mesh.nodes.size());
  DenseN4 Psi = DenseN4::Zero(3 * nn, 4);
  for (long a = 0; a < nn; ++a) {
    const double x2 = mesh.nodes[a].x(), x3 = mesh.nodes[a].y();
    Psi(3 * a, 0) = 1;
    Psi(3 * a + 1, 1) = 1;
    Psi(3 * a + 2, 2) = 1;
    Psi(3 * a + 1, 3) = -x3;
    Psi(3 * a + 2, 3) = x2;
  }
  return Psi;
}

// Adds one element's E into the stored pattern and its Dhe, Dle rows.
void scatterElement(const SparsePattern& pattern, const ElementNodes& en, const MatE& Ee, const Mat4& He,
                    const Mat4& Le, Assembled& A) {
  const int ne = en.count;
  const auto slots = pattern.elementSlots(en.node.data(), ne);
  double* pE = A.E.valuePtr();
  for (int a = 0; a < ne; ++a)
    for (int b = 0; b < ne; ++b) {
      const long stride = pattern.blockStride(en.node[b]);
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) pE[slots(a, b) + i + stride * j] += Ee(3 * a + i, 3 * b + j);
    }
  for (int a = 0; a < ne; ++a) {
    const long r0 = 3L * en.node[a];
    A.Dhe.middleRows(r0, 3) += He.middleRows(3 * a, 3);
    A.Dle.middleRows(r0, 3) += Le.middleRows(3 * a, 3);
  }
}

// Without V0: assembles E, Dhe, Dle, Dee, the constraints and the inertia.
// With V0: only fills `products`.
Assembled assemble(const SectionMesh& mesh, const SparsePattern& pattern,
                   const AnalysisOptions& opt, const DenseN4* V0 = nullptr,
                   FirstOrderProducts* products = nullptr) {
  const long nn = static_cast<long>(mesh.nodes.size());
  const long ndof = 3 * nn;
  Assembled A;
  if (!V0) A.E = pattern.makeMatrix();
  if (V0) {
    products->HV = DenseN4::Zero(ndof, 4);
    products->HtV = DenseN4::Zero(ndof, 4);
  }
  A.Dhe = DenseN4::Zero(ndof, 4);
  A.Dle = DenseN4::Zero(ndof, 4);
  A.HPsi = DenseN4::Zero(ndof, 4);
  A.Psi = rigidWarpingModes(mesh);

  const long n_el = static_cast<long>(mesh.elements.size());
  const long report_every = std::max<long>(1, n_el / 20);
  for (long ie = 0; ie < n_el; ++ie) {
    if (opt.progress && ie % report_every == 0)
      opt.progress(V0 ? "first-order warping" : "assembly", double(ie) / n_el);
    const SectionElement& el = mesh.elements[ie];
    const SectionMaterial& mat = mesh.materials[el.material];
    const ElementNodes en = elementNodes(el);
    const int ne = en.count, nd = 3 * ne;
    Eigen::Matrix<double, 9, 2> X;
    for (int a = 0; a < ne; ++a) X.row(a) = mesh.nodes[en.node[a]].transpose();

    Matrix6d D = Matrix6d::Zero();
    if (!el.theta1_nodal)
      D = rotateVoigtStiffness(mat.C, materialAxes(el.theta1_deg[0] * kDegree, el.theta3_deg * kDegree));

    MatE Ee = MatE::Zero(nd, nd), Hl = MatE::Zero(nd, nd), Ll = MatE::Zero(nd, nd);
    Mat4 He = Mat4::Zero(nd, 4), Le = Mat4::Zero(nd, 4);
    ElementIntegrals I;
    I.setZero();
    for (const auto& q : quadratureRule(el.shape, ne)) {
      const ShapeValues sv = shapeFunctions(el.shape, en.present, q.r, q.s);
      double J00 = 0, J01 = 0, J10 = 0, J11 = 0, x2 = 0, x3 = 0, th1 = 0;
      for (int a = 0; a < ne; ++a) {
        const int k = en.slot[a];
        J00 += sv.dNdr[k] * X(a, 0);
        J01 += sv.dNdr[k] * X(a, 1);
        J10 += sv.dNds[k] * X(a, 0);
        J11 += sv.dNds[k] * X(a, 1);
        x2 += sv.N[k] * X(a, 0);
        x3 += sv.N[k] * X(a, 1);
        th1 += sv.N[k] * el.theta1_deg[k];
      }
      const double det = J00 * J11 - J01 * J10;
      if (!(std::abs(det) > 0) || !std::isfinite(det))
        elementError(mesh, el, "is degenerate (zero Jacobian): check its node order and coordinates");
      const double w = std::abs(det) * q.w;
      Eigen::Matrix<double, 9, 1> N, N2, N3;
      for (int a = 0; a < ne; ++a) {
        const int k = en.slot[a];
        N[a] = sv.N[k];
        N2[a] = (J11 * sv.dNdr[k] - J01 * sv.dNds[k]) / det;
        N3[a] = (-J10 * sv.dNdr[k] + J00 * sv.dNds[k]) / det;
        // H Psi: the warping constraints <w, rigid mode>.
        const long r0 = 3L * en.node[a];
        A.HPsi(r0, 0) += N[a] * w;
        A.HPsi(r0 + 1, 1) += N[a] * w;
        A.HPsi(r0 + 2, 2) += N[a] * w;
        A.HPsi(r0 + 1, 3) -= N[a] * x3 * w;
        A.HPsi(r0 + 2, 3) += N[a] * x2 * w;
      }
      I.add(ne, w, N, N2, N3, x2, x3);
      if (el.theta1_nodal) {
        // The material frame varies inside the element: combine point by point.
        D = rotateVoigtStiffness(mat.C, materialAxes(th1 * kDegree, el.theta3_deg * kDegree));
        combine(ne, D, I, Ee, Hl, Ll, He, Le, A.Dee);
        I.setZero();
      }

      const double rw = mat.rho * w;
      A.area += w;
      A.first_area += w * Eigen::Vector2d(x2, x3);
      A.mu += rw;
      A.first_mass += rw * Eigen::Vector2d(x2, x3);
      A.second_mass(0, 0) += rw * x2 * x2;
      A.second_mass(1, 1) += rw * x3 * x3;
      A.second_mass(0, 1) += rw * x2 * x3;
    }
    if (!el.theta1_nodal) combine(ne, D, I, Ee, Hl, Ll, He, Le, A.Dee);
    A.second_mass(1, 0) = A.second_mass(0, 1);

    if (V0) {
      Mat4 Ve(nd, 4);
      for (int a = 0; a < ne; ++a) Ve.middleRows(3 * a, 3) = V0->middleRows(3L * en.node[a], 3);
      const Mat4 hv = Hl * Ve, htv = Hl.transpose() * Ve;
      for (int a = 0; a < ne; ++a) {
        products->HV.middleRows(3L * en.node[a], 3) += hv.middleRows(3 * a, 3);
        products->HtV.middleRows(3L * en.node[a], 3) += htv.middleRows(3 * a, 3);
      }
      products->VLV.noalias() += Ve.transpose() * Ll * Ve;
      continue;
    }
    scatterElement(pattern, en, Ee, He, Le, A);
  }
  A.second_mass(1, 0) = A.second_mass(0, 1);
  return A;
}

// Solves E V = b for V orthogonal (in H) to the rigid warping modes Psi. The
// right-hand side is first freed of its Psi component, which is what the
// Lagrange multipliers of the constraints absorb; the kernel is removed by
// pinning four degrees of freedom, and the pinned solution is then projected.
class ConstrainedSolver {
 public:
  // Pins E in place (E is not needed afterwards).
  ConstrainedSolver(Assembled& A, const std::vector<Eigen::Vector2d>& nodes,
                    const std::vector<char>& used)
      : A_(A) {
    M4inv_ = (A.Psi.transpose() * A.HPsi).inverse();
    const long nn = static_cast<long>(nodes.size());
    long a = 0;
    while (!used[a]) ++a;
    long b = a;
    double best = -1;
    for (long i = 0; i < nn; ++i) {
      if (!used[i]) continue;
      const double d = (nodes[i] - nodes[a]).squaredNorm();
      if (d > best) { best = d; b = i; }
    }
    const Eigen::Vector2d d = nodes[b] - nodes[a];
    // A rotation about x1 moves w3 at b by theta * dx2 and w2 by -theta * dx3.
    pinned_ = {3 * a, 3 * a + 1, 3 * a + 2,
               std::abs(d.x()) >= std::abs(d.y()) ? 3 * b + 2 : 3 * b + 1};
    std::vector<char> is_pinned(3 * nn, 0);
    for (long p : pinned_) is_pinned[p] = 1;
    // Unused nodes (in a file but in no element) are pinned too.
    for (long i = 0; i < nn; ++i)
      if (!used[i]) for (int k = 0; k < 3; ++k) is_pinned[3 * i + k] = 1;
    mask_ = is_pinned;
    Eigen::SparseMatrix<double>& K = A.E;
    for (long col = 0; col < K.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it)
        if (is_pinned[it.row()] || is_pinned[it.col()])
          it.valueRef() = (it.row() == it.col()) ? 1.0 : 0.0;
#ifdef FLEXCOMP_SECTION_EIGEN_BLAS
    static const bool kernels = eigenDenseKernelsLinked();
    (void)kernels;
#endif
    solver_.compute(K);
    K.resize(0, 0);
    K.data().squeeze();
    if (solver_.info() != Eigen::Success)
      throw std::runtime_error("the warping stiffness matrix could not be factorised: "
                               "check for elements with zero stiffness");
  }

  DenseN4 solve(DenseN4 rhs) const {
    rhs -= A_.HPsi * (M4inv_ * (A_.Psi.transpose() * rhs));
    for (long i = 0; i < rhs.rows(); ++i)
      if (mask_[i]) rhs.row(i).setZero();
    DenseN4 V = solver_.solve(rhs).eval();
    V -= A_.Psi * (M4inv_ * (A_.HPsi.transpose() * V));
    return V;
  }

 private:
  const Assembled& A_;
  Eigen::Matrix4d M4inv_;
  std::vector<long> pinned_;
  std::vector<char> mask_;
#ifdef FLEXCOMP_SECTION_CHOLMOD
  // CHOLMOD picks simplicial or supernodal and the ordering (AMD, else METIS)
  // from the matrix; the factorisation is ~80 % of the time on large sections.
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> solver_;
#else
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
#endif
};

// The 3-D strain of one element at the point (r, s), per unit classical strain
// e and per unit derivative e' (each 6x4, Voigt [11,22,33,23,13,12], engineering
// shear), from the first-order warping w = V0 e + V1 e' (Hodges 2006, ch. 4;
// Yu et al. 2002, sec. 3):
//   Gamma = (Gamma_h V0 + Gamma_e) e + (Gamma_h V1 + Gamma_l V0) e' + Gamma_l V1 e'',
// the last term left out: e'' vanishes without distributed loads, and it is
// of second order in the slenderness otherwise.
struct PointStrain {
  Matrix64d Se, Sp;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  double weight = 0, theta1_deg = 0;
};

PointStrain pointStrain(const SectionMesh& mesh, const SectionElement& el, const ElementNodes& en,
                        const DenseN4& V0, const DenseN4& V1, double r, double s) {
  const ShapeValues sv = shapeFunctions(el.shape, en.present, r, s);
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  PointStrain p;
  for (int a = 0; a < en.count; ++a) {
    const int k = en.slot[a];
    const Eigen::Vector2d& X = mesh.nodes[en.node[a]];
    J.row(0) += sv.dNdr[k] * X.transpose();
    J.row(1) += sv.dNds[k] * X.transpose();
    p.x += sv.N[k] * X;
    p.theta1_deg += sv.N[k] * el.theta1_deg[k];
  }
  if (!el.theta1_nodal) p.theta1_deg = el.theta1_deg[0];
  const double det = J.determinant();
  p.weight = std::abs(det);
  p.Se = kSel.G0 + p.x.x() * kSel.G2 + p.x.y() * kSel.G3;
  p.Sp.setZero();
  for (int a = 0; a < en.count; ++a) {
    const int k = en.slot[a];
    const double N2 = (J(1, 1) * sv.dNdr[k] - J(0, 1) * sv.dNds[k]) / det;
    const double N3 = (-J(1, 0) * sv.dNdr[k] + J(0, 0) * sv.dNds[k]) / det;
    const Eigen::Matrix<double, 6, 3> Bh = N2 * kSel.P2 + N3 * kSel.P3;
    const long r0 = 3L * en.node[a];
    p.Se.noalias() += Bh * V0.middleRows(r0, 3);
    p.Sp.noalias() += Bh * V1.middleRows(r0, 3) + sv.N[k] * kSel.PL * V0.middleRows(r0, 3);
  }
  return p;
}

// The recovery basis (docs/section-prep.md, "Stress recovery"). For
// resultants F = [F1, F2, F3, M1, M2, M3] of an unloaded stretch of beam, the
// equilibrium equations F' = 0, M' + e1 x F = 0 give the derivatives of the
// classical resultants R = [F1, M1, M2, M3]: R' = [0, 0, F3, -F2]; then
//   e' = K^-1 R'   and   e = K^-1 (R - B e'),
// where B = int Gamma_e^T D (Gamma_h V1 + Gamma_l V0) dA is what the first-order
// field adds to the classical resultants: the recovered stresses integrate to
// exactly the given R (Gamma_e^T sigma picks sigma11, x2 s13 - x3 s12, x3 s11,
// -x2 s11), and their shear stresses to F2, F3 by the weak equilibrium the
// warping solves.
std::vector<ElementRecovery> recoveryBasis(const SectionMesh& mesh, const DenseN4& V0,
                                           const DenseN4& V1) {
  const long n_el = static_cast<long>(mesh.elements.size());
  std::vector<ElementRecovery> out(n_el);
  std::vector<Matrix6d> D(n_el);
  std::vector<Matrix64d> Se(n_el), Sp(n_el);
  Eigen::Matrix4d Kr = Eigen::Matrix4d::Zero(), B = Eigen::Matrix4d::Zero();
  for (long ie = 0; ie < n_el; ++ie) {
    const SectionElement& el = mesh.elements[ie];
    const SectionMaterial& mat = mesh.materials[el.material];
    const ElementNodes en = elementNodes(el);
    const bool tri = el.shape == ElementShape::Triangle;
    const PointStrain c = pointStrain(mesh, el, en, V0, V1, tri ? 1.0 / 3 : 0.0, tri ? 1.0 / 3 : 0.0);
    const Eigen::Matrix3d Rm = materialAxes(c.theta1_deg * kDegree, el.theta3_deg * kDegree);
    D[ie] = rotateVoigtStiffness(mat.C, Rm);
    out[ie].centroid = c.x;
    out[ie].axes = isIsotropicMaterial(mat.C) ? materialAxes(c.theta1_deg * kDegree, 0.0) : Rm;
    Se[ie] = c.Se;
    Sp[ie] = c.Sp;
    // The resultants of the field, integrated with the rule the stiffness uses.
    for (const auto& q : quadratureRule(el.shape, en.count)) {
      const PointStrain p = pointStrain(mesh, el, en, V0, V1, q.r, q.s);
      const Matrix6d Dq = el.theta1_nodal
                              ? rotateVoigtStiffness(mat.C, materialAxes(p.theta1_deg * kDegree,
                                                                         el.theta3_deg * kDegree))
                              : D[ie];
      const Matrix64d Ge = kSel.G0 + p.x.x() * kSel.G2 + p.x.y() * kSel.G3;
      const Eigen::Matrix<double, 4, 6> GtD = q.w * p.weight * Ge.transpose() * Dq;
      Kr.noalias() += GtD * p.Se;
      B.noalias() += GtD * p.Sp;
    }
  }
  // Unit resultants -> R and R' (4x6 selections, columns in the Timoshenko order).
  Eigen::Matrix<double, 4, 6> R = Eigen::Matrix<double, 4, 6>::Zero(), Rd = R;
  R(0, 0) = R(1, 3) = R(2, 4) = R(3, 5) = 1;
  Rd(2, 2) = 1;   // M2' = F3
  Rd(3, 1) = -1;  // M3' = -F2
  const Eigen::Matrix4d Kinv = Kr.inverse();
  const Eigen::Matrix<double, 4, 6> Ed = Kinv * Rd;
  const Eigen::Matrix<double, 4, 6> E0 = Kinv * (R - B * Ed);
  for (long ie = 0; ie < n_el; ++ie) {
    out[ie].strain = Se[ie] * E0 + Sp[ie] * Ed;
    out[ie].stress = D[ie] * out[ie].strain;
  }
  return out;
}

}  // namespace

Matrix6d sectionMassMatrix(double mu, const Eigen::Vector2d& fm, const Eigen::Matrix2d& sm) {
  // Kinetic energy of the rigid section moving with the reference line:
  // [v; omega] with v about the origin (Hodges 2006, ch. 4; VABS order).
  Matrix6d M = Matrix6d::Zero();
  M(0, 0) = M(1, 1) = M(2, 2) = mu;
  M(0, 4) = M(4, 0) = fm.y();
  M(0, 5) = M(5, 0) = -fm.x();
  M(1, 3) = M(3, 1) = -fm.y();
  M(2, 3) = M(3, 2) = fm.x();
  M(3, 3) = sm(0, 0) + sm(1, 1);
  M(4, 4) = sm(1, 1);
  M(5, 5) = sm(0, 0);
  M(4, 5) = M(5, 4) = -sm(0, 1);
  return M;
}

Eigen::Vector2d shearCenterFromTimoshenko(const Matrix6d& K) {
  // A transverse force through the shear centre causes no twist: with the
  // compliance S, a force F3 at x2 gives M1 = x2 F3, so kappa1 = S(3,2) F3 +
  // S(3,3) x2 F3 = 0; likewise for F2 (M1 = -x3 F2).
  const Matrix6d S = K.inverse();
  return {-S(3, 2) / S(3, 3), S(3, 1) / S(3, 3)};
}

Eigen::Vector2d tensionCenterFromClassical(const Eigen::Matrix4d& K) {
  // An axial force through the tension centre causes no bending: F1 at
  // (x2, x3) adds M2 = x3 F1, M3 = -x2 F1; both curvatures vanish.
  const Eigen::Matrix4d S = K.inverse();
  Eigen::Matrix2d a;
  a << -S(2, 3), S(2, 2), -S(3, 3), S(3, 2);
  const Eigen::Vector2d rhs(-S(2, 0), -S(3, 0));
  return a.lu().solve(rhs);
}

SectionProperties analyzeSection(const SectionMesh& mesh, const AnalysisOptions& opt) {
  checkMesh(mesh);
  checkElementGeometry(mesh);
  const long nn = static_cast<long>(mesh.nodes.size());
  std::vector<std::vector<int>> element_nodes;
  element_nodes.reserve(mesh.elements.size());
  std::vector<char> used(nn, 0);
  for (const auto& e : mesh.elements) {
    std::vector<int> v;
    for (int n : e.nodes)
      if (n >= 0) { v.push_back(n); used[n] = 1; }
    element_nodes.push_back(std::move(v));
  }
  SectionProperties P;
  const SparsePattern pattern(nn, element_nodes);
  checkConnected(pattern, nn, used);

  std::clock_t c0 = std::clock();
  auto lap = [&c0]() {
    const std::clock_t c = std::clock();
    const double s = double(c - c0) / CLOCKS_PER_SEC;
    c0 = c;
    return s;
  };
  Assembled A = assemble(mesh, pattern, opt);
  P.cpu_assembly = lap();
  P.n_nodes = std::count(used.begin(), used.end(), 1);
  P.n_elements = static_cast<long>(mesh.elements.size());
  P.n_dof = 3 * P.n_nodes;
  P.area = A.area;
  P.mass_per_length = A.mu;
  P.geometric_center = A.first_area / A.area;
  P.mass_center = A.mu > 0 ? Eigen::Vector2d(A.first_mass / A.mu) : P.geometric_center;
  P.mass = sectionMassMatrix(A.mu, A.first_mass, A.second_mass);

  if (opt.progress) opt.progress("factorisation", 0.0);
  const ConstrainedSolver solver(A, mesh.nodes, used);
  P.cpu_factorisation = lap();
  if (opt.progress) opt.progress("warping", 0.5);

  // Zeroth order (classical): E V0 = -Dhe (Cesnik & Hodges 1997).
  const DenseN4 V0 = solver.solve(-A.Dhe);
  Eigen::Matrix4d K = A.Dee + V0.transpose() * A.Dhe;
  K = 0.5 * (K + K.transpose()).eval();
  P.classical = K;
  P.tension_center = tensionCenterFromClassical(K);

  if (opt.timoshenko) {
    // First order in the slenderness (Yu et al. 2002, sec. 3): V1 = V1hat e',
    //   E V1hat = (Dhl^T - Dhl) V0 + Dle,
    // energy 2U = e'A e + 2 e'B e' + e''C e' with
    //   B = (Dhl^T V0 + Dle)^T V0,  C = V0^T Dll V0 + V1^T (Dhl^T V0 + Dhl V0 + Dle).
    FirstOrderProducts fp;
    assemble(mesh, pattern, opt, &V0, &fp);
    const DenseN4 T1 = fp.HtV + A.Dle;
    const DenseN4& T2 = fp.HV;
    const DenseN4 V1 = solver.solve(T1 - T2);
    const Eigen::Matrix4d B = T1.transpose() * V0;
    Eigen::Matrix4d C = fp.VLV + V1.transpose() * (T2 + T1);
    C = 0.5 * (C + C.transpose()).eval();
    // Equivalence with the Timoshenko energy through the equilibrium equations
    // of the unloaded beam, e' = K^-1 P F (Yu et al. 2002, sec. 3).
    Eigen::Matrix<double, 4, 2> Pm;
    Pm << 0, 0, 0, 0, 0, -1, 1, 0;
    const Eigen::Matrix4d Kinv = K.inverse();
    const Eigen::Matrix<double, 4, 2> Q = Kinv * Pm;
    const Eigen::Matrix2d Ginv = Q.transpose() * (C - B.transpose() * Kinv * B) * Q;
    const Eigen::Matrix2d Gs = Ginv.inverse();
    const Eigen::Matrix<double, 4, 2> Y = B.transpose() * Q * Gs;
    const Eigen::Matrix4d X = K + Y * Ginv * Y.transpose();
    // Reorder [e (4), gamma (2)] -> VABS [g11, 2g12, 2g13, k1, k2, k3].
    const int map_e[4] = {0, 3, 4, 5}, map_g[2] = {1, 2};
    Matrix6d T = Matrix6d::Zero();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) T(map_e[i], map_e[j]) = X(i, j);
      for (int j = 0; j < 2; ++j) T(map_e[i], map_g[j]) = T(map_g[j], map_e[i]) = Y(i, j);
    }
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) T(map_g[i], map_g[j]) = Gs(i, j);
    P.timoshenko = 0.5 * (T + T.transpose());
    P.has_timoshenko = true;
    P.shear_center = shearCenterFromTimoshenko(P.timoshenko);
    if (opt.recovery) P.recovery = recoveryBasis(mesh, V0, V1);
  }
  P.cpu_solves = lap();
  if (opt.progress) opt.progress("done", 1.0);
  // A backstop after the input checks: no NaN/inf leaves the analysis.
  if (!P.timoshenko.allFinite() || !P.classical.allFinite() || !P.mass.allFinite() ||
      !std::isfinite(P.area) || !P.shear_center.allFinite() || !P.tension_center.allFinite())
    throw std::runtime_error(
        "the section analysis produced non-finite numbers: the mesh or the materials are "
        "numerically degenerate (coordinates or moduli of wildly different magnitudes?)");
  return P;
}

bool isIsotropicMaterial(const Matrix6d& C) {
  const double tol = 1e-9 * C.cwiseAbs().maxCoeff();
  const double l2m = C(0, 0), l = C(0, 1), mu = 0.5 * (l2m - l);
  Matrix6d iso = Matrix6d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) iso(i, j) = i == j ? l2m : l;
  for (int i = 3; i < 6; ++i) iso(i, i) = mu;
  return (C - iso).cwiseAbs().maxCoeff() <= tol;
}

std::string materialProblem(const SectionMaterial& m) {
  if (!m.C.allFinite()) return "its stiffness holds a non-finite number";
  if (!std::isfinite(m.rho) || m.rho < 0) return "its density must be a finite number >= 0";
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(0.5 * (m.C + m.C.transpose()), Eigen::EigenvaluesOnly);
  const double lo = es.eigenvalues().minCoeff(), hi = es.eigenvalues().maxCoeff();
  if (!(lo > 0)) return "its stiffness is not positive definite";
  constexpr double kMaxCondition = 1e5;
  if (hi / lo > kMaxCondition) {
    std::ostringstream os;
    os << "its stiffness has a condition number of " << hi / lo << " (above " << kMaxCondition
       << "): nearly incompressible (nu above 0.49998 if isotropic) or wildly anisotropic; "
          "section-prep's displacement elements lock there and the shear stiffness would be "
          "wrong (300x at nu = 0.49999999)";
    return os.str();
  }
  return "";
}

}  // namespace fc::section
