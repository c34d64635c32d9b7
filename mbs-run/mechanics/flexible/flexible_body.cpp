#include "mbs-run/mechanics/flexible/flexible_body.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/files.h"
#include "common/h5io.h"

namespace fc::mbs {

const FlexInterface* FlexibleBodyData::findInterface(const std::string& name) const {
  for (const auto& it : interfaces)
    if (it.name == name) return &it;
  return nullptr;
}

std::vector<std::string> FlexibleBodyData::interfaceNames() const {
  std::vector<std::string> names;
  for (const auto& it : interfaces) names.push_back(it.name);
  return names;
}

Marker FlexibleBodyData::marker(const std::string& interface, const Eigen::Matrix3d& axes) const {
  const FlexInterface* it = findInterface(interface);
  if (!it) {
    std::string known;
    for (const auto& n : interfaceNames()) known += (known.empty() ? "" : ", ") + n;
    throw std::out_of_range(file + " has no interface '" + interface + "' (it has: " +
                            (known.empty() ? "none" : known) + ")");
  }
  return markerFromInterface(*it, modes, axes);
}

double flexibleBodySize(const FlexibleBodyData& f, double mass, const Eigen::Matrix3d& inertia_com,
                        const Eigen::Vector3d& com) {
  double size = std::sqrt(std::max(inertia_com.trace(), 0.0) / mass);
  for (const FlexInterface& it : f.interfaces) size = std::max(size, (it.position - com).norm());
  return size;
}

InterfaceMotion interfaceMotion(const FlexInterface& it, const Eigen::VectorXd& q) {
  return {(it.shapes.leftCols(3).transpose() * q).norm(), (it.shapes.rightCols(3).transpose() * q).norm()};
}

Eigen::VectorXd fixedInterfaceStrainEnergies(const FlexibleBodyData& b, const Eigen::VectorXd& q) {
  if (b.fixed_interface_coordinates.size() == 0) return {};
  const Eigen::VectorXd eta = b.fixed_interface_coordinates.transpose() * q;
  return 0.5 * b.fixed_interface_eigenvalues.cwiseProduct(eta.cwiseAbs2());
}

FlexibleBodyData loadFlexibleBody(const std::string& file, int modes, double damping_ratio) {
  const FlexBodyFile f = readFlexBody(file, modes, FlexBodyParts::Dynamics);
  FlexibleBodyData b;
  b.file = file;
  b.modes = f.invariants.n_modes;
  b.damping_ratio = damping_ratio;
  b.inertia = f.invariants;
  b.modal = modalProperties(f.body.eigenvalues, damping_ratio);
  b.frequencies_hz = f.body.frequencies_hz;
  b.interfaces = f.body.interfaces;
  if (f.body.fixed_interface_coordinates.size() && b.modes > 0) {
    b.fixed_interface_coordinates = f.body.fixed_interface_coordinates;
    b.fixed_interface_eigenvalues = f.body.kept_eigenvalues;
    b.fixed_interface_modes = f.body.kept_modes;
  }
  // The node form reads the nodal masses and shapes, so it is considered only
  // when it can be the cheaper one: every node of a mesh moves along at least
  // one axis, so its rows r are at least the node count.
  if (b.modes > 0 && nodalFormCheaper(H5File(file, H5File::Mode::Read).shape("/mesh/nodes").at(0), b.modes)) {
    const FlexBodyFile all = readFlexBody(file, modes, FlexBodyParts::All);
    auto nodal = std::make_shared<NodalInertia>(nodalInertia(all.body, b.modes));
    if (nodalFormCheaper(nodal->rows(), b.modes)) b.nodal = std::move(nodal);
  }
  if (!b.nodal && b.modes > 0) {
    auto sparse = std::make_shared<SparseModalProducts>(sparseModalProducts(b.inertia));
    if (sparseFormCheaper(*sparse)) b.sparse = std::move(sparse);
  }
  return b;
}

FlexibleBodyData loadFlexibleBody(const InputNode& flexible) {
  flexible.allowKeys({"file", "modes", "damping_ratio", "geometric_stiffening"});
  const InputNode file_node = flexible["file"];
  const std::string file = resolveRelativeTo(flexible.file(), file_node.asString());
  int available = 0;
  try {
    available = flexBodyModeCount(file);
  } catch (const H5Error& e) {
    file_node.fail(std::string("expected a flexible body file written by fe-prep: ") + e.what());
  }
  int modes = available;
  if (auto m = flexible.get("modes"); m && !(m->isScalar() && m->asString() == "all")) {
    // modes: all (the default) keeps every shape: a Craig-Bampton basis is
    // statically complete at its interfaces only whole.
    const long asked = m->asInt();
    if (asked < 0) m->fail("expected a number of modes >= 0, got " + std::to_string(asked));
    if (asked > available)
      m->fail(file + " holds " + std::to_string(available) + " modes, " + std::to_string(asked) +
              " asked (rebuild it with fe-prep 'modes: " + std::to_string(asked) + "' or ask for fewer)");
    modes = static_cast<int>(asked);
  }
  double zeta = 0.0;
  // A ratio of critical damping: structures have 0.001-0.1, the overdamped
  // settling runs of the tests 1; beyond 100 a value is a typo.
  if (auto z = flexible.get("damping_ratio")) zeta = z->asInRange(0.0, 100.0, "(ratio of critical damping)");
  FlexibleBodyData b;
  try {
    b = loadFlexibleBody(file, modes, zeta);
  } catch (const H5Error& e) {
    file_node.fail(e.what());
  } catch (const std::invalid_argument& e) {
    file_node.fail(e.what());
  }
  if (auto g = flexible.get("geometric_stiffening"); g && g->asBool() && b.modes > 0) {
    try {
      b.stiffening = std::make_shared<const GeometricStiffening>(readGeometricStiffening(file, b.modes));
    } catch (const std::bad_alloc&) {
      throw;  // out of memory is no input error
    } catch (const std::exception& e) {
      g->fail(e.what());
    }
  }
  return b;
}

}  // namespace fc::mbs
