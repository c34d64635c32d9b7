#pragma once
// Small dense models for the element tests: a structured triangle mesh of a
// rectangle [0,a] x [0,b] in the z = 0 plane, dense assembly, boundary
// conditions by DOF elimination, and the generalized eigenproblem.
#include <Eigen/Dense>
#include <array>
#include <Eigen/Sparse>
#include <vector>

#include "fe-prep/elements/shell_triangle.h"

namespace fc::fe::test {

struct PlateMesh {
  int nx = 0, ny = 0;
  double a = 0, b = 0;
  std::vector<Eigen::Vector3d> nodes;
  std::vector<std::array<int, 3>> triangles;
  int node(int i, int j) const { return j * (nx + 1) + i; }
};

// Each cell is split along alternating diagonals (a "herringbone" pattern) so
// that the mesh has no single preferred diagonal direction.
PlateMesh rectangleMesh(double a, double b, int nx, int ny);

struct Assembled {
  Eigen::MatrixXd K, M;  // 6 DOF per node, body frame
};
Assembled assembleShell(const PlateMesh& mesh, const LaminateStiffness& lam, ShellKind kind,
                        bool lumped, double drilling = 1e-4,
                        const Eigen::Vector3d& material_x = Eigen::Vector3d::UnitX());

// The same plate assembled sparse (consistent mass) for meshes too large for
// the dense solver: the lowest `count` angular frequencies on the DOF `keep`,
// by subspace iteration on K^-1 M (block of 2 count + 4 vectors, Rayleigh-Ritz
// each step) until the eigenvalues settle to 1e-12 relative.
std::vector<double> lowestOmegasSparse(const PlateMesh& mesh, const LaminateStiffness& lam,
                                       ShellKind kind, const std::vector<int>& keep, int count);

// Sorted generalized eigenvalues of (K, M) restricted to the DOF in `keep`.
Eigen::VectorXd eigenvalues(const Assembled& sys, const std::vector<int>& keep);

// Bending DOF (w, theta_x, theta_y) of a flat plate in z = 0 that survive the
// given support: 'S' = hard simple support on all edges (w and the tangential
// rotation fixed), 'C' = clamped along x = 0 (cantilever).
std::vector<int> plateBendingDofs(const PlateMesh& mesh, char support);

}  // namespace fc::fe::test
