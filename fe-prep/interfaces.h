#pragma once
// Interfaces of a body on its mesh: a point rigidly attached to one node (the
// original kind), or a distributed interface (contracts.md, fe-prep
// "Distributed interfaces") whose reference point is coupled to a patch of nodes
//   rigid (RBE2, CalculiX *KINEMATIC): the patch moves rigidly with the point;
//   distributing (RBE3, CalculiX *DISTRIBUTING): the point moves with the
//     weighted least-squares rigid fit of the patch's translations, adding no
//     stiffness (MSC Nastran Quick Reference Guide, RBE3).
// The RBE3 fit: with d_i = X_i - P and G_i = [I, -skew(d_i)] (3 x 6),
//   minimise sum_i w_i |u_i - G_i [u_P; theta_P]|^2
//   => [u_P; theta_P] = A^-1 sum_i w_i G_i^T u_i,  A = sum_i w_i G_i^T G_i,
// the weights w_i the nodes' tributary areas (shells) or lengths (beams), for box
// patches the areas inside the box (patchAreaWeights). When
// the translations alone cannot fix the rotation (a single node, collinear
// nodes: A singular) the nodal rotations about the undetermined axes (only
// those: never a shell's drilling rotation of an edge patch) join the fit with
// weight w_i Lc^2 (Lc the patch size): a single node then gives exactly the
// rigid offset of the point kind. By virtual work the same W distributes a force at P to the nodes
// (F_i = W_i^T F): joints and forces act on the whole patch.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "fe-prep/body_spec.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

struct MeshInterface {
  std::string name;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Coupling coupling = Coupling::Node;
  long node = -1;            // the attached node (Node), the master (Rigid), the nearest patch node (Distributing)
  std::vector<long> nodes;   // the patch (Rigid, Distributing)
  Eigen::VectorXd weights;   // Distributing
  Eigen::MatrixXd W;         // Distributing: (6, 6 nodes.size()), reference motion from the patch's nodal DOF
};

// Resolves an interface on the mesh (the projection of its point: mid-surface
// for rectangular panels, axis for beams). Errors name the interface's YAML node.
MeshInterface resolveInterface(const Mesh& mesh, const InterfaceSpec& spec, const Eigen::Vector3d& projection);

// Tributary weight of each node: a third of every triangle's area and half of
// every beam element's length touching it.
Eigen::VectorXd tributaryWeights(const Mesh& mesh, const std::vector<long>& nodes);

// Weights of a box patch: the integral of each node's linear shape function over
// the patch's own triangles (all three nodes in the patch). Box patches on
// rectangular panels are meshed conforming (meshRectangle), so this is the
// integral over the box itself: the weights sum to its area and put their centre
// at its centroid at every mesh, their second moments converge as h^2. The full
// tributary areas would add a rim of outside triangles (area and centre O(h)
// off, differently at each mesh). With no triangle inside (a box smaller than a
// mesh file's elements) the full tributary areas.
Eigen::VectorXd patchAreaWeights(const Mesh& mesh, const std::vector<long>& nodes);

// The RBE3 map W (6, 6 p) above.
Eigen::MatrixXd distributingMap(const Mesh& mesh, const std::vector<long>& nodes, const Eigen::VectorXd& weights,
                                const Eigen::Vector3d& point);

// L^T (6 n, 6): the nodal loads of a unit force (columns 0-2) or moment (3-5) at the point.
Eigen::MatrixXd interfaceLoads(const MeshInterface& it, const Mesh& mesh);

// The reference point's motion per mode (n_modes, 6) from the nodal shapes (6 n, n_modes).
Eigen::MatrixXd referencePointShapes(const MeshInterface& it, const Mesh& mesh, const Eigen::MatrixXd& node_shapes);

}  // namespace fc::feprep
