#pragma once
// The sparsity of a finite element matrix with three unknowns per node, built
// once from the element connectivity so that several matrices (E, Dhl, Dll)
// are assembled in place without triplet lists: at 50 000 quadratic elements
// triplets would need gigabytes.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

namespace fc::section {

class SparsePattern {
 public:
  SparsePattern(long n_nodes, const std::vector<std::vector<int>>& element_nodes);

  // A zero matrix (3n x 3n, column-major) with the full symmetric pattern:
  // column 3b+j lists rows 3a+i for every node a sharing an element with b.
  Eigen::SparseMatrix<double> makeMatrix() const;

  const std::vector<int>& neighbours(long node) const { return adj_[node]; }
  // Value index of entry (3a, 3b); entry (3a+i, 3b+j) is at that + i + blockStride(b) * j.
  long blockOffset(int a, int b) const;
  long blockStride(int b) const { return 3L * static_cast<long>(adj_[b].size()); }
  // blockOffset for every pair of an element's nodes.
  Eigen::Matrix<long, Eigen::Dynamic, Eigen::Dynamic, 0, 9, 9> elementSlots(const int* nodes,
                                                                           int count) const;

 private:
  std::vector<std::vector<int>> adj_;
  std::vector<long> base_;
  long nnz_ = 0;
};

}  // namespace fc::section
