// The flexible body's arrays and the quantities computed from them (invariants,
// rigid properties, physical checks); its file I/O is flexbody_file.cpp (HDF5).
#include "common/flexbody.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace fc {

const std::array<const char*, kGeometricStiffnessCaseCount> kGeometricStiffnessCases = {
    "a_x", "a_y", "a_z", "w_x w_x", "w_y w_y", "w_z w_z", "w_x w_y", "w_y w_z", "w_z w_x",
    "alpha_x", "alpha_y", "alpha_z"};


namespace {

std::string str(long v) { return std::to_string(v); }

}  // namespace

void checkFlexBodySizes(const FlexBody& b, const InertiaInvariants* inv, const std::string& where) {
  const long n = b.nodeCount();
  const int nm = b.modeCount();
  auto bad = [&](const std::string& what) {
    throw std::invalid_argument(where + ": body '" + b.name + "': " + what);
  };
  if (b.nodes.cols() != 3) bad("nodes must be (n_nodes, 3), got " + str(b.nodes.cols()) + " columns");
  if (b.nodal_mass.rows() != n || b.nodal_mass.cols() != 4)
    bad("nodal_mass must be (" + str(n) + ", 4), got (" + str(b.nodal_mass.rows()) + ", " +
        str(b.nodal_mass.cols()) + ")");
  if ((b.shapes.rows() != 6 * n || b.shapes.cols() != nm) && !(nm == 0 && b.shapes.size() == 0))
    bad("shapes must be (6 n_nodes, n_modes) = (" + str(6 * n) + ", " + str(nm) + "), got (" +
        str(b.shapes.rows()) + ", " + str(b.shapes.cols()) + ")");
  if (b.frequencies_hz.size() != nm)
    bad("frequencies_hz must have one entry per eigenvalue (" + str(nm) + ")");
  for (const auto& it : b.interfaces) {
    if (it.node < 0 || it.node >= n) bad("interface " + it.name + ": node " + str(it.node) + " out of range");
    if (it.shapes.rows() != nm || it.shapes.cols() != 6)
      bad("interface " + it.name + ": shapes must be (" + str(nm) + ", 6)");
  }
  if (b.kept_eigenvalues.size() != static_cast<long>(b.kept_modes.size()))
    bad("kept_eigenvalues must have one entry per kept mode (" + str(static_cast<long>(b.kept_modes.size())) + ")");
  if (b.fixed_interface_coordinates.size() &&
      (b.fixed_interface_coordinates.rows() != nm || b.fixed_interface_coordinates.cols() != static_cast<long>(b.kept_modes.size())))
    bad("fixed_interface_coordinates must be (n_modes, n_kept) = (" + str(nm) + ", " +
        str(static_cast<long>(b.kept_modes.size())) + ")");
  for (const auto& [type, conn] : b.elements)
    for (long i = 0; i < conn.size(); ++i)
      if (conn.data()[i] < 0 || conn.data()[i] >= n) bad("elements " + type + ": node index out of range");
  if (!b.geometric_stiffness.empty()) {
    if (static_cast<int>(b.geometric_stiffness.size()) != kGeometricStiffnessCaseCount)
      bad("geometric_stiffness must hold " + str(kGeometricStiffnessCaseCount) + " load cases");
    for (const auto& k : b.geometric_stiffness)
      if (k.rows() != nm || k.cols() != nm) bad("geometric_stiffness matrices must be (" + str(nm) + ", " + str(nm) + ")");
  }
  for (const auto& it : b.interfaces) {
    if (it.geometric_stiffness.empty()) continue;
    if (it.geometric_stiffness.size() != 6) bad("interface " + it.name + ": geometric_stiffness must hold 6 load cases");
    for (const auto& k : it.geometric_stiffness)
      if (k.rows() != nm || k.cols() != nm)
        bad("interface " + it.name + ": geometric_stiffness matrices must be (" + str(nm) + ", " + str(nm) + ")");
  }
  if (inv && inv->n_modes != nm)
    bad("invariants are for " + str(inv->n_modes) + " modes, the body has " + str(nm));
}

// ---------------------------------------------------------------------------

const FlexInterface& FlexBody::interface(const std::string& n) const {
  std::string known;
  for (const auto& it : interfaces) {
    if (it.name == n) return it;
    known += (known.empty() ? "" : ", ") + it.name;
  }
  throw std::out_of_range("body '" + name + "' has no interface '" + n + "' (it has: " +
                          (known.empty() ? "none" : known) + ")");
}

Eigen::Matrix3d InertiaInvariants::inertiaAboutOrigin() const {
  return second_moment.trace() * Eigen::Matrix3d::Identity() - second_moment + rotary_inertia;
}

Eigen::MatrixXd InertiaInvariants::modalMass() const {
  Eigen::MatrixXd m = rotary_modal_mass;
  for (int a = 0; a < 3; ++a) m += modal_products[4 * a];
  return m;
}

InertiaInvariants InertiaInvariants::truncated(int n) const {
  if (n < 0 || n > n_modes)
    throw std::invalid_argument("invariants hold " + std::to_string(n_modes) + " modes, " +
                                std::to_string(n) + " asked");
  InertiaInvariants t = *this;
  t.n_modes = n;
  t.modal_first_moment = modal_first_moment.leftCols(n);
  t.modal_second_moment = modal_second_moment.leftCols(n);
  for (int i = 0; i < 9; ++i) t.modal_products[i] = modal_products[i].topLeftCorner(n, n);
  t.rotary_modal = rotary_modal.leftCols(n);
  t.rotary_modal_mass = rotary_modal_mass.topLeftCorner(n, n);
  return t;
}

InertiaInvariants computeInertiaInvariants(const FlexBody& body, int n_modes) {
  checkFlexBodySizes(body, nullptr, "computeInertiaInvariants");
  const int nm = n_modes < 0 ? body.modeCount() : n_modes;
  if (nm > body.modeCount())
    throw std::invalid_argument("computeInertiaInvariants: body '" + body.name + "' has " +
                                std::to_string(body.modeCount()) + " modes, " +
                                std::to_string(nm) + " asked");
  InertiaInvariants inv;
  inv.n_modes = nm;
  inv.modal_first_moment = Eigen::MatrixXd::Zero(3, nm);
  inv.modal_second_moment = Eigen::MatrixXd::Zero(9, nm);
  for (auto& s : inv.modal_products) s = Eigen::MatrixXd::Zero(nm, nm);
  inv.rotary_modal = Eigen::MatrixXd::Zero(3, nm);
  inv.rotary_modal_mass = Eigen::MatrixXd::Zero(nm, nm);

  const long n = body.nodeCount();
  for (long k = 0; k < n; ++k) {
    const double m = body.nodal_mass(k, 0);
    const Eigen::Vector3d s0 = body.nodes.row(k).transpose();
    inv.mass += m;
    inv.first_moment += m * s0;
    inv.second_moment += m * s0 * s0.transpose();
    inv.rotary_inertia += body.nodal_mass.row(k).tail<3>().asDiagonal();
  }
  if (nm == 0) return inv;
  // The modal sums over nodes as products of (nodes x modes) matrices, one per
  // displacement component c (the shapes' rows 6k + c), taken a block of
  // nodes at a time: S_ab = sum_k m_k Phi_ka^T Phi_kb = X_a^T diag(m) X_b.
  // Blocks keep the copies small whatever the mesh; the products are GEMMs.
  constexpr long kBlock = 256;
  using Rows = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, 6>>;
  std::array<Eigen::MatrixXd, 6> X, mX;
  for (long k0 = 0; k0 < n; k0 += kBlock) {
    const long b = std::min(kBlock, n - k0);
    const Eigen::VectorXd m = body.nodal_mass.col(0).segment(k0, b);
    for (int c = 0; c < 6; ++c) {
      X[c] = Rows(body.shapes.data() + 6 * k0 + c, b, nm, Eigen::Stride<Eigen::Dynamic, 6>(body.shapes.rows(), 6));
      // Translations weighted by the nodal mass, rotations by the rotary inertia about axis c - 3.
      mX[c] = (c < 3 ? m : Eigen::VectorXd(body.nodal_mass.col(c - 2).segment(k0, b))).asDiagonal() * X[c];
    }
    for (int a = 0; a < 3; ++a) {
      inv.modal_first_moment.row(a) += m.transpose() * X[a];
      const Eigen::VectorXd ms = m.cwiseProduct(body.nodes.col(a).segment(k0, b));
      for (int c = 0; c < 3; ++c) {
        inv.modal_second_moment.row(3 * a + c) += ms.transpose() * X[c];
        inv.modal_products[3 * a + c].noalias() += X[a].transpose() * mX[c];
      }
      inv.rotary_modal.row(a) += body.nodal_mass.col(a + 1).segment(k0, b).transpose() * X[3 + a];
      inv.rotary_modal_mass.noalias() += X[3 + a].transpose() * mX[3 + a];
    }
  }
  return inv;
}

InertiaInvariants rigidInvariants(double mass, const Eigen::Vector3d& c, const Eigen::Matrix3d& Jc) {
  InertiaInvariants inv;
  inv.mass = mass;
  inv.first_moment = mass * c;
  inv.second_moment = mass * c * c.transpose();
  inv.rotary_inertia = Jc;
  inv.modal_first_moment.resize(3, 0);
  inv.modal_second_moment.resize(9, 0);
  for (auto& s : inv.modal_products) s.resize(0, 0);
  inv.rotary_modal.resize(3, 0);
  inv.rotary_modal_mass.resize(0, 0);
  return inv;
}

void setRigidPropertiesFromLumpedMasses(FlexBody& body) {
  FlexBody rigid = body;
  rigid.shapes.resize(6 * body.nodeCount(), 0);
  rigid.eigenvalues.resize(0);
  rigid.frequencies_hz.resize(0);
  rigid.interfaces.clear();
  rigid.geometric_stiffness.clear();
  rigid.fixed_interface_coordinates.resize(0, 0);
  const InertiaInvariants inv = computeInertiaInvariants(rigid, 0);
  body.mass = inv.mass;
  body.center_of_mass = inv.centerOfMass();
  body.inertia_tensor = inv.inertiaAboutOrigin();
}

// ---------------------------------------------------------------------------

std::string flexBodyPhysicalProblem(const FlexBody& body) {
  std::ostringstream os;
  os << std::setprecision(4);
  if (!(body.mass > 0) || !std::isfinite(body.mass)) {
    os << "its mass is " << body.mass << " kg; expected a positive mass";
    return os.str();
  }
  if (!body.center_of_mass.allFinite() || !body.inertia_tensor.allFinite())
    return "its centre of mass or inertia tensor holds a non-finite number";
  // About the centre of mass (parallel axes): a rigid body's equations need it
  // positive definite, else its mass matrix is singular and no integrator can run.
  const Eigen::Vector3d c = body.center_of_mass;
  const Eigen::Matrix3d Ic = body.inertia_tensor - body.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (Ic + Ic.transpose()));
  const Eigen::Vector3d p = es.eigenvalues();
  const double scale = std::max(p.cwiseAbs().maxCoeff(), 1e-300);
  if (p.minCoeff() <= 1e-10 * scale) {
    const Eigen::Vector3d axis = es.eigenvectors().col(0);
    os << "its inertia tensor about the centre of mass is singular (principal moments " << p(0) << ", "
       << p(1) << ", " << p(2) << " kg m^2; the smallest about the axis [" << axis.x() << ", "
       << axis.y() << ", " << axis.z()
       << "]): all its mass lies on a line, e.g. a beam whose section mass has no rotary inertia; "
          "give the section its rotary (polar) inertia";
    return os.str();
  }
  // Triangle inequalities of principal moments (a physical mass distribution).
  if (p(0) + p(1) < p(2) * (1 - 1e-9)) {
    os << "its principal moments " << p(0) << ", " << p(1) << ", " << p(2)
       << " kg m^2 violate the triangle inequality: no mass distribution has them";
    return os.str();
  }
  return "";
}
std::string modeViewName(int mode_index) {
  char name[32];
  std::snprintf(name, sizeof name, "mode_%02d", mode_index + 1);
  return name;
}

}  // namespace fc
