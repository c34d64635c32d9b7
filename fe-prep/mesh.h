#pragma once
// The finite element mesh of one body, in the body frame: what the mesher
// produces, the assembly consumes and the body file stores under /mesh/.
#include <Eigen/Dense>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace fc::feprep {

struct Mesh {
  Eigen::MatrixXd nodes;                       // (n_nodes, 3)
  std::vector<std::array<long, 3>> triangles;  // counter-clockwise about the normal
  std::vector<std::array<long, 2>> beams;
  // Named node sets usable in `reference:` (edges, beam ends, geo physical groups).
  std::map<std::string, std::vector<long>> sets;

  long nodeCount() const { return static_cast<long>(nodes.rows()); }
  // Index of the node closest to p, and its distance.
  long nearestNode(const Eigen::Vector3d& p, double* distance = nullptr) const;
  double characteristicLength() const;  // bounding-box diagonal
};

}  // namespace fc::feprep
