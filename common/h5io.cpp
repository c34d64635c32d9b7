#include "common/h5io.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <set>
#include <sstream>

#include "common/dataset_docs.h"
#include "common/files.h"
#include "common/memory.h"
#include "common/termination.h"
#include "common/version.h"

namespace fc {

namespace {

// HDF5 prints its error stack by default; we report errors ourselves.
// H5dont_atexit: after a failed close (a full disk) HDF5 1.10's own exit-time
// cleanup dereferences the half-closed file and segfaults; every file we write is
// closed explicitly (AtomicH5Writer::commit), so that cleanup has nothing to do.
struct SilenceHdf5 {
  SilenceHdf5() {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
};
const SilenceHdf5 silence_hdf5;

// The most specific description on HDF5's current error stack, e.g. the sec2
// driver's "... errno = 28, error message = 'No space left on device'": the OS
// reason a write failed, which HDF5's own return codes do not carry.
herr_t collectReason(unsigned n, const H5E_error2_t* err, void* data) {
  auto* out = static_cast<std::string*>(data);
  const std::string desc = err->desc ? err->desc : "";
  // The innermost (n == 0) entry is the most specific; keep one naming errno if any.
  if (out->find("errno") == std::string::npos &&
      (n == 0 || desc.find("errno") != std::string::npos))
    *out = desc;
  return 0;
}

}  // namespace

std::string hdf5ErrorReason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, collectReason, &reason);
  const auto pos = reason.find("error message = '");
  if (pos != std::string::npos) {
    const auto start = pos + 17;
    const auto end = reason.find('\'', start);
    reason = reason.substr(start, end == std::string::npos ? std::string::npos : end - start);
  }
  return reason.empty() ? std::string() : " (" + reason + ")";
}

namespace {

// Owns one HDF5 identifier and closes it with the matching H5xclose.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = -1; }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

std::string parentOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  if (pos == std::string::npos || pos == 0) return "/";
  return path.substr(0, pos);
}

void ensureGroups(hid_t file, const std::string& path, const std::string& fname) {
  std::string cur;
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '/')) {
    if (part.empty()) continue;
    cur += "/" + part;
    if (H5Lexists(file, cur.c_str(), H5P_DEFAULT) > 0) continue;
    Handle g(H5Gcreate2(file, cur.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (!g.ok()) throw H5Error(fname + ": cannot create group " + cur + hdf5ErrorReason());
  }
}

void writeRaw(hid_t file, const std::string& fname, const std::string& path, hid_t mem_type,
              hid_t file_type, const std::vector<hsize_t>& dims, const void* data) {
  ensureGroups(file, parentOf(path), fname);
  if (H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0)
    throw H5Error(fname + ": dataset " + path + " already exists");
  Handle space(dims.empty() ? H5Screate(H5S_SCALAR)
                            : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
               H5Sclose);
  Handle dset(H5Dcreate2(file, path.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                         H5P_DEFAULT),
              H5Dclose);
  if (!dset.ok()) throw H5Error(fname + ": cannot create dataset " + path + hdf5ErrorReason());
  if (H5Dwrite(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw H5Error(fname + ": cannot write dataset " + path + hdf5ErrorReason());
}

}  // namespace

// HDF5's metadata cache on opening a file: 1.10 does not check that allocation.
constexpr std::size_t kHdf5OpenHeadroom = 16u << 20;

H5File::H5File(const std::string& path, Mode mode) : path_(path) {
  requireHeadroom(kHdf5OpenHeadroom, "opening " + path + " (HDF5)");
  if (mode == Mode::Read) {
    recordInputFile(path);
    id_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (id_ < 0) throw H5Error(path + ": cannot open as an HDF5 file (missing or not HDF5)");
  } else if (mode == Mode::Create) {
    id_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (id_ < 0) throw H5Error(path + ": cannot create HDF5 file" + hdf5ErrorReason());
  } else {
    // O_CREAT|O_EXCL underneath: fails on an existing file or link, never follows one.
    id_ = H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT);
    if (id_ < 0) throw H5Error(path + ": cannot create HDF5 file" + hdf5ErrorReason());
  }
}

H5File::~H5File() { close(); }

H5File H5File::adopt(hid_t id, const std::string& path) {
  H5File f;
  f.id_ = id;
  f.path_ = path;
  return f;
}

H5File::H5File(H5File&& o) noexcept : id_(o.id_), path_(std::move(o.path_)) { o.id_ = -1; }

H5File& H5File::operator=(H5File&& o) noexcept {
  if (this != &o) {
    close();
    id_ = o.id_;
    path_ = std::move(o.path_);
    o.id_ = -1;
  }
  return *this;
}

void H5File::close() {
  if (id_ >= 0) {
    H5Fclose(id_);
    id_ = -1;
  }
}

void H5File::closeChecked() {
  if (id_ < 0) return;
  // Objects still open would keep the file open past H5Fclose, hiding its errors.
  const ssize_t open_objects = H5Fget_obj_count(id_, H5F_OBJ_ALL | H5F_OBJ_LOCAL);
  if (H5Fflush(id_, H5F_SCOPE_GLOBAL) < 0) {
    const std::string reason = hdf5ErrorReason();
    close();
    throw H5Error(path_ + ": cannot flush the file" + reason);
  }
  const herr_t rc = H5Fclose(id_);
  id_ = -1;
  if (rc < 0) throw H5Error(path_ + ": cannot close the file" + hdf5ErrorReason());
  if (open_objects > 1)
    throw H5Error(path_ + ": " + std::to_string(open_objects - 1) +
                  " HDF5 objects were still open at close (a bug in the writer)");
}

bool H5File::exists(const std::string& object_path) const {
  if (object_path == "/") return true;
  // Check each level: H5Lexists fails on a missing intermediate group.
  std::string cur;
  std::stringstream ss(object_path);
  std::string part;
  while (std::getline(ss, part, '/')) {
    if (part.empty()) continue;
    cur += "/" + part;
    if (H5Lexists(id_, cur.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

std::vector<std::string> H5File::children(const std::string& group_path) const {
  std::vector<std::string> out;
  Handle g(H5Gopen2(id_, group_path.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.ok()) throw H5Error(path_ + ": no group " + group_path);
  H5G_info_t info;
  if (H5Gget_info(g.get(), &info) < 0) throw H5Error(path_ + ": cannot list group " + group_path);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    ssize_t n = H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0,
                                   H5P_DEFAULT);
    // Any length HDF5 stores (a 5000-character joint name is a valid name); the bound
    // only stops a damaged length field from asking for gigabytes.
    if (n < 0 || n > (1 << 20)) throw H5Error(path_ + ": unreadable link name in " + group_path);
    std::string name(static_cast<std::size_t>(n), '\0');
    H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), n + 1,
                       H5P_DEFAULT);
    out.push_back(name);
  }
  return out;
}

namespace {

// File number and address (token from HDF5 1.12) of the object a path leads to:
// equal for every link to one object. False when the path leads nowhere.
bool objectIdentity(hid_t file, const std::string& path, std::string* key, H5O_type_t* type) {
#if H5_VERSION_GE(1, 12, 0)
  H5O_info2_t info;
  if (H5Oget_info_by_name3(file, path.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return false;
  *key = std::to_string(info.fileno) + ":" +
         std::string(reinterpret_cast<const char*>(&info.token), sizeof info.token);
#else
  H5O_info_t info;
  if (H5Oget_info_by_name2(file, path.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return false;
  *key = std::to_string(info.fileno) + ":" + std::to_string(info.addr);
#endif
  *type = info.type;
  return true;
}

// Where a soft or external link points ("FILE:/path" for external ones).
std::string linkTarget(hid_t file, const std::string& path, const H5L_info_t& li) {
  const std::size_t n = li.u.val_size;
  if (n == 0 || n > 65536) return "?";
  std::vector<char> buf(n + 1, '\0');
  if (H5Lget_val(file, path.c_str(), buf.data(), n, H5P_DEFAULT) < 0) return "?";
  if (li.type == H5L_TYPE_SOFT) return std::string(buf.data());
  const char* target_file = nullptr;
  const char* target_path = nullptr;
  unsigned flags = 0;
  if (H5Lunpack_elink_val(buf.data(), n, &flags, &target_file, &target_path) < 0) return "?";
  return std::string(target_file ? target_file : "?") + ":" + (target_path ? target_path : "?");
}

}  // namespace

void walkTree(const H5File& f, const std::string& group,
              const std::function<bool(const H5TreeEntry&)>& enter) {
  std::set<std::string> seen;
  std::string key;
  H5O_type_t type;
  if (!objectIdentity(f.id(), group, &key, &type) || type != H5O_TYPE_GROUP)
    throw H5Error(f.path() + ": no group " + group);
  seen.insert(key);
  // Links still to visit, the next one last: depth first without recursion, so a
  // deeply nested file cannot exhaust the stack either.
  std::vector<std::pair<std::string, int>> pending;
  const auto push_children = [&](const std::string& g, int depth) {
    const std::vector<std::string> kids = f.children(g);
    for (auto it = kids.rbegin(); it != kids.rend(); ++it)
      pending.emplace_back((g == "/" ? "" : g) + "/" + *it, depth);
  };
  push_children(group, 0);
  while (!pending.empty()) {
    H5TreeEntry e;
    e.path = pending.back().first;
    e.depth = pending.back().second;
    pending.pop_back();
    e.name = e.path.substr(e.path.rfind('/') + 1);
    H5L_info_t li;
    if (H5Lget_info(f.id(), e.path.c_str(), &li, H5P_DEFAULT) < 0) {
      e.kind = H5TreeEntry::Kind::Dangling;
      enter(e);
      continue;
    }
    if (li.type == H5L_TYPE_SOFT || li.type == H5L_TYPE_EXTERNAL) e.target = linkTarget(f.id(), e.path, li);
    if (li.type == H5L_TYPE_EXTERNAL) {
      e.kind = H5TreeEntry::Kind::External;
      enter(e);
      continue;
    }
    if (li.type != H5L_TYPE_HARD && li.type != H5L_TYPE_SOFT) {
      e.kind = H5TreeEntry::Kind::Other;
      enter(e);
      continue;
    }
    if (!objectIdentity(f.id(), e.path, &key, &type)) {
      e.kind = H5TreeEntry::Kind::Dangling;
      enter(e);
      continue;
    }
    e.kind = type == H5O_TYPE_GROUP     ? H5TreeEntry::Kind::Group
             : type == H5O_TYPE_DATASET ? H5TreeEntry::Kind::Dataset
                                        : H5TreeEntry::Kind::Other;
    e.seen_before = !seen.insert(key).second;
    if (enter(e) && e.kind == H5TreeEntry::Kind::Group && !e.seen_before) push_children(e.path, e.depth + 1);
  }
}

void H5File::createGroup(const std::string& path) { ensureGroups(id_, path, path_); }

void H5File::writeMatrix(const std::string& path, const Eigen::MatrixXd& m) {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> r = m;
  writeRaw(id_, path_, path, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
           {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())}, r.data());
}

void H5File::writeVector(const std::string& path, const Eigen::VectorXd& v) {
  writeRaw(id_, path_, path, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {static_cast<hsize_t>(v.size())},
           v.data());
}

void H5File::writeScalar(const std::string& path, double value) {
  writeRaw(id_, path_, path, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {}, &value);
}

void H5File::writeInt(const std::string& path, long value) {
  writeRaw(id_, path_, path, H5T_NATIVE_LONG, H5T_STD_I64LE, {}, &value);
}

void H5File::writeIntVector(const std::string& path, const std::vector<long>& v) {
  writeRaw(id_, path_, path, H5T_NATIVE_LONG, H5T_STD_I64LE, {static_cast<hsize_t>(v.size())},
           v.data());
}

void H5File::writeIntMatrix(
    const std::string& path,
    const Eigen::Matrix<long, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& m) {
  writeRaw(id_, path_, path, H5T_NATIVE_LONG, H5T_STD_I64LE,
           {static_cast<hsize_t>(m.rows()), static_cast<hsize_t>(m.cols())}, m.data());
}

void H5File::writeArray3(const std::string& path, const std::vector<double>& data, std::size_t n0,
                         std::size_t n1, std::size_t n2) {
  if (data.size() != n0 * n1 * n2)
    throw H5Error(path_ + ": " + path + ": data size does not match its shape");
  writeRaw(id_, path_, path, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {n0, n1, n2}, data.data());
}

void H5File::writeString(const std::string& path, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.empty() ? 1 : value.size());
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  const std::string v = value.empty() ? std::string(1, '\0') : value;
  writeRaw(id_, path_, path, type.get(), type.get(), {}, v.data());
}

std::vector<std::string> H5File::readStrings(const std::string& path) const {
  Handle dset(H5Dopen2(id_, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw H5Error(path_ + ": missing dataset " + path);
  Handle ftype(H5Dget_type(dset.get()), H5Tclose);
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  if (H5Tget_class(ftype.get()) != H5T_STRING || H5Sget_simple_extent_ndims(space.get()) != 1)
    throw H5Error(path_ + ": " + path + " is not a list of strings");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<std::string> out;
  Handle mtype(H5Tcopy(H5T_C_S1), H5Tclose);
  if (H5Tis_variable_str(ftype.get()) > 0) {
    H5Tset_size(mtype.get(), H5T_VARIABLE);
    std::vector<char*> p(static_cast<std::size_t>(n), nullptr);
    if (H5Dread(dset.get(), mtype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, p.data()) < 0)
      throw H5Error(path_ + ": cannot read " + path + hdf5ErrorReason());
    for (char* s : p) out.emplace_back(s ? s : "");
    H5Dvlen_reclaim(mtype.get(), space.get(), H5P_DEFAULT, p.data());
    return out;
  }
  const std::size_t w = H5Tget_size(ftype.get()) + 1;
  H5Tset_size(mtype.get(), w);
  std::string buf(w * static_cast<std::size_t>(n), '\0');
  if (H5Dread(dset.get(), mtype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    throw H5Error(path_ + ": cannot read " + path + hdf5ErrorReason());
  for (hssize_t i = 0; i < n; ++i) {
    const std::string s = buf.substr(static_cast<std::size_t>(i) * w, w);
    out.push_back(s.substr(0, s.find('\0')));
  }
  return out;
}

void H5File::writeStrings(const std::string& path, const std::vector<std::string>& values) {
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size());
  std::string buf(width * values.size(), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) buf.replace(i * width, values[i].size(), values[i]);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), width);
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  writeRaw(id_, path_, path, type.get(), type.get(), {static_cast<hsize_t>(values.size())}, buf.data());
}

namespace {
Handle openObject(hid_t file, const std::string& fname, const std::string& object_path) {
  Handle obj(H5Oopen(file, object_path.c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.ok()) throw H5Error(fname + ": no object " + object_path);
  return obj;
}

void writeAttribute(hid_t file, const std::string& fname, const std::string& object_path,
                    const std::string& name, hid_t type, const void* data) {
  Handle obj = openObject(file, fname, object_path);
  if (H5Aexists(obj.get(), name.c_str()) > 0) H5Adelete(obj.get(), name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj.get(), name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  if (!attr.ok() || H5Awrite(attr.get(), type, data) < 0)
    throw H5Error(fname + ": cannot write attribute " + name + " on " + object_path + hdf5ErrorReason());
}
}  // namespace

void H5File::setAttribute(const std::string& object_path, const std::string& name,
                          const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.empty() ? 1 : value.size());
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  const std::string v = value.empty() ? std::string(1, '\0') : value;
  writeAttribute(id_, path_, object_path, name, type.get(), v.data());
}

void H5File::setAttribute(const std::string& object_path, const std::string& name, double value) {
  writeAttribute(id_, path_, object_path, name, H5T_NATIVE_DOUBLE, &value);
}

void H5File::setAttribute(const std::string& object_path, const std::string& name, long value) {
  writeAttribute(id_, path_, object_path, name, H5T_NATIVE_LONG, &value);
}

bool H5File::hasAttribute(const std::string& object_path, const std::string& name) const {
  if (!exists(object_path)) return false;
  Handle obj = openObject(id_, path_, object_path);
  return H5Aexists(obj.get(), name.c_str()) > 0;
}

namespace {

// One string from an attribute or a scalar dataset, fixed or variable length.
// h5py writes variable-length UTF-8 strings: the memory type must carry the
// file's character set, or HDF5 refuses the conversion (and the unchecked read
// used to return "" - a section file written from Python had `format` "").
std::string readStringValue(hid_t obj, hid_t ftype, bool is_attribute, const std::string& what) {
  Handle mtype(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_cset(mtype.get(), H5Tget_cset(ftype));
  if (H5Tis_variable_str(ftype) > 0) {
    H5Tset_size(mtype.get(), H5T_VARIABLE);
    char* s = nullptr;
    const herr_t rc = is_attribute ? H5Aread(obj, mtype.get(), &s)
                                   : H5Dread(obj, mtype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &s);
    if (rc < 0) throw H5Error(what + ": cannot read the string" + hdf5ErrorReason());
    std::string out = s ? s : "";
    H5free_memory(s);
    return out;
  }
  // One byte more than stored: a NULLTERM memory type of the same size would
  // drop the last character of a NULLPAD string.
  const std::size_t stored = H5Tget_size(ftype);
  if (stored == 0 || stored > (1u << 24)) throw H5Error(what + ": implausible string size");
  const std::size_t n = stored + 1;
  std::string buf(n, '\0');
  H5Tset_size(mtype.get(), n);
  const herr_t rc = is_attribute
                        ? H5Aread(obj, mtype.get(), buf.data())
                        : H5Dread(obj, mtype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data());
  if (rc < 0) throw H5Error(what + ": cannot read the string" + hdf5ErrorReason());
  return buf.substr(0, buf.find('\0'));
}

}  // namespace

std::string H5File::stringAttribute(const std::string& object_path,
                                    const std::string& name) const {
  Handle obj = openObject(id_, path_, object_path);
  Handle attr(H5Aopen(obj.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attr.ok()) throw H5Error(path_ + ": no attribute '" + name + "' on " + object_path);
  Handle ftype(H5Aget_type(attr.get()), H5Tclose);
  if (H5Tget_class(ftype.get()) != H5T_STRING)
    throw H5Error(path_ + ": attribute '" + name + "' on " + object_path + " is not a string");
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    throw H5Error(path_ + ": attribute '" + name + "' on " + object_path + " is not a single string");
  return readStringValue(attr.get(), ftype.get(), /*is_attribute=*/true,
                         path_ + ": attribute '" + name + "' on " + object_path);
}

double H5File::doubleAttribute(const std::string& object_path, const std::string& name) const {
  Handle obj = openObject(id_, path_, object_path);
  Handle attr(H5Aopen(obj.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attr.ok()) throw H5Error(path_ + ": no attribute '" + name + "' on " + object_path);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if ((cls != H5T_FLOAT && cls != H5T_INTEGER) || H5Sget_simple_extent_npoints(space.get()) != 1)
    throw H5Error(path_ + ": attribute '" + name + "' on " + object_path + " is not a number");
  double v = 0;
  if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    throw H5Error(path_ + ": attribute '" + name + "' on " + object_path + " cannot be read as a number");
  return v;
}

std::vector<hsize_t> H5File::shape(const std::string& path) const {
  Handle dset(H5Dopen2(id_, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw H5Error(path_ + ": missing dataset " + path);
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw H5Error(path_ + ": unreadable shape of " + path);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

namespace {
template <typename T>
std::vector<T> readAll(hid_t file, const std::string& fname, const std::string& path,
                       hid_t mem_type) {
  Handle dset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw H5Error(fname + ": missing dataset " + path);
  // Numbers only: HDF5 would otherwise try (and fail, or worse) to convert strings,
  // compounds or references.
  Handle type(H5Dget_type(dset.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw H5Error(fname + ": dataset " + path + " holds " +
                  (cls == H5T_STRING ? "text" : "non-numeric data") + ", expected numbers");
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) throw H5Error(fname + ": unreadable shape of dataset " + path);
  // A chunked dataset can declare 2^36 numbers and store none (a damaged or hostile
  // file): reading it would ask for terabytes. Past 256 MB, the declared size must be
  // near what the file stores (our writers do not compress; 64x leaves room for others).
  const double declared = static_cast<double>(n) * sizeof(T);
  if (declared > 256.0 * (1 << 20)) {
    const double stored = static_cast<double>(H5Dget_storage_size(dset.get()));
    if (declared > 64.0 * std::max(stored, 1.0))
      throw H5Error(fname + ": dataset " + path + " declares " + std::to_string(n) +
                    " numbers but the file stores " + std::to_string(static_cast<long long>(stored)) +
                    " bytes of it; expected a dataset holding its data (a damaged file?)");
  }
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n > 0 && H5Dread(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw H5Error(fname + ": cannot read dataset " + path + " as numbers");
  return out;
}
}  // namespace

std::vector<double> H5File::readArray(const std::string& path) const {
  return readAll<double>(id_, path_, path, H5T_NATIVE_DOUBLE);
}

Eigen::MatrixXd H5File::readMatrix(const std::string& path) const {
  const auto dims = shape(path);
  const auto data = readArray(path);
  if (dims.size() > 2) throw H5Error(path_ + ": " + path + " has rank > 2");
  const Eigen::Index rows = dims.empty() ? 1 : static_cast<Eigen::Index>(dims[0]);
  const Eigen::Index cols = dims.size() == 2 ? static_cast<Eigen::Index>(dims[1]) : 1;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      data.data(), rows, cols);
}

Eigen::MatrixXd H5File::readMatrix(const std::string& path, Eigen::Index rows, Eigen::Index cols) const {
  const auto dims = shape(path);
  if (dims.size() != 2 || dims[0] != static_cast<hsize_t>(rows) || dims[1] != static_cast<hsize_t>(cols)) {
    std::string got;
    for (std::size_t i = 0; i < dims.size(); ++i) got += (i ? " x " : "") + std::to_string(dims[i]);
    throw H5Error(path_ + ": " + path + " must be a " + std::to_string(rows) + " x " +
                  std::to_string(cols) + " matrix, got " + (dims.empty() ? "a scalar" : got));
  }
  const Eigen::MatrixXd m = readMatrix(path);
  if (!m.allFinite()) throw H5Error(path_ + ": " + path + " holds NaN or infinite values");
  return m;
}

Eigen::VectorXd H5File::readVector(const std::string& path) const {
  const auto data = readArray(path);
  return Eigen::Map<const Eigen::VectorXd>(data.data(), static_cast<Eigen::Index>(data.size()));
}

double H5File::readScalar(const std::string& path) const {
  const auto data = readArray(path);
  if (data.size() != 1) throw H5Error(path_ + ": " + path + " is not a scalar");
  return data[0];
}

long H5File::readInt(const std::string& path) const {
  const auto data = readAll<long>(id_, path_, path, H5T_NATIVE_LONG);
  if (data.size() != 1) throw H5Error(path_ + ": " + path + " is not a scalar");
  return data[0];
}

std::vector<long> H5File::readIntVector(const std::string& path) const {
  return readAll<long>(id_, path_, path, H5T_NATIVE_LONG);
}

std::string H5File::readString(const std::string& path) const {
  Handle dset(H5Dopen2(id_, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw H5Error(path_ + ": missing dataset " + path);
  Handle ftype(H5Dget_type(dset.get()), H5Tclose);
  if (H5Tget_class(ftype.get()) != H5T_STRING)
    throw H5Error(path_ + ": dataset " + path + " is not text");
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    throw H5Error(path_ + ": dataset " + path + " is not a single string");
  return readStringValue(dset.get(), ftype.get(), /*is_attribute=*/false, path_ + ": " + path);
}

int H5File::checkFormat(const std::string& kind, int max_version) const {
  if (!hasAttribute("/", "format"))
    throw H5Error(path_ + ": not a " + kind + " file (no 'format' attribute; expected \"" + kind +
                  "/" + std::to_string(max_version) + "\")");
  const std::string f = stringAttribute("/", "format");
  const auto slash = f.find('/');
  const std::string k = f.substr(0, slash);
  if (k != kind || slash == std::string::npos)
    throw H5Error(path_ + ": format is \"" + f + "\", expected a " + kind + " file (\"" + kind +
                  "/" + std::to_string(max_version) + "\")");
  int version = 0;
  try {
    version = std::stoi(f.substr(slash + 1));
  } catch (const std::exception&) {
    throw H5Error(path_ + ": unreadable format version in \"" + f + "\"");
  }
  if (version > max_version)
    throw H5Error(path_ + ": format \"" + f + "\" is newer than this tool reads (up to " + kind +
                  "/" + std::to_string(max_version) + "); upgrade flexcomp " + FLEXCOMP_VERSION);
  return version;
}

namespace {

// Visits every dataset and attribute of type float and throws naming the first
// non-finite value: no tool writes NaN or inf, whatever path produced it.
struct FiniteCheck {
  std::string file, bad;
};

std::string firstNonFinite(const std::vector<double>& v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) {
      std::ostringstream os;
      os << v[i] << " at flat index " << i;
      return os.str();
    }
  return "";
}

herr_t checkAttributeFinite(hid_t loc, const char* name, const H5A_info_t*, void* data) {
  auto* c = static_cast<FiniteCheck*>(data);
  Handle attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
  if (!attr.ok()) return 0;
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_FLOAT) return 0;
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<double> v(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
  if (n > 0 && H5Aread(attr.get(), H5T_NATIVE_DOUBLE, v.data()) >= 0) {
    const std::string bad = firstNonFinite(v);
    if (!bad.empty()) {
      c->bad = std::string("attribute '") + name + "' is " + bad;
      return 1;
    }
  }
  return 0;
}

herr_t checkObjectFinite(hid_t file, const char* name, const H5O_info_t* info, void* data) {
  auto* c = static_cast<FiniteCheck*>(data);
  const std::string where = std::string("/") + (std::string(name) == "." ? "" : name);
  Handle obj(H5Oopen(file, name, H5P_DEFAULT), H5Oclose);
  if (!obj.ok()) return 0;
  hsize_t idx = 0;
  if (H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, checkAttributeFinite, c) > 0) {
    c->bad = where + ": " + c->bad;
    return 1;
  }
  if (info->type != H5O_TYPE_DATASET) return 0;
  Handle type(H5Dget_type(obj.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_FLOAT) return 0;
  // A virtual dataset (a body's /view/*) holds no value of its own: its
  // sources are checked where they are stored.
  Handle dcpl(H5Dget_create_plist(obj.get()), H5Pclose);
  if (dcpl.ok() && H5Pget_layout(dcpl.get()) == H5D_VIRTUAL) return 0;
  Handle space(H5Dget_space(obj.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  // In slabs of rows of at most 64 Ki values (512 kB) where rows allow, so that
  // the check adds little to the peak of the program that writes (a body's
  // shapes and stress strains are its largest arrays) and a large (streamed)
  // dataset is not loaded whole.
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  if (n <= 0) return 0;
  const hsize_t row = rank > 0 ? static_cast<hsize_t>(n) / dims[0] : 1;
  const hsize_t rows_per_slab = rank > 0 ? std::max<hsize_t>(1, (1u << 16) / std::max<hsize_t>(row, 1)) : 1;
  const hsize_t total_rows = rank > 0 ? dims[0] : 1;
  for (hsize_t r0 = 0; r0 < total_rows; r0 += rows_per_slab) {
    const hsize_t nr = std::min(rows_per_slab, total_rows - r0);
    std::vector<double> v(static_cast<std::size_t>(nr * row));
    herr_t rc;
    if (rank > 0) {
      std::vector<hsize_t> start(dims.size(), 0), count = dims;
      start[0] = r0;
      count[0] = nr;
      Handle fspace(H5Scopy(space.get()), H5Sclose);
      H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
      Handle mspace(H5Screate_simple(rank, count.data(), nullptr), H5Sclose);
      rc = H5Dread(obj.get(), H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), H5P_DEFAULT, v.data());
    } else {
      rc = H5Dread(obj.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    }
    if (rc < 0) {
      c->bad = where + ": cannot be read back" + hdf5ErrorReason();
      return 1;
    }
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i])) {
        std::ostringstream os;
        os << where << " holds " << v[i] << " at flat index " << (r0 * row + i);
        c->bad = os.str();
        return 1;
      }
  }
  return 0;
}

}  // namespace

void checkAllFinite(const H5File& f) {
  FiniteCheck c{f.path(), ""};
#if H5_VERSION_GE(1, 12, 0)
  H5Ovisit3(f.id(), H5_INDEX_NAME, H5_ITER_INC, checkObjectFinite, &c, H5O_INFO_BASIC);
#else
  H5Ovisit2(f.id(), H5_INDEX_NAME, H5_ITER_INC, checkObjectFinite, &c, H5O_INFO_BASIC);
#endif
  if (!c.bad.empty())
    throw H5Error(f.path() + ": refusing to write a non-finite number: " + c.bad);
}

AtomicH5Writer::AtomicH5Writer(const std::string& final_path) : final_path_(final_path) {
  requireHeadroom(kHdf5OpenHeadroom, "creating " + final_path + " (HDF5)");
  for (int attempt = 0;; ++attempt) {
    tmp_path_ = temporaryNameFor(final_path);
    const hid_t id = H5Fcreate(tmp_path_.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT);
    if (id >= 0) {
      file_ = H5File::adopt(id, tmp_path_);
      break;
    }
    const std::string reason = hdf5ErrorReason();
    // EEXIST: a name collision (or a planted file/link, which is not ours to
    // remove): draw another name. Any other failure happened after O_EXCL created
    // the file (e.g. no space for the superblock): it is ours, remove it.
    if (reason.find("File exists") != std::string::npos && attempt < 8) continue;
    if (reason.find("File exists") == std::string::npos) std::remove(tmp_path_.c_str());
    throw H5Error("cannot create a temporary file beside " + final_path + ": " + tmp_path_ + reason);
  }
  registration_ = std::make_unique<TemporaryRegistration>(tmp_path_);
}

AtomicH5Writer::~AtomicH5Writer() {
  if (!committed_) {
    file_.close();
    std::remove(tmp_path_.c_str());
  }
}

void AtomicH5Writer::commit() {
  annotateDatasets(file_);
  checkAllFinite(file_);
  file_.closeChecked();
  fsyncFile(tmp_path_);
  // Read back what the library says it wrote: a truncated file does not open.
  {
    const hid_t check = H5Fopen(tmp_path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (check < 0)
      throw H5Error(tmp_path_ + ": the file just written does not read back as HDF5" +
                    hdf5ErrorReason() + "; " + final_path_ + " left unchanged");
    H5Fclose(check);
  }
  if (std::rename(tmp_path_.c_str(), final_path_.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp_path_.c_str());
    throw H5Error("cannot rename " + tmp_path_ + " to " + final_path_ + ": " + osReason(err));
  }
  committed_ = true;
  registration_.reset();
  fsyncDirectoryOf(final_path_);
}

void writeProvenance(H5File& f, const std::string& format, const std::string& tool,
                     const std::string& inputs_sha256) {
  f.setAttribute("/", "format", format);
  f.setAttribute("/", "units", std::string("SI"));
  f.setAttribute("/", "tool", tool);
  f.setAttribute("/", "version", std::string(FLEXCOMP_VERSION));
  f.setAttribute("/", "inputs_sha256", inputs_sha256);
  std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  f.setAttribute("/", "created", std::string(buf));
}

}  // namespace fc
