#include "mbs-run/mechanics/flexible/modal_products.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace fc::mbs {

long SparseModalProducts::entries() const {
  long n = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) n += static_cast<long>(products[3 * a + b].value.size());
  return n;
}

SparseModalProducts sparseModalProducts(const InertiaInvariants& inv) {
  const int nm = inv.n_modes;
  SparseModalProducts s;
  s.n_modes = nm;
  if (nm == 0) return s;
  double largest = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      const Eigen::MatrixXd& S = inv.modal_products[3 * a + b];
      if (S.rows() != nm || S.cols() != nm)
        throw std::invalid_argument("flexible body: modal products of " + std::to_string(S.rows()) + " x " +
                                    std::to_string(S.cols()) + " for " + std::to_string(nm) + " modes");
      largest = std::max(largest, S.cwiseAbs().maxCoeff());
    }
  // Below the rounding bound of a dense dot product of nm terms (header).
  const double drop = nm * std::numeric_limits<double>::epsilon() * largest;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      const Eigen::MatrixXd& S = inv.modal_products[3 * a + b];
      SparseProduct& p = s.products[3 * a + b];
      p.start.assign(1, 0);
      for (int j = 0; j < nm; ++j) {
        for (int i = 0; i < nm; ++i)
          if (std::abs(S(i, j)) > drop) {
            p.row.push_back(i);
            p.value.push_back(S(i, j));
          }
        p.start.push_back(static_cast<int>(p.row.size()));
      }
    }
  return s;
}

bool sparseFormCheaper(const SparseModalProducts& s) {
  // Below 16 modes the six S_ab are a few kB, in cache, and the dense loop
  // costs next to nothing (as for the node form, nodalFormCheaper): such
  // bodies keep the dense products and their results bit for bit.
  return s.n_modes >= 16 && 2 * s.entries() < 6L * s.n_modes * s.n_modes;
}

void sparseTransposedAndDirect(const SparseProduct& S, const Eigen::VectorXd& x, Eigen::VectorXd& St_x,
                               Eigen::VectorXd& S_x) {
  const Eigen::Index n = x.size();
  S_x.setZero(n);
  St_x.resize(n);
  const int* row = S.row.data();
  const double* value = S.value.data();
  for (Eigen::Index j = 0; j < n; ++j) {
    const double xj = x[j];
    double dot = 0.0;
    for (int p = S.start[j]; p < S.start[j + 1]; ++p) {
      dot += value[p] * x[row[p]];
      S_x[row[p]] += value[p] * xj;
    }
    St_x[j] = dot;
  }
}

}  // namespace fc::mbs
