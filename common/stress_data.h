#pragma once
// What stress recovery needs from a flexible body file (layout in
// docs/body-file.md, "Stress recovery data"): fe-prep computes it with the
// modes, writeFlexBody stores it under /mesh/centroids and /stress/, and
// mbs-run reads it (readStressData, common/flexbody.h) only for the bodies a
// scene names in `outputs: {stresses: [...]}`.
#include <Eigen/Dense>
#include <vector>

#include "common/laminate.h"

namespace fc {

// The plies of a shell's laminate as stress recovery sees them, bottom up.
struct PlyTable {
  Eigen::VectorXd z_mid;                   // (n_plies) mid-thickness z from the mid-surface [m]
  Eigen::VectorXd angle_deg;               // (n_plies) fibre angle from the laminate x axis [deg]
  std::vector<Eigen::Matrix3d> stiffness;  // reduced stiffness Q in material axes [Pa], order [11, 22, 12]
  Eigen::MatrixXd strength;                // (n_plies, 5): Xt Xc Yt Yc S12 [Pa]; empty unless every ply has one
  long size() const { return static_cast<long>(z_mid.size()); }
  bool hasStrength() const { return strength.rows() == size() && size() > 0; }
};

// The ply table of `lam` (materials must hold every ply's material; the
// reduced stiffness is reducedStiffness of common/laminate.h, the one the
// shell's ABD matrices are built from).
PlyTable plyTable(const Laminate& lam, const MaterialLibrary& materials);

struct StressRecoveryData {
  // (n_elements, 3): element centroids (triangles) or midpoints (beams), body frame [m].
  Eigen::MatrixXd centroids;
  // Shells: (6 n_elements, n_modes), row 6e + c is component c of element e at
  // its centroid for unit modal coordinate: [eps_xx, eps_yy, gamma_xy,
  // kappa_xx, kappa_yy, kappa_xy] in the laminate axes (column-major storage
  // is the file's C-order (n_modes, n_elements, 6)). Empty for beams.
  Eigen::MatrixXd shell_strains;
  PlyTable plies;  // shells
  // Beams: (6 n_elements, n_modes), row 6e + c is component c of element e's
  // section resultants [N, V2, V3, T, M2, M3] at its midpoint, in its section
  // axes, per unit modal coordinate (fc::fe::beamModalResultants; file C-order
  // (n_modes, n_elements, 6), /stress/section_resultants). Empty for shells.
  Eigen::MatrixXd beam_resultants;
  bool empty() const { return centroids.rows() == 0; }
  bool hasShell() const { return shell_strains.rows() > 0 && plies.size() > 0; }
  bool hasBeam() const { return beam_resultants.rows() > 0; }
};

}  // namespace fc
