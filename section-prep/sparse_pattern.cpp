#include "section-prep/sparse_pattern.h"

#include <algorithm>

namespace fc::section {

SparsePattern::SparsePattern(long n_nodes, const std::vector<std::vector<int>>& element_nodes)
    : adj_(n_nodes), base_(n_nodes + 1, 0) {
  for (const auto& e : element_nodes)
    for (int a : e)
      for (int b : e) adj_[a].push_back(b);
  for (long i = 0; i < n_nodes; ++i) {
    auto& v = adj_[i];
    v.push_back(static_cast<int>(i));  // keeps unused nodes' diagonal in the pattern
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    base_[i + 1] = base_[i] + 9L * static_cast<long>(v.size());
  }
  nnz_ = base_[n_nodes];
}

Eigen::SparseMatrix<double> SparsePattern::makeMatrix() const {
  const long n = static_cast<long>(adj_.size());
  Eigen::SparseMatrix<double> m(3 * n, 3 * n);
  m.resizeNonZeros(nnz_);
  auto* outer = m.outerIndexPtr();
  auto* inner = m.innerIndexPtr();
  long k = 0;
  for (long b = 0; b < n; ++b)
    for (int j = 0; j < 3; ++j) {
      outer[3 * b + j] = static_cast<int>(k);
      for (int a : adj_[b])
        for (int i = 0; i < 3; ++i) inner[k++] = 3 * a + i;
    }
  outer[3 * n] = static_cast<int>(k);
  std::fill(m.valuePtr(), m.valuePtr() + nnz_, 0.0);
  return m;
}

long SparsePattern::blockOffset(int a, int b) const {
  const auto& v = adj_[b];
  const long pos = std::lower_bound(v.begin(), v.end(), a) - v.begin();
  return base_[b] + 3 * pos;
}

Eigen::Matrix<long, Eigen::Dynamic, Eigen::Dynamic, 0, 9, 9> SparsePattern::elementSlots(
    const int* nodes, int count) const {
  Eigen::Matrix<long, Eigen::Dynamic, Eigen::Dynamic, 0, 9, 9> s(count, count);
  for (int a = 0; a < count; ++a)
    for (int b = 0; b < count; ++b) s(a, b) = blockOffset(nodes[a], nodes[b]);
  return s;
}

}  // namespace fc::section
