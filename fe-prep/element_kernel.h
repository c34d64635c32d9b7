#pragma once
// What an assembly loop asks of a body's elements (assembly.h): element e's
// nodes and matrices. Apart from assembly.h so that code without linear
// algebra (imported_body.h) names it without a backend.
#include <Eigen/Dense>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fc::feprep {

// Element e: its nodes, stiffness and mass (6 DOF per node, body frame), and the
// lumped nodal mass vector (6 per node) reported in /mass/nodal.
struct ElementResult {
  std::vector<long> nodes;
  Eigen::MatrixXd K, M;
  Eigen::VectorXd lumped;
};
using ElementKernel = std::function<void(long element, ElementResult& out)>;

// Node a's 6 x 6 block of element e's mass, for an assembly into the
// node-local pattern of a lumped M; a mass that couples two nodes has no place
// in that pattern (a logic error of the caller's choice of pattern).
inline Eigen::MatrixXd nodalMassBlock(const ElementResult& er, long e, long a) {
  const long n = static_cast<long>(er.nodes.size());
  for (long j = 0; j < n; ++j)
    if (j != a && er.M.block(6 * a, 6 * j, 6, 6).cwiseAbs().maxCoeff() > 0.0)
      throw std::logic_error("assembly: a nodal mass pattern was asked but element " + std::to_string(e) +
                             "'s mass couples two nodes");
  return er.M.block(6 * a, 6 * a, 6, 6);
}

}  // namespace fc::feprep
