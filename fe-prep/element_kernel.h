#pragma once
// What an assembly loop asks of a body's elements (assembly.h): element e's
// nodes and matrices. Apart from assembly.h so that code without linear
// algebra (imported_body.h) names it without a backend.
#include <Eigen/Dense>
#include <functional>
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

}  // namespace fc::feprep
