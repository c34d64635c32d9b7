#pragma once
// Stress recovery from the modal coordinates of a run (docs/stresses.md),
// only for the bodies a scene names in `outputs: {stresses: [...]}`: the
// others cost nothing. Theory, sources and validation: docs/stresses.md.
//
// Shells (classical lamination theory, Reddy, Mechanics of Laminated
// Composite Plates and Shells, 2nd ed., ch. 3; Jones, Mechanics of Composite
// Materials, 2nd ed., ch. 2 and 4):
//   e = S q                      generalised strains [eps0; kappa] per element
//                                centroid (S from the body file's /stress/strains)
//   eps(z) = eps0 + z kappa      in the laminate axes, at each ply's mid-plane
//   eps_12 = T(theta) eps(z)     to the ply's material axes (engineering shear)
//   sigma_12 = Q eps_12          the ply's reduced stiffness
//   F = Tsai-Wu(sigma_12)        contracts.md's formula, failure at 1
//   H = Hashin(sigma_12)         four mode indices, plane-stress form
//                                (common/failure_criteria.h), beside F
// A body's recovery is a BodyStressRecovery: its datasets and one recover()
// that dispatches on the kind of body, so that another kind (beams' section
// forces) joins by adding its data, its outputs and its branch.
#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

#include "common/failure_criteria.h"
#include "common/stress_data.h"

namespace fc::mbs {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Strength5 = Eigen::Matrix<double, 5, 1>;  // Xt Xc Yt Yc S12 [Pa]

// ---- kernels (plain functions; each tested alone, tests/mbs-run/monitors/test_stress_recovery.cpp)

// In-plane strain [eps_x, eps_y, gamma_xy] at height z of generalised strains
// e = [eps0; kappa]: eps0 + z kappa (Kirchhoff kinematics; Reddy eq. 3.3.9).
Eigen::Vector3d strainAtHeight(const Vector6d& e, double z);

// Engineering-strain transformation from the laminate axes to the axes of a
// ply whose fibre lies at angle_rad from the laminate x axis, positive about
// the normal: eps_12 = T eps_xy (Jones eq. 2.84 with the Reuter matrix;
// Reddy eq. 2.3.19): rows [c^2, s^2, cs], [s^2, c^2, -cs], [-2cs, 2cs, c^2 - s^2].
Eigen::Matrix3d strainToPlyAxes(double angle_rad);

// Tsai-Wu coefficients of contracts.md (Tsai & Wu, J. Compos. Mater. 5 (1971)
// 58; F12 = -sqrt(F11 F22)/2 as Tsai & Hahn recommend).
struct TsaiWu {
  double F1 = 0, F2 = 0, F11 = 0, F22 = 0, F66 = 0, F12 = 0;
};
TsaiWu tsaiWuCoefficients(const Strength5& strength);
PlyStrength plyStrength(const Strength5& strength);
// F1 s1 + F2 s2 + F11 s1^2 + F22 s2^2 + F66 t12^2 + 2 F12 s1 s2 of
// sigma = [s1, s2, t12] in material axes; failure at 1.
double tsaiWuIndex(const TsaiWu& c, const Eigen::Vector3d& sigma);

// The (3 n_plies, 6) operator from an element's generalised strains to the
// stresses of all its plies in their material axes, stacked ply by ply:
// row block k = Q_k T(theta_k) [I, z_k I].
Eigen::MatrixXd plyStressOperator(const PlyTable& plies);

// ---- one body's recovery

// A dataset the recovery writes under /bodies/NAME/ at each output, the
// output-time dimension leading: e.g. "ply_stress" with dims {n_el, n_plies, 3}.
struct StressOutput {
  std::string name;
  std::vector<long> dims;
  long size() const;
};

struct BodyStressRecovery {
  // Shell: ply stresses and failure indices; Beam: section forces
  // (mbs-run/mechanics/flexible/section_forces.h).
  enum class Kind { Shell, Beam };
  Kind kind = Kind::Shell;
  std::string file;           // the body file, for messages
  long n_elements = 0;
  std::vector<StressOutput> outputs;  // in the order recover() fills them
  int failure_output = -1;            // index into outputs of the failure index, -1 if none
  int hashin_output = -1;             // index into outputs of the Hashin indices (.., 4), -1 if none
  long n_plies = 0;                   // shells

  // Shells: (6 n_el, n_modes) strains per unit modal coordinate, the ply
  // stress operator and the plies' Tsai-Wu coefficients (empty without strengths).
  Eigen::MatrixXd shell_strains;
  Eigen::MatrixXd ply_operator;
  std::vector<TsaiWu> tsai_wu;
  std::vector<PlyStrength> ply_strength;     // (n_plies) with tsai_wu, for Hashin

  // Beams: (6 n_el, n_modes) midpoint section resultants per unit modal coordinate.
  Eigen::MatrixXd beam_resultants;
  // Beams whose section has a recovery basis (SectionStressBasis): the ply
  // stresses of every section element at 3 stations per element (its first
  // node, midpoint, second node); n_plies then counts section elements, so a
  // failure location's (element, ply) is (station, section element).
  Eigen::MatrixXd section_ply;               // (3 n_se, 6) per unit resultant
  Eigen::VectorXd beam_lengths;              // (n_el)
  Eigen::MatrixXd stations;                  // (3 n_el, 3) body frame, written as /bodies/NAME/stations
  std::vector<char> section_has_strength;    // (n_se)
  std::vector<TsaiWu> section_tsai_wu;       // (n_se), unused where no strength
  std::vector<PlyStrength> section_strength; // (n_se), unused where no strength
  // The output holding the stresses that go with the failure index (the
  // envelope's *_at_peak): 0 for shells, the beam's ply_stress otherwise.
  int ply_output = 0;
  // A body mixing shells and beams (stressRecovery): its beams as a beam
  // body's recovery, whose outputs are this one's from mixedShellOutputs on,
  // so that the beams' envelope and peak section moment are a beam body's.
  std::shared_ptr<const BodyStressRecovery> beam_part;

  // fields[i] (outputs[i].size() values, C order) at modal coordinates q.
  void recover(const Eigen::VectorXd& q, std::vector<Eigen::VectorXd>& fields) const;

 private:
  void recoverBeamPlies(std::vector<Eigen::VectorXd>& fields) const;

 public:
};

// Section resultants [N, V2, V3, T, M2, M3] at a station s along an element
// (from its midpoint, along the element's x1) from the midpoint values R, by
// the equilibrium of an element without distributed load, M2' = V3,
// M3' = -V2 (the FE model's masses are at the nodes): R + s [0,0,0,0,V3,-V2].
Vector6d resultantsAtStation(const Vector6d& mid, double s);

// A body's recovery for its first n_modes modes from the data of its file
// (readStressData): a shell's ply stresses, or a beam's section forces. Throws
// fc::H5Error naming the file when it has none.
std::shared_ptr<const BodyStressRecovery> loadStressRecovery(const std::string& body_file, int n_modes);

// Beam recovery from data in memory: one output, "section_forces" (n_el, 6).
std::shared_ptr<const BodyStressRecovery> beamStressRecovery(const StressRecoveryData& data,
                                                             const std::string& file = "");

// Shell recovery from data in memory (tests, benchmarks).
std::shared_ptr<const BodyStressRecovery> shellStressRecovery(const StressRecoveryData& data,
                                                              const std::string& file = "");

// Where a failure index peaks: largest value over elements and plies of one field.
struct FailureLocation {
  double value = 0.0;
  long element = -1, ply = -1;
};
FailureLocation largestFailureIndex(const BodyStressRecovery& r, const Eigen::VectorXd& failure_index);

}  // namespace fc::mbs
