#pragma once
// Reference conditions (clamp, pin) and the couplings of distributed interfaces
// as one change of variables q = T r, and the rigid-body motions a reference
// leaves free.
//
// A point condition at P attached to node n (offset d = P - X_n) gives linear
// conditions on the node's six DOF: a pin asks u_P = u_n + theta_n x d = 0,
// a clamp additionally theta_n = 0. The node's admissible DOF are q_n = T_n r_n
// with T_n (6 x k_n) an orthonormal basis of the null space of its conditions,
// so the reduced problem (T^T K T, T^T M T) is exactly the constrained one, with
// no penalty or Lagrange multiplier.
//
// Distributed interfaces (fe-prep/interfaces.h) add multi-node relations:
// - rigid (RBE2): every other patch node s follows the master node m rigidly,
//   q_s = G(X_s - X_m) q_m, G(d) = [I -skew(d); 0 I]; s has no DOF of its own
//   and maps onto m's reduced DOF;
// - distributing (RBE3) under a reference condition: the reference point's
//   motion W q_patch (a weighted least-squares fit, no stiffness) must satisfy
//   the condition, C W q_patch = 0; c dependent patch DOF (pivoted QR of C W)
//   are either eliminated in favour of the others, q_D = -(C W)_D^-1 (C W)_I q_I
//   (PatchHold::Eliminate), or kept by Lagrange multipliers (PatchHold::
//   Multipliers, the default): the patch nodes keep their six DOF and the
//   c rows C W q_patch = 0 join the system as
//     [K  A^T] [q]   [f]        [M 0]
//     [A   0 ] [mu] = [0],       [0 0]   (A = alpha C W on the reduced DOF),
//   a symmetric indefinite (saddle-point) K factorised by MUMPS LDL^T. The
//   elimination expresses c DOF through all 6 p of the patch, so every element
//   at those nodes couples the whole patch: a dense (6 p)^2 block in K per
//   held patch, which grows as h^-4 under refinement; the multipliers add c
//   rows of 6 p entries instead. The eigenpairs and static responses are the
//   same (the constrained problem's); the multipliers have no mass, so they add
//   only infinite eigenvalues, which shift-and-invert maps to zero.
// So a node's DOF are q_n = T_n r[idx_n], idx_n the reduced DOF it depends on
// (its own, its master's, or its patch's); the multipliers come after every
// nodal reduced DOF and belong to no node.
#include <Eigen/Dense>
#include <vector>

#include "fe-prep/mesh.h"

namespace fc::feprep {

struct PointCondition {
  long node = -1;                                   // -1: no node (rigid-mode admissibility only)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // where the condition acts (body frame)
  bool clamp = false;                               // false: pin (translations only)
};

// A rigid (RBE2) patch: the slaves follow the master rigidly.
struct RigidCoupling {
  long master = -1;
  std::vector<long> slaves;
};

// Linear conditions C q_patch = 0 on the full nodal DOF of a patch of nodes
// (a distributing interface's reference point held).
struct PatchCondition {
  std::vector<long> nodes;
  Eigen::MatrixXd C;  // (c, 6 nodes.size())
};

enum class PatchHold { Multipliers, Eliminate };

// A held distributing patch kept by multipliers: its rows C on the patch
// nodes' full DOF (c, 6 nodes.size()).
struct HeldPatch {
  std::vector<long> nodes;
  Eigen::MatrixXd C;
};

struct DofMap {
  std::vector<Eigen::MatrixXd> T;    // per node, 6 x idx[n].size()
  std::vector<std::vector<long>> idx;// per node: the reduced DOF its T columns refer to
  std::vector<Eigen::MatrixXd> own;  // per node, own_n x 6: its own reduced DOF from a conforming q_n
  std::vector<long> offset;          // first own reduced DOF of each node (contiguous per node)
  long reduced = 0;                  // number of reduced DOF
  std::vector<char> unconstrained;   // per node: T_n is the identity on its own DOF
  std::vector<HeldPatch> held;       // PatchHold::Multipliers: one block of multipliers per held patch
  long multipliers = 0;              // their number: the last rows of the reduced system

  // First multiplier row (every nodal reduced DOF comes before).
  long firstMultiplier() const { return reduced - multipliers; }
  // Dimension of the constrained problem: the nodal reduced DOF less one per
  // multiplier (what the elimination would have kept).
  long constrainedDofs() const { return reduced - 2 * multipliers; }

  // Number of reduced DOF node n owns (its rows of the reduced system).
  int count(long node) const { return static_cast<int>(own[static_cast<std::size_t>(node)].rows()); }
  // Full nodal vector (n_nodes * 6) from a reduced one.
  Eigen::VectorXd expand(const Eigen::VectorXd& reduced_vector) const;
  // Reduced vector from a full one that satisfies the conditions (multipliers zero).
  Eigen::VectorXd restrict(const Eigen::VectorXd& full_vector) const;
};

// Whether HELD's nodal reduced DOF (those before its multipliers) are exactly
// FREE's, node by node (FREE has no multipliers): then a system assembled over
// HELD holds FREE's in its leading block.
bool sameNodalDofs(const DofMap& held, const DofMap& free);

// Throws std::invalid_argument when a node is claimed twice in incompatible ways
// (a rigid slave that also carries a condition, overlapping patches).
DofMap buildDofMap(const Mesh& mesh, const std::vector<PointCondition>& conditions,
                   const std::vector<RigidCoupling>& rigid = {}, const std::vector<PatchCondition>& patches = {},
                   PatchHold hold = PatchHold::Multipliers);

// The multiplier rows of held patch k on the reduced DOF: C T_patch, the
// columns that carry a non-zero entry (`indices`, ascending) and their values
// (c, indices.size()); the rows are map.firstMultiplier() + (the multipliers of
// the patches before k) + 0 .. c-1.
struct MultiplierRows {
  long first_row = 0;
  std::vector<long> indices;
  Eigen::MatrixXd values;
};
MultiplierRows multiplierRows(const DofMap& map, std::size_t k);

// Per node, the nodes whose reduced DOF express it (sorted, unique): itself,
// or for a node expressed through other nodes' reduced DOF (a rigid slave
// through its master, a held distributing patch through the patch) those
// nodes instead: the node graph both assemblies build K's pattern on.
std::vector<std::vector<long>> nodeSources(const DofMap& map, long n_nodes);

// The sources of an element's `count` nodes, one after the other, into `out`
// (cleared first): the nodes the element's matrices couple.
void elementSources(const std::vector<std::vector<long>>& sources, const long* nodes, int count,
                    std::vector<long>& out);

// The rigid motions u = t + omega x X, theta = omega (small rotations about the
// body origin) that satisfy every condition: (n_nodes * 6) x r, r <= 6.
// Free-free: r = 6; a panel pinned at two points: r = 1 (turning about their line).
// Couplings never restrict rigid motions; a held distributing interface is a
// point condition at its reference point here.
Eigen::MatrixXd admissibleRigidModes(const Mesh& mesh, const std::vector<PointCondition>& conditions);

// Skew matrix: skew(a) b = a x b.
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

// Motion of a point at X + d rigidly attached to a node moving (u, theta): G(d) = [I -skew(d); 0 I].
Eigen::Matrix<double, 6, 6> rigidTransfer(const Eigen::Vector3d& d);

// T^T K T of one element whose nodes are `nodes` (element matrix 6a x 6a in
// body DOF order), and the reduced global indices of its rows.
void reduceElement(const DofMap& map, const std::vector<long>& nodes, const Eigen::MatrixXd& Ke,
                   Eigen::MatrixXd& Kr, std::vector<long>& indices);

}  // namespace fc::feprep
