#pragma once
// Reference conditions as a change of variables, and the rigid-body motions a
// reference leaves free.
//
// A constrained point P attached to node n (offset d = P - X_n) gives linear
// conditions on the node's six DOF: a pin asks u_P = u_n + theta_n x d = 0,
// a clamp additionally theta_n = 0. Each node's admissible DOF are written as
// q_n = T_n r_n with T_n (6 x k_n) an orthonormal basis of the null space of its
// conditions, so the reduced problem (T^T K T, T^T M T) is exactly the
// constrained one, with no penalty or Lagrange multiplier.
#include <Eigen/Dense>
#include <vector>

#include "fe-prep/mesh.h"

namespace fc::feprep {

struct PointConstraint {
  long node = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // where the condition acts (body frame)
  bool clamp = false;                               // false: pin (translations only)
};

struct DofMap {
  std::vector<Eigen::MatrixXd> T;  // per node, 6 x k_n
  std::vector<long> offset;        // first reduced DOF of each node
  long reduced = 0;                // number of reduced DOF
  std::vector<char> unconstrained; // per node: T_n is the identity (no condition)

  int count(long node) const { return static_cast<int>(T[static_cast<std::size_t>(node)].cols()); }
  // Full nodal vector (n_nodes * 6) from a reduced one.
  Eigen::VectorXd expand(const Eigen::VectorXd& reduced_vector) const;
  // Reduced vector from a full one that satisfies the constraints (T orthonormal: T^T q).
  Eigen::VectorXd restrict(const Eigen::VectorXd& full_vector) const;
};

DofMap buildDofMap(const Mesh& mesh, const std::vector<PointConstraint>& constraints);

// The rigid motions u = t + omega x X, theta = omega (small rotations about the
// body origin) that satisfy every constraint: (n_nodes * 6) x r, r <= 6.
// Free-free: r = 6; a panel pinned at two points: r = 1 (turning about their line).
Eigen::MatrixXd admissibleRigidModes(const Mesh& mesh, const std::vector<PointConstraint>& constraints);

// Skew matrix: skew(a) b = a x b.
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

// T^T K T of one element whose nodes are `nodes` (element matrix 6a x 6a in
// body DOF order), and the reduced global indices of its rows.
void reduceElement(const DofMap& map, const std::vector<long>& nodes, const Eigen::MatrixXd& Ke,
                   Eigen::MatrixXd& Kr, std::vector<long>& indices);

}  // namespace fc::feprep
