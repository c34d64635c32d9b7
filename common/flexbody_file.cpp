// The body file (contract layout "flexbody/1"): writeFlexBody, readFlexBody and the
// stress data readers, on HDF5 (common/h5io.h). Kept apart from flexbody.cpp so that
// a program that computes bodies without writing them links no HDF5 (fe-prep's
// serial program loads this code as a module, for the write only).
#include "common/flexbody.h"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "common/h5io.h"

namespace fc {

namespace {

constexpr int kFormatVersion = 1;

std::string str(long v) { return std::to_string(v); }

// ---- raw HDF5 for rank > 3 writes and partial (hyperslab) reads -------------

struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

void writeArray(H5File& f, const std::string& path, const std::vector<hsize_t>& dims,
                const double* data) {
  Handle lcpl{H5Pcreate(H5P_LINK_CREATE), H5Pclose};
  H5Pset_create_intermediate_group(lcpl.id, 1);
  Handle space{H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose};
  Handle set{H5Dcreate2(f.id(), path.c_str(), H5T_IEEE_F64LE, space.id, lcpl.id, H5P_DEFAULT,
                        H5P_DEFAULT),
             H5Dclose};
  bool empty = false;
  for (hsize_t d : dims) empty = empty || d == 0;
  if (set.id < 0 || (!empty && H5Dwrite(set.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
    throw H5Error(f.path() + ": cannot write dataset " + path + hdf5ErrorReason());
}

// (n, width) virtual views of columns [first, first + width) of the (n_sets, n, cols)
// dataset `source` in the same file, one per leading index: ParaView's Xdmf3 readers
// read no XDMF hyperslab (they skip such fields), so the body's XDMF names these plain
// datasets. HDF5 virtual datasets store only the mapping: no value is written twice.
void writeColumnView(H5File& f, const std::string& path, const std::string& source,
                     const std::vector<hsize_t>& source_dims, hsize_t set, hsize_t first, hsize_t width) {
  const hsize_t n = source_dims[source_dims.size() - 2];
  Handle lcpl{H5Pcreate(H5P_LINK_CREATE), H5Pclose};
  H5Pset_create_intermediate_group(lcpl.id, 1);
  Handle dcpl{H5Pcreate(H5P_DATASET_CREATE), H5Pclose};
  const hsize_t view_dims[2] = {n, width};
  Handle view{H5Screate_simple(width == 1 ? 1 : 2, view_dims, nullptr), H5Sclose};
  Handle src{H5Screate_simple(static_cast<int>(source_dims.size()), source_dims.data(), nullptr), H5Sclose};
  std::vector<hsize_t> start(source_dims.size(), 0), count = source_dims;
  if (source_dims.size() == 3) start[0] = set, count[0] = 1;
  start.back() = first;
  count.back() = width;
  bool ok = lcpl.id >= 0 && dcpl.id >= 0 && view.id >= 0 && src.id >= 0 &&
            H5Sselect_hyperslab(src.id, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) >= 0 &&
            H5Pset_virtual(dcpl.id, view.id, ".", source.c_str(), src.id) >= 0;
  if (ok) {
    Handle set_id{H5Dcreate2(f.id(), path.c_str(), H5T_IEEE_F64LE, view.id, lcpl.id, dcpl.id, H5P_DEFAULT),
                  H5Dclose};
    ok = set_id.id >= 0;
  }
  if (!ok) throw H5Error(f.path() + ": cannot write the view " + path + " of " + source + hdf5ErrorReason());
}

std::string dimsText(const std::vector<hsize_t>& d) {
  std::ostringstream s;
  s << "(";
  for (std::size_t i = 0; i < d.size(); ++i) s << (i ? ", " : "") << d[i];
  s << ")";
  return s.str();
}

// Reads the leading block [0, count_i) of each dimension of a float64 dataset whose
// shape must be (>= count_0, ..., exactly count_i where exact[i]). Only that block
// is transferred from the file.
// No number of a body file (SI units, modes mass-normalised) comes near this; a
// larger one is a damaged or foreign file. Finite 1e300 values passed the reader
// and made the results' peak reaction force or failure index infinite, refused
// only when the results were written (an error naming the temporary, not the body
// file: fuzz campaign on the new datasets, session 6).
constexpr double kMaxBodyNumber = 1e30;
const char* const kBeyondBodyNumbers = ", beyond 1e30: no body's number is that large (a damaged or foreign file)";

std::string magnitudeText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::vector<double> readLeading(const H5File& f, const std::string& path,
                                const std::vector<hsize_t>& count,
                                const std::vector<bool>& exact) {
  if (!f.exists(path)) throw H5Error(f.path() + ": missing dataset " + path + " (flexbody/1 layout)");
  const std::vector<hsize_t> shape = f.shape(path);
  bool ok = shape.size() == count.size();
  for (std::size_t i = 0; ok && i < count.size(); ++i)
    ok = exact[i] ? shape[i] == count[i] : shape[i] >= count[i];
  if (!ok)
    throw H5Error(f.path() + ": dataset " + path + " has shape " + dimsText(shape) +
                  ", expected at least " + dimsText(count));
  std::size_t n = 1;
  for (hsize_t c : count) n *= c;
  std::vector<double> out(n);
  if (n == 0) return out;
  Handle set{H5Dopen2(f.id(), path.c_str(), H5P_DEFAULT), H5Dclose};
  Handle fspace{H5Dget_space(set.id), H5Sclose};
  std::vector<hsize_t> start(count.size(), 0);
  H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  Handle mspace{H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose};
  if (H5Dread(set.id, H5T_NATIVE_DOUBLE, mspace.id, fspace.id, H5P_DEFAULT, out.data()) < 0)
    throw H5Error(f.path() + ": cannot read dataset " + path + " as numbers");
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      throw H5Error(f.path() + ": dataset " + path + " holds a non-finite value (" +
                    std::to_string(out[i]) + " at flat index " + std::to_string(i) + ")");
    else if (std::abs(out[i]) > kMaxBodyNumber)
      throw H5Error(f.path() + ": dataset " + path + " holds " + magnitudeText(out[i]) + " at flat index " +
                    std::to_string(i) + kBeyondBodyNumbers);
  return out;
}

double finiteScalar(const H5File& f, const std::string& path) {
  const double v = f.readScalar(path);
  if (!std::isfinite(v)) throw H5Error(f.path() + ": " + path + " is not a finite number");
  if (std::abs(v) > kMaxBodyNumber) throw H5Error(f.path() + ": " + path + " is " + magnitudeText(v) + kBeyondBodyNumbers);
  return v;
}

// Row-major (rows, cols) block into an Eigen matrix.
Eigen::MatrixXd rowMajor(const std::vector<double>& d, long rows, long cols) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      d.data(), rows, cols);
}

}  // namespace

namespace {

long n_elements(const FlexBody& b) {
  long n = 0;
  for (const auto& kv : b.elements) n += kv.second.rows();
  return n;
}

// A beam's section recovery basis under /stress/section/ (docs/body-file.md).
void writeSectionBasis(H5File& f, const StressRecoveryData& d, long n_el) {
  const SectionStressBasis& s = d.section;
  if (s.empty()) return;
  const long ns = s.size();
  if (s.ply_stress.rows() != 3 * ns || s.ply_stress.cols() != 6 || static_cast<long>(s.material.size()) != ns ||
      static_cast<long>(s.has_plies.size()) != ns || s.strength.rows() != ns || s.strength.cols() != 5 ||
      d.beam_lengths.size() != n_el || d.beam_stations.rows() != 3 * n_el || d.beam_stations.cols() != 3)
    throw std::invalid_argument(f.path() + ": the section recovery basis's columns differ in length");
  // Column-major (3 ns, 6) is C-order (6, ns, 3), as the section file's /recovery/ply_stress.
  writeArray(f, "/stress/section/ply_stress", {6, static_cast<hsize_t>(ns), 3}, s.ply_stress.data());
  f.writeMatrix("/stress/section/centroids", s.centroids);
  f.writeStrings("/stress/section/material", s.material);
  f.writeIntVector("/stress/section/has_plies", s.has_plies);
  f.writeMatrix("/stress/section/strength", s.strength);
  f.writeVector("/stress/beam_lengths", d.beam_lengths);
  f.writeMatrix("/stress/stations", d.beam_stations);
}

// /mesh/centroids and, for shells, /stress/strains and /stress/plies/*, for
// beams /stress/section_resultants (docs/body-file.md, "Stress recovery
// data"). A mixed body's /mesh/centroids lists its triangles, then its beams.
void writeStressData(H5File& f, const StressRecoveryData& d, long n_el, int nm) {
  const std::string where = f.path() + ": stress recovery data: ";
  const long n_beam = d.hasBeam() ? d.beam_resultants.rows() / 6 : 0;
  const long n_shell = n_el - n_beam;
  if (d.hasBeam() && (d.beam_resultants.rows() % 6 != 0 || (!d.hasShell() && n_beam != n_el)))
    throw std::invalid_argument(where + "beam section resultants must be (6 n_beams, n_modes)");
  if (d.centroids.rows() != n_el || d.centroids.cols() != 3)
    throw std::invalid_argument(where + "centroids must be (n_elements, 3) = (" + str(n_el) + ", 3)");
  f.writeMatrix("/mesh/centroids", d.centroids);
  if (d.hasBeam()) {
    if (d.beam_resultants.rows() != 6 * n_beam || d.beam_resultants.cols() != nm)
      throw std::invalid_argument(where + "beam section resultants must be (6 n_beams, n_modes)");
    // Column-major (6 n_el, nm) is C-order (nm, n_el, 6), as /modes/shapes.
    writeArray(f, "/stress/section_resultants", {static_cast<hsize_t>(nm), static_cast<hsize_t>(n_beam), 6},
               d.beam_resultants.data());
    writeSectionBasis(f, d, n_beam);
  }
  if (!d.hasShell()) return;
  const long np = d.plies.size();
  if (d.shell_strains.rows() != 6 * n_shell || d.shell_strains.cols() != nm)
    throw std::invalid_argument(where + "shell strains must be (6 n_triangles, n_modes)");
  if (d.plies.angle_deg.size() != np || static_cast<long>(d.plies.stiffness.size()) != np ||
      (d.plies.strength.rows() != 0 && d.plies.strength.rows() != np))
    throw std::invalid_argument(where + "the ply table's columns differ in length");
  // Column-major (6 n_el, nm) is C-order (nm, n_el, 6), as /modes/shapes.
  writeArray(f, "/stress/strains", {static_cast<hsize_t>(nm), static_cast<hsize_t>(n_shell), 6}, d.shell_strains.data());
  f.writeVector("/stress/plies/z_mid", d.plies.z_mid);
  f.writeVector("/stress/plies/angle_deg", d.plies.angle_deg);
  std::vector<double> q;
  for (const Eigen::Matrix3d& Q : d.plies.stiffness)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) q.push_back(Q(i, j));
  writeArray(f, "/stress/plies/stiffness", {static_cast<hsize_t>(np), 3, 3}, q.data());
  if (d.plies.hasStrength()) f.writeMatrix("/stress/plies/strength", d.plies.strength);
}

}  // namespace

namespace {

// /regions/NAME: each region's members, mass, axes and what it is (docs/body-file.md, Regions).
void writeRegions(H5File& f, const std::vector<FlexRegion>& regions) {
  for (const FlexRegion& r : regions) {
    std::string key = r.name;  // a group name may hold a '/', a link name may not
    std::replace(key.begin(), key.end(), '/', '_');
    const std::string g = "/regions/" + (key.empty() ? std::string("_") : key);
    f.writeIntVector(g + "/members", r.members);
    if (r.kind != "set") f.writeScalar(g + "/mass", r.mass);
    if (r.axes.rows() > 0) f.writeMatrix(g + "/axes", r.axes);
    f.setAttribute(g, "name", r.name);
    f.setAttribute(g, "kind", r.kind);
    f.setAttribute(g, "members_of", r.members_of);
    if (!r.property.empty()) f.setAttribute(g, "property", r.property);
    if (!r.element.empty()) f.setAttribute(g, "element", r.element);
    if (!r.axis.empty()) f.setAttribute(g, "axis", r.axis);
    if (!r.summary.empty()) f.setAttribute(g, "summary", r.summary);
  }
}

}  // namespace

void writeFlexBody(const std::string& path, const FlexBody& body, const InertiaInvariants& inv,
                   const Provenance& prov) {
  try {
    checkFlexBodySizes(body, &inv, path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("cannot write flexible body file ") + e.what());
  }
  if (const std::string why = flexBodyPhysicalProblem(body); !why.empty())
    throw std::invalid_argument("body '" + body.name + "': " + why);
  const long n = body.nodeCount();
  const int nm = body.modeCount();
  const hsize_t un = static_cast<hsize_t>(n), um = static_cast<hsize_t>(nm);

  AtomicH5Writer writer(path);
  H5File& f = writer.file();
  writeProvenance(f, "flexbody/" + std::to_string(kFormatVersion), prov.tool, prov.inputs_sha256);
  if (!prov.version.empty()) f.setAttribute("/", "version", prov.version);
  f.setAttribute("/", "name", body.name);
  if (!body.reduction.empty()) f.setAttribute("/", "reduction", body.reduction);

  f.writeMatrix("/mesh/nodes", body.nodes);
  for (const auto& [type, conn] : body.elements) f.writeIntMatrix("/mesh/" + type, conn);
  f.writeMatrix("/mass/nodal", body.nodal_mass);
  writeRegions(f, body.regions);

  writeArray(f, "/modes/eigenvalues", {um}, body.eigenvalues.data());
  writeArray(f, "/modes/frequencies_hz", {um}, body.frequencies_hz.data());
  // Column-major (6n, nm) storage is exactly C-order (nm, n, 6): written from
  // the body's own array (the largest of the file), never a copy.
  const Eigen::MatrixXd no_modes(6 * n, 0);
  writeArray(f, "/modes/shapes", {um, un, 6}, (body.shapes.rows() == 0 ? no_modes : body.shapes).data());
  // The per-mode fields of BODY.xdmf (fe-prep/xdmf_writer.cpp): views, not copies.
  if (n > 0) {
    writeColumnView(f, "/view/nodal_mass", "/mass/nodal", {un, 4}, 0, 0, 1);
    for (int j = 0; j < nm; ++j) {
      const std::string base = "/view/" + modeViewName(j);
      writeColumnView(f, base, "/modes/shapes", {um, un, 6}, j, 0, 3);
      writeColumnView(f, base + "_rotation", "/modes/shapes", {um, un, 6}, j, 3, 3);
    }
  }

  f.writeScalar("/inertia/mass", body.mass);
  f.writeVector("/inertia/center_of_mass", body.center_of_mass);
  f.writeMatrix("/inertia/tensor", body.inertia_tensor);
  if (body.has_exact_inertia) {
    f.writeScalar("/inertia/exact/mass", body.exact_mass);
    f.writeVector("/inertia/exact/center_of_mass", body.exact_center_of_mass);
    f.writeMatrix("/inertia/exact/tensor", body.exact_inertia_tensor);
  }

  if (!body.kept_modes.empty()) {
    f.writeIntVector("/reduction/kept_modes", body.kept_modes);
    f.writeVector("/reduction/kept_eigenvalues", body.kept_eigenvalues);
    if (body.fixed_interface_coordinates.size()) {
      const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c = body.fixed_interface_coordinates;
      writeArray(f, "/reduction/fixed_interface_coordinates", {um, static_cast<hsize_t>(c.cols())}, c.data());
    }
  }

  f.createGroup("/interfaces");
  for (const auto& it : body.interfaces) {
    const std::string g = "/interfaces/" + it.name;
    f.writeInt(g + "/node", it.node);
    f.writeVector(g + "/position", it.position);
    const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> s = it.shapes;
    writeArray(f, g + "/shapes", {um, 6}, s.data());
    if (it.static_error.size() == 6 && it.static_participation.rows() == nm) {
      f.writeVector(g + "/static_compliance", it.static_compliance);
      f.writeVector(g + "/static_error", it.static_error);
      const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> p = it.static_participation;
      writeArray(f, g + "/static_participation", {um, 6}, p.data());
    }
  }

  if (!body.geometric_stiffness.empty()) {
    // (n_cases, nm, nm), C order; each matrix symmetric, so storage order is moot.
    std::vector<double> g;
    for (const auto& k : body.geometric_stiffness) g.insert(g.end(), k.data(), k.data() + k.size());
    writeArray(f, "/geometric_stiffness/matrices", {static_cast<hsize_t>(kGeometricStiffnessCaseCount), um, um}, g.data());
    std::string cases;
    for (const char* c : kGeometricStiffnessCases) cases += (cases.empty() ? "" : ", ") + std::string(c);
    f.setAttribute("/geometric_stiffness/matrices", "cases", cases);
  }
  for (const auto& it : body.interfaces) {
    if (it.geometric_stiffness.empty()) continue;
    std::vector<double> g;
    for (const auto& k : it.geometric_stiffness) g.insert(g.end(), k.data(), k.data() + k.size());
    const std::string path = "/geometric_stiffness/interfaces/" + it.name + "/matrices";
    writeArray(f, path, {6, um, um}, g.data());
    f.setAttribute(path, "cases", "force_x, force_y, force_z, moment_x, moment_y, moment_z");
  }

  // Invariants, mode index leading so that the first nm modes are a leading hyperslab.
  f.writeScalar("/invariants/mass", inv.mass);
  f.writeVector("/invariants/first_moment", inv.first_moment);
  f.writeMatrix("/invariants/second_moment", inv.second_moment);
  f.writeMatrix("/invariants/rotary_inertia", inv.rotary_inertia);
  Eigen::MatrixXd s1 = inv.modal_first_moment;  // (3, nm) column-major == C-order (nm, 3)
  writeArray(f, "/invariants/modal_first_moment", {um, 3}, s1.data());
  // (nm, 3, 3): [j][a][b] = C(3a+b, j); column-major (9, nm) is that C order.
  Eigen::MatrixXd c = inv.modal_second_moment;
  writeArray(f, "/invariants/modal_second_moment", {um, 3, 3}, c.data());
  std::vector<double> prod(static_cast<std::size_t>(nm) * nm * 9);
  for (int j = 0; j < nm; ++j)
    for (int l = 0; l < nm; ++l)
      for (int ab = 0; ab < 9; ++ab) prod[(static_cast<std::size_t>(j) * nm + l) * 9 + ab] = inv.modal_products[ab](j, l);
  writeArray(f, "/invariants/modal_products", {um, um, 3, 3}, prod.data());
  Eigen::MatrixXd jt = inv.rotary_modal;
  writeArray(f, "/invariants/rotary_modal", {um, 3}, jt.data());
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jtt = inv.rotary_modal_mass;
  writeArray(f, "/invariants/rotary_modal_mass", {um, um}, jtt.data());
  if (!body.stress.empty()) writeStressData(f, body.stress, n_elements(body), nm);
  writer.commit();
}

namespace {

int modeCount(const H5File& f) {
  f.checkFormat("flexbody", kFormatVersion);
  if (!f.exists("/modes/eigenvalues"))
    throw H5Error(f.path() + ": missing dataset /modes/eigenvalues (flexbody/1 layout)");
  const std::vector<hsize_t> shape = f.shape("/modes/eigenvalues");
  if (shape.size() != 1) throw H5Error(f.path() + ": /modes/eigenvalues must be a vector, got shape " + dimsText(shape));
  return static_cast<int>(shape[0]);
}

}  // namespace

namespace {

// /inertia/ holds exactly what the invariants imply (fe-prep writes both from
// the same nodal masses), so a disagreement beyond round-off is a damaged or
// foreign file; caught here, it is an error naming the file instead of a run
// whose dynamics use one body and whose report another (a mass invariant
// scaled by 1e300 used to end as "step size too small").
std::string invariantsDisagreeWithInertia(const FlexBody& b, const InertiaInvariants& inv) {
  // Relative 1e-9: the two are computed from the same sums (measured 1e-16 on
  // fe-prep's files); well above round-off, far below any physical difference.
  constexpr double kAgree = 1e-9;
  std::ostringstream os;
  os << std::setprecision(10);
  if (!(std::abs(inv.mass - b.mass) <= kAgree * b.mass)) {
    os << "/invariants/mass is " << inv.mass << " kg but /inertia/mass " << b.mass
       << " kg; the two must agree (a damaged file, or one not written by fe-prep)";
    return os.str();
  }
  const Eigen::Matrix3d I = inv.inertiaAboutOrigin();
  const double scale = b.inertia_tensor.cwiseAbs().maxCoeff();
  const double length = std::sqrt(scale / b.mass);  // the body's radius of gyration about the origin
  if (!((inv.first_moment / inv.mass - b.center_of_mass).norm() <= kAgree * std::max(length, b.center_of_mass.norm()))) {
    os << "/invariants/first_moment puts the centre of mass at [" << (inv.first_moment / inv.mass).transpose()
       << "] m but /inertia/center_of_mass says [" << b.center_of_mass.transpose() << "] m; the two must agree";
    return os.str();
  }
  if (!((I - b.inertia_tensor).cwiseAbs().maxCoeff() <= kAgree * scale)) {
    os << "the invariants (/invariants/second_moment, rotary_inertia) give an inertia about the origin of diagonal ["
       << I.diagonal().transpose() << "] kg m^2 but /inertia/tensor has [" << b.inertia_tensor.diagonal().transpose()
       << "]; the two must agree";
    return os.str();
  }
  return "";
}

}  // namespace

int flexBodyModeCount(const std::string& path) { return modeCount(H5File(path, H5File::Mode::Read)); }

FlexBodyFile readFlexBody(const std::string& path, int n_modes, FlexBodyParts parts) {
  H5File f(path, H5File::Mode::Read);
  FlexBodyFile out;
  const int in_file = modeCount(f);
  out.provenance.format = f.stringAttribute("/", "format");
  if (f.hasAttribute("/", "tool")) out.provenance.tool = f.stringAttribute("/", "tool");
  if (f.hasAttribute("/", "version")) out.provenance.version = f.stringAttribute("/", "version");
  if (f.hasAttribute("/", "inputs_sha256"))
    out.provenance.inputs_sha256 = f.stringAttribute("/", "inputs_sha256");
  FlexBody& b = out.body;
  if (f.hasAttribute("/", "name")) b.name = f.stringAttribute("/", "name");
  if (f.hasAttribute("/", "reduction")) b.reduction = f.stringAttribute("/", "reduction");

  out.modes_in_file = in_file;
  const int nm = n_modes < 0 ? in_file : n_modes;
  if (nm > in_file)
    throw H5Error(path + ": the body file holds " + std::to_string(in_file) + " modes, " +
                  std::to_string(nm) + " asked (rebuild it with fe-prep 'modes: " +
                  std::to_string(nm) + "' or ask for fewer)");
  const hsize_t um = static_cast<hsize_t>(nm);

  const std::vector<double> ev = readLeading(f, "/modes/eigenvalues", {um}, {false});
  const std::vector<double> fr = readLeading(f, "/modes/frequencies_hz", {um}, {false});
  b.eigenvalues = Eigen::Map<const Eigen::VectorXd>(ev.data(), nm);
  b.frequencies_hz = Eigen::Map<const Eigen::VectorXd>(fr.data(), nm);

  b.mass = finiteScalar(f, "/inertia/mass");
  const std::vector<double> com = readLeading(f, "/inertia/center_of_mass", {3}, {true});
  b.center_of_mass = Eigen::Vector3d(com[0], com[1], com[2]);
  b.inertia_tensor = rowMajor(readLeading(f, "/inertia/tensor", {3, 3}, {true, true}), 3, 3);
  if (f.exists("/inertia/exact/mass")) {
    b.has_exact_inertia = true;
    b.exact_mass = finiteScalar(f, "/inertia/exact/mass");
    const std::vector<double> ec = readLeading(f, "/inertia/exact/center_of_mass", {3}, {true});
    b.exact_center_of_mass = Eigen::Vector3d(ec[0], ec[1], ec[2]);
    b.exact_inertia_tensor = rowMajor(readLeading(f, "/inertia/exact/tensor", {3, 3}, {true, true}), 3, 3);
  }

  if (f.exists("/reduction/kept_modes")) {
    b.kept_modes = f.readIntVector("/reduction/kept_modes");
    const hsize_t nk = static_cast<hsize_t>(b.kept_modes.size());
    const std::vector<double> ke = readLeading(f, "/reduction/kept_eigenvalues", {nk}, {true});
    b.kept_eigenvalues = Eigen::Map<const Eigen::VectorXd>(ke.data(), static_cast<long>(nk));
    if (f.exists("/reduction/fixed_interface_coordinates"))
      b.fixed_interface_coordinates =
          rowMajor(readLeading(f, "/reduction/fixed_interface_coordinates", {um, nk}, {false, true}), nm, static_cast<long>(nk));
  }

  if (f.exists("/interfaces"))
    for (const std::string& name : f.children("/interfaces")) {
      FlexInterface it;
      const std::string g = "/interfaces/" + name;
      it.name = name;
      it.node = f.readInt(g + "/node");
      const std::vector<double> p = readLeading(f, g + "/position", {3}, {true});
      it.position = Eigen::Vector3d(p[0], p[1], p[2]);
      it.shapes = rowMajor(readLeading(f, g + "/shapes", {um, 6}, {false, true}), nm, 6);
      b.interfaces.push_back(std::move(it));
    }

  InertiaInvariants& inv = out.invariants;
  inv.n_modes = nm;
  inv.mass = finiteScalar(f, "/invariants/mass");
  const std::vector<double> s0 = readLeading(f, "/invariants/first_moment", {3}, {true});
  inv.first_moment = Eigen::Vector3d(s0[0], s0[1], s0[2]);
  inv.second_moment = rowMajor(readLeading(f, "/invariants/second_moment", {3, 3}, {true, true}), 3, 3);
  inv.rotary_inertia = rowMajor(readLeading(f, "/invariants/rotary_inertia", {3, 3}, {true, true}), 3, 3);
  inv.modal_first_moment =
      rowMajor(readLeading(f, "/invariants/modal_first_moment", {um, 3}, {false, true}), nm, 3).transpose();
  inv.modal_second_moment =
      rowMajor(readLeading(f, "/invariants/modal_second_moment", {um, 3, 3}, {false, true, true}), nm, 9)
          .transpose();
  const std::vector<double> prod =
      readLeading(f, "/invariants/modal_products", {um, um, 3, 3}, {false, false, true, true});
  for (int ab = 0; ab < 9; ++ab) {
    inv.modal_products[ab].resize(nm, nm);
    for (int j = 0; j < nm; ++j)
      for (int l = 0; l < nm; ++l) inv.modal_products[ab](j, l) = prod[(static_cast<std::size_t>(j) * nm + l) * 9 + ab];
  }
  inv.rotary_modal = rowMajor(readLeading(f, "/invariants/rotary_modal", {um, 3}, {false, true}), nm, 3).transpose();
  inv.rotary_modal_mass =
      rowMajor(readLeading(f, "/invariants/rotary_modal_mass", {um, um}, {false, false}), nm, nm);

  if (const std::string why = flexBodyPhysicalProblem(b); !why.empty())
    throw H5Error(path + ": body '" + b.name + "': " + why);
  if (const std::string why = invariantsDisagreeWithInertia(b, inv); !why.empty())
    throw H5Error(path + ": body '" + b.name + "': " + why);

  if (parts == FlexBodyParts::All) {
    const std::vector<hsize_t> nd = f.shape("/mesh/nodes");
    if (nd.size() != 2 || nd[1] != 3) throw H5Error(path + ": /mesh/nodes must be (n_nodes, 3), got " + dimsText(nd));
    b.nodes = f.readMatrix("/mesh/nodes", static_cast<Eigen::Index>(nd[0]), 3);
    const long n = b.nodes.rows();
    const hsize_t un = static_cast<hsize_t>(n);
    for (const std::string& child : f.children("/mesh")) {
      if (child == "nodes" || child == "centroids") continue;  // connectivity only
      const std::vector<hsize_t> sh = f.shape("/mesh/" + child);
      const std::vector<long> flat = f.readIntVector("/mesh/" + child);
      const long cols = sh.size() == 2 ? static_cast<long>(sh[1]) : 1;
      b.elements[child] = Eigen::Map<const IndexMatrix>(flat.data(), static_cast<long>(flat.size()) / cols, cols);
    }
    b.nodal_mass = rowMajor(readLeading(f, "/mass/nodal", {un, 4}, {true, true}), n, 4);
    const std::vector<double> sh = readLeading(f, "/modes/shapes", {um, un, 6}, {false, true, true});
    b.shapes = Eigen::Map<const Eigen::MatrixXd>(sh.data(), 6 * n, nm);
  }
  return out;
}

namespace {

// The shell part of readStressData: /stress/strains over the une triangles
// and the ply table /stress/plies/*.
void readShellStressData(H5File& f, const std::string& path, hsize_t une, int n_modes, StressRecoveryData& d) {
  const long ne = static_cast<long>(une);
  const hsize_t um = static_cast<hsize_t>(n_modes);
  const std::vector<double> st = readLeading(f, "/stress/strains", {um, une, 6}, {false, true, true});
  d.shell_strains = Eigen::Map<const Eigen::MatrixXd>(st.data(), 6 * ne, n_modes);
  const std::vector<hsize_t> zs = f.shape("/stress/plies/z_mid");
  if (zs.size() != 1 || zs[0] == 0) throw H5Error(path + ": /stress/plies/z_mid must be (n_plies), n_plies > 0");
  const hsize_t np = zs[0];
  const std::vector<double> z = readLeading(f, "/stress/plies/z_mid", {np}, {true});
  const std::vector<double> a = readLeading(f, "/stress/plies/angle_deg", {np}, {true});
  const std::vector<double> q = readLeading(f, "/stress/plies/stiffness", {np, 3, 3}, {true, true, true});
  d.plies.z_mid = Eigen::Map<const Eigen::VectorXd>(z.data(), static_cast<long>(np));
  d.plies.angle_deg = Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<long>(np));
  for (hsize_t k = 0; k < np; ++k) d.plies.stiffness.push_back(rowMajor(std::vector<double>(q.begin() + 9 * k, q.begin() + 9 * k + 9), 3, 3));
  if (f.exists("/stress/plies/strength")) {
    d.plies.strength = rowMajor(readLeading(f, "/stress/plies/strength", {np, 5}, {true, true}), static_cast<long>(np), 5);
    if ((d.plies.strength.array() <= 0).any())
      throw H5Error(path + ": /stress/plies/strength holds a non-positive strength");
  }
}

}  // namespace

StressRecoveryData readStressData(const std::string& path, int n_modes) {
  H5File f(path, H5File::Mode::Read);
  f.checkFormat("flexbody", kFormatVersion);
  const int in_file = modeCount(f);
  if (n_modes < 0 || n_modes > in_file)
    throw H5Error(path + ": the body file holds " + std::to_string(in_file) + " modes, " + std::to_string(n_modes) +
                  " asked");
  const bool beam = f.exists("/stress/section_resultants");
  const bool shell = f.exists("/stress/strains");
  if (!f.exists("/mesh/centroids") && f.exists("/mesh/triangles") && f.exists("/mesh/beams"))
    throw H5Error(path + ": no stress recovery data: the body mixes shell and beam elements, and the fe-prep that "
                  "wrote it wrote none for such bodies; rebuild it with this fe-prep (docs/stresses.md, \"Mixed bodies\")");
  if (!f.exists("/mesh/centroids") || (!shell && !beam))
    throw H5Error(path + ": no stress recovery data (/mesh/centroids with /stress/strains for shells or "
                  "/stress/section_resultants for beams); a body file written by this fe-prep has them (rebuild it)");
  StressRecoveryData d;
  const std::vector<hsize_t> cs = f.shape("/mesh/centroids");
  if (cs.size() != 2 || cs[1] != 3) throw H5Error(path + ": /mesh/centroids must be (n_elements, 3), got " + dimsText(cs));
  // A mixed body: the triangles' centroids, then the beams' midpoints.
  hsize_t n_shell = shell ? cs[0] : 0;
  if (shell && beam) {
    const std::vector<hsize_t> rs = f.shape("/stress/section_resultants");
    if (rs.size() != 3 || rs[1] > cs[0])
      throw H5Error(path + ": /stress/section_resultants must be (n_modes, n_beams, 6) with n_beams at most the " +
                    std::to_string(cs[0]) + " rows of /mesh/centroids, got " + dimsText(rs));
    n_shell = cs[0] - rs[1];
  }
  const std::vector<double> all = readLeading(f, "/mesh/centroids", {cs[0], 3}, {true, true});
  const Eigen::MatrixXd centroids = rowMajor(all, static_cast<long>(cs[0]), 3);
  const hsize_t um = static_cast<hsize_t>(n_modes);
  if (shell) readShellStressData(f, path, n_shell, n_modes, d);
  d.centroids = centroids;
  if (!beam) return d;
  const long ne = static_cast<long>(cs[0] - n_shell);
  const hsize_t ub = static_cast<hsize_t>(ne);
  const std::vector<double> r = readLeading(f, "/stress/section_resultants", {um, ub, 6}, {false, true, true});
  d.beam_resultants = Eigen::Map<const Eigen::MatrixXd>(r.data(), 6 * ne, n_modes);
  if (f.exists("/stress/section/ply_stress")) {
    const std::vector<hsize_t> ss = f.shape("/stress/section/centroids");
    if (ss.size() != 2 || ss[1] != 2) throw H5Error(path + ": /stress/section/centroids must be (n, 2)");
    const long ns = static_cast<long>(ss[0]);
    SectionStressBasis& s = d.section;
    const std::vector<double> ps = readLeading(f, "/stress/section/ply_stress", {6, ss[0], 3}, {true, true, true});
    s.ply_stress = Eigen::Map<const Eigen::MatrixXd>(ps.data(), 3 * ns, 6);
    s.centroids = rowMajor(readLeading(f, "/stress/section/centroids", {ss[0], 2}, {true, true}), ns, 2);
    s.strength = rowMajor(readLeading(f, "/stress/section/strength", {ss[0], 5}, {true, true}), ns, 5);
    s.material = f.readStrings("/stress/section/material");
    s.has_plies = f.readIntVector("/stress/section/has_plies");
    const std::vector<double> L = readLeading(f, "/stress/beam_lengths", {ub}, {true});
    d.beam_lengths = Eigen::Map<const Eigen::VectorXd>(L.data(), ne);
    d.beam_stations = rowMajor(readLeading(f, "/stress/stations", {3 * ub, 3}, {true, true}), 3 * ne, 3);
    if (static_cast<long>(s.material.size()) != ns || static_cast<long>(s.has_plies.size()) != ns)
      throw H5Error(path + ": /stress/section/material and has_plies must have one entry per section element");
  }
  return d;
}

SectionStressBasis readSectionStressBasis(const std::string& path) {
  H5File f(path, H5File::Mode::Read);
  SectionStressBasis s;
  if (!f.exists("/recovery/ply_stress")) return s;
  const std::vector<hsize_t> sh = f.shape("/recovery/ply_stress");
  if (sh.size() != 3 || sh[0] != 6 || sh[2] != 3)
    throw H5Error(path + ": /recovery/ply_stress must be (6, n_elements, 3), got " + dimsText(sh));
  const long ns = static_cast<long>(sh[1]);
  const std::vector<double> ps = readLeading(f, "/recovery/ply_stress", {6, sh[1], 3}, {true, true, true});
  s.ply_stress = Eigen::Map<const Eigen::MatrixXd>(ps.data(), 3 * ns, 6);
  s.centroids = rowMajor(readLeading(f, "/mesh/centroids", {sh[1], 2}, {true, true}), ns, 2);
  s.material = f.readStrings("/mesh/material");
  s.has_plies = f.readIntVector("/mesh/has_plies");
  const std::vector<long> index = f.readIntVector("/mesh/material_index");
  const Eigen::MatrixXd strength = f.readMatrix("/materials/strength");
  if (static_cast<long>(s.material.size()) != ns || static_cast<long>(s.has_plies.size()) != ns ||
      static_cast<long>(index.size()) != ns || strength.cols() != 5)
    throw H5Error(path + ": /mesh/material, has_plies, material_index and /materials/strength do not match "
                  "/recovery/ply_stress");
  s.strength.resize(ns, 5);
  for (long e = 0; e < ns; ++e) {
    if (index[e] < 0 || index[e] >= strength.rows()) throw H5Error(path + ": /mesh/material_index out of range");
    s.strength.row(e) = strength.row(index[e]);
  }
  return s;
}

}  // namespace fc
