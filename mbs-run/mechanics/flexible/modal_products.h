#pragma once
// The invariants' second-order products S_ab = sum_k m_k Phi_k,a^T Phi_k,b
// (common/flexbody.h) over their non-zero entries. A body whose modes each
// move mostly along one axis (a beam's axial, bending and torsion modes; a
// plate's in-plane and out-of-plane ones) has S_ab with a block pattern: the
// 1 m steel bar with 64 modes keeps 13 % of the entries of its six S_ab
// (a <= b), the rest being the eigen-solve's orthogonality noise, 1e-14 of
// the largest entry and below. Every evaluation multiplies these matrices by
// w (and wdot, for the Coriolis rows): over the pattern that is the same sum
// without its zero terms.
//
// Which entries are dropped: |S_ab,ij| <= nm eps max_ab,ij |S_ab,ij|. A dense
// dot product of nm terms is itself only exact to nm eps sum |S_ij x_i|
// (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., eq. 3.5),
// so the dropped terms together move a product by no more than the rounding
// bound it already has relative to the largest entry (the test
// tests/mbs-run/flexible/test_modal_products.cpp measures it).
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "common/flexbody.h"

namespace fc::mbs {

// One S_ab in compressed columns.
struct SparseProduct {
  std::vector<int> start;   // (nm + 1): entries of column j are [start[j], start[j+1])
  std::vector<int> row;     // row of each entry
  std::vector<double> value;
};

struct SparseModalProducts {
  int n_modes = 0;
  std::array<SparseProduct, 9> products;  // [3a+b], filled for a <= b (S_ba = S_ab^T)
  long entries() const;                   // kept entries of the six S_ab, a <= b
};

// The pattern of inv's six S_ab (a <= b), taken once at load.
SparseModalProducts sparseModalProducts(const InertiaInvariants& inv);

// True when the kept entries make the sparse products cheaper than the dense
// ones: an entry over the pattern costs an index load and a scattered
// update besides its two multiply-adds, taken as twice a dense entry (the
// dense loop vectorises), so fewer than half of the 6 nm^2 entries. The
// steel bar (13 % kept) spends 5x less in these products (docs/benchmarks.md,
// "Stiff beam pendulum").
bool sparseFormCheaper(const SparseModalProducts& s);

// S^T x and S x in one pass over the kept entries (the dense form's
// transposedAndDirectProducts over the pattern).
void sparseTransposedAndDirect(const SparseProduct& S, const Eigen::VectorXd& x, Eigen::VectorXd& St_x,
                               Eigen::VectorXd& S_x);

}  // namespace fc::mbs
