#pragma once
// A flexible body of a scene, loaded from its body file: the scene's
//   flexible: {file: panel.h5, modes: 14, damping_ratio: 0.01}
// (file relative to the scene; modes: how many of the file's first modes, 0 = the
// rigid body of the same inertia, default all; damping_ratio: modal, default 0;
// geometric_stiffening: true adds the stiffness of the body's inertial loads).
// Holds exactly what the dynamics needs: invariants, modal stiffness and damping,
// interfaces (for markers), the body's rigid properties.
#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "common/flexbody.h"
#include "common/input.h"
#include "mbs-run/mechanics/flexible/flexible_inertia.h"
#include "mbs-run/mechanics/flexible/geometric_stiffening.h"
#include "mbs-run/mechanics/flexible/marker.h"
#include "mbs-run/mechanics/flexible/modal.h"
#include "mbs-run/mechanics/flexible/nodal_inertia.h"

namespace fc::mbs {

struct FlexibleBodyData {
  std::string file;  // as resolved
  int modes = 0;
  double damping_ratio = 0.0;
  InertiaInvariants inertia;
  // The node form of the second-order inertia terms when it is the cheaper
  // one for this body's nodes and modes (nodal_inertia.h), decided at load
  // time; null: the invariants' nm x nm products.
  std::shared_ptr<const NodalInertia> nodal;
  // Otherwise the invariants' S_ab over their non-zero entries when that is
  // cheaper (modal_products.h); null: the dense S_ab.
  std::shared_ptr<const SparseModalProducts> sparse;
  // The form the inertia kernels are given (flexible_inertia.h).
  SecondOrderForm secondOrder() const { return {nodal.get(), sparse.get()}; }
  ModalProperties modal;
  Eigen::VectorXd frequencies_hz;
  std::vector<FlexInterface> interfaces;  // shapes restricted to the first `modes` modes
  // Craig-Bampton bodies (the file's /reduction/fixed_interface_coordinates;
  // empty otherwise): eta = F^T q gives the fixed-interface modal amplitudes,
  // whose strain energies lambda_j eta_j^2 / 2 the run summary reports (which
  // fixed-interface modes a run excited: what fe-prep's modes: {keep: [...]}
  // can then choose). Numbers 1-based as in the file.
  Eigen::MatrixXd fixed_interface_coordinates;  // (modes, n_kept)
  Eigen::VectorXd fixed_interface_eigenvalues;
  std::vector<long> fixed_interface_modes;
  // geometric_stiffening: true (geometric_stiffening.h); null when off: nothing computed.
  std::shared_ptr<const GeometricStiffening> stiffening;

  const FlexInterface* findInterface(const std::string& name) const;  // nullptr if absent
  std::vector<std::string> interfaceNames() const;
  // Marker at an interface; throws std::out_of_range listing the known names.
  Marker marker(const std::string& interface,
                const Eigen::Matrix3d& axes = Eigen::Matrix3d::Identity()) const;
};

// A flexible body's size, against which its interfaces' deflections are
// judged (initial modal state, assembled start): its radius of gyration about
// the centre of mass, or its farthest interface from it if that is larger.
double flexibleBodySize(const FlexibleBodyData& f, double mass, const Eigen::Matrix3d& inertia_com,
                        const Eigen::Vector3d& com);
// How far modal state q moves interface `it`: |Phi_u^T q| [m] and |Phi_theta^T q| [rad].
struct InterfaceMotion {
  double displacement = 0.0, rotation = 0.0;
};
InterfaceMotion interfaceMotion(const FlexInterface& it, const Eigen::VectorXd& q);

// Each fixed-interface mode's strain energy lambda_j eta_j^2 / 2, eta = F^T q,
// at modal state q (empty for bodies without fixed_interface_coordinates).
// Exact: a Craig-Bampton reduced stiffness is block diagonal, the constraint
// modes' block and diag(lambda), so these and the boundary's part add up to
// q^T diag(omega^2) q / 2.
Eigen::VectorXd fixedInterfaceStrainEnergies(const FlexibleBodyData& b, const Eigen::VectorXd& q);

// From the scene's `flexible:` block; every problem is an fc::InputError at the
// offending key (unknown key, missing/unreadable/foreign file at `file`, more
// modes than the file holds at `modes`, negative eigenvalue or damping).
FlexibleBodyData loadFlexibleBody(const InputNode& flexible);
// Direct form (no scene): errors as fc::H5Error / std::invalid_argument.
FlexibleBodyData loadFlexibleBody(const std::string& file, int modes, double damping_ratio);

}  // namespace fc::mbs
