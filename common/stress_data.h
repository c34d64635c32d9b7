#pragma once
// What stress recovery needs from a flexible body file (layout in
// docs/body-file.md, "Stress recovery data"): fe-prep computes it with the
// modes, writeFlexBody stores it under /mesh/centroids and /stress/, and
// mbs-run reads it (readStressData, common/flexbody.h) only for the bodies a
// scene names in `outputs: {stresses: [...]}`.
#include <Eigen/Dense>
#include <string>
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

// A beam section's stress recovery basis, from section-prep's /recovery/
// (contracts.md, docs/section-prep.md "Stress recovery"), carried by fe-prep
// into the body file under /stress/section/ (docs/body-file.md).
struct SectionStressBasis {
  // (3 n_se, 6): row 3s + c is component c of [s_11, s_22, t_12] of section
  // element s in its material axes per unit resultant [N, V2, V3, T, M2, M3]
  // (the section file's /recovery/ply_stress (6, n_se, 3), column-major).
  Eigen::MatrixXd ply_stress;
  Eigen::MatrixXd centroids;          // (n_se, 2): (x2, x3) [m]
  std::vector<std::string> material;  // (n_se) material names
  std::vector<long> has_plies;        // (n_se) 1 for a ply material, 0 isotropic (section frame)
  Eigen::MatrixXd strength;           // (n_se, 5): Xt Xc Yt Yc S12 [Pa], zero rows where none
  long size() const { return centroids.rows(); }
  bool empty() const { return size() == 0; }
};

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
  // Beams whose section file has a recovery basis: the basis, and each
  // element's length (the stations at its ends follow from the midpoint
  // resultants by equilibrium).
  SectionStressBasis section;
  Eigen::VectorXd beam_lengths;
  Eigen::MatrixXd beam_stations;  // (3 n_el, 3): each element's first node, midpoint, second node, body frame [m]
  bool empty() const { return centroids.rows() == 0; }
  bool hasShell() const { return shell_strains.rows() > 0 && plies.size() > 0; }
  bool hasBeam() const { return beam_resultants.rows() > 0; }
};

}  // namespace fc
