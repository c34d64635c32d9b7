// ParaView animation of a finished run (see animation.h). VTK XML files with
// the data appended raw (binary, exact doubles): no VTK library needed.
#include "mbs-run/output/animation.h"

#include <sys/stat.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "common/files.h"
#include "common/flexbody.h"
#include "common/h5io.h"
#include "common/input.h"
#include "common/rotations.h"
#include "mbs-run/mechanics/flexible/flexible_body.h"
#include "mbs-run/monitors/stress_recovery.h"

namespace fc::mbs {

namespace {

// A body's drawing in its own frame: points, polygons, lines and (flexible
// bodies) the translational mode shapes of its points, (3 n_points, n_modes).
struct Shape {
  Eigen::MatrixXd points;                 // (n, 3) body frame
  std::vector<std::vector<long>> polys;   // triangles or quads
  std::vector<std::array<long, 2>> lines;
  Eigen::MatrixXd modes;                  // (3n, nm) point-major
};

Shape boxShape(const Eigen::Vector3d& size, const Eigen::Vector3d& centre, const Eigen::Matrix3d& axes) {
  Shape s;
  s.points.resize(8, 3);
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d c(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
    s.points.row(k) = (centre + axes * c.cwiseProduct(size)).transpose();
  }
  // Faces with outward normals (corner k has bits x=1, y=2, z=4).
  s.polys = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return s;
}

Shape flexibleShape(const Body& b) {
  const FlexBodyFile f = readFlexBody(b.flex->file, b.modes, FlexBodyParts::All);
  Shape s;
  s.points = f.body.nodes;
  const long n = f.body.nodeCount();
  if (auto it = f.body.elements.find("triangles"); it != f.body.elements.end())
    for (long e = 0; e < it->second.rows(); ++e) s.polys.push_back({it->second(e, 0), it->second(e, 1), it->second(e, 2)});
  if (auto it = f.body.elements.find("beams"); it != f.body.elements.end())
    for (long e = 0; e < it->second.rows(); ++e) s.lines.push_back({it->second(e, 0), it->second(e, 1)});
  s.modes.resize(3 * n, b.modes);
  for (long k = 0; k < n; ++k) s.modes.middleRows(3 * k, 3) = f.body.shapes.middleRows(6 * k, 3);
  return s;
}

// The scene's own description of a rigid body (rod/plate dimensions), else
// the box of its inertia.
Shape rigidShape(const Body& b, const InputNode* node) {
  if (node && node->has("rod")) {
    const InputNode r = (*node)["rod"];
    const double L = r["length"].asPositive(), d = r["diameter"].asPositive();
    return boxShape(Eigen::Vector3d(L, d, d), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  }
  if (node && node->has("plate")) {
    const InputNode p = (*node)["plate"];
    return boxShape(Eigen::Vector3d(p["length"].asPositive(), p["width"].asPositive(), p["thickness"].asPositive()),
                    Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(b.inertia_com);
  return boxShape(equivalentBox(b.mass, es.eigenvalues()), b.com, es.eigenvectors());
}

std::string safeName(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  return s;
}

std::string baseName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string xmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// One PolyData file, data appended raw: [UInt64 byte count][bytes] per array.
class VtpWriter {
 public:
  template <class T>
  void add(const std::string& section, const std::string& name, const char* type, int components,
           const std::vector<T>& v) {
    std::ostringstream x;
    x << "<DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\"" << components
      << "\" format=\"appended\" offset=\"" << blob_.size() << "\"/>";
    xml_[section] += x.str();
    const std::uint64_t bytes = v.size() * sizeof(T);
    blob_.append(reinterpret_cast<const char*>(&bytes), sizeof bytes);
    blob_.append(reinterpret_cast<const char*>(v.data()), bytes);
  }
  void write(const std::string& path, long n_points, long n_lines, long n_polys) {
    std::ostringstream x;
    x << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<PolyData>\n<Piece NumberOfPoints=\""
      << n_points << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << n_lines << "\" NumberOfStrips=\"0\" NumberOfPolys=\""
      << n_polys << "\">\n";
    for (const char* s : {"PointData", "CellData", "Points", "Lines", "Polys"})
      x << "<" << s << ">" << xml_[s] << "</" << s << ">\n";
    x << "</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
    std::ofstream f(path, std::ios::binary);
    f << x.str();
    f.write(blob_.data(), static_cast<std::streamsize>(blob_.size()));
    f << "\n</AppendedData>\n</VTKFile>\n";
    if (!f) throw std::runtime_error(path + ": cannot write the animation file");
  }

 private:
  std::map<std::string, std::string> xml_;
  std::string blob_;
};

void writeBodyFrame(const std::string& path, const Shape& s, const Eigen::Vector3d& r, const Eigen::Matrix3d& A,
                    const Eigen::VectorXd* w, const Eigen::VectorXd* failure = nullptr) {
  const long n = s.points.rows();
  std::vector<double> x(3 * n), u(3 * n, 0.0);
  Eigen::VectorXd local;
  if (w && s.modes.cols() > 0) local = s.modes * (*w);
  for (long k = 0; k < n; ++k) {
    const Eigen::Vector3d p = r + A * s.points.row(k).transpose();
    for (int d = 0; d < 3; ++d) x[3 * k + d] = p(d);
    if (local.size()) {
      const Eigen::Vector3d g = A * local.segment<3>(3 * k);
      for (int d = 0; d < 3; ++d) u[3 * k + d] = g(d);
    }
  }
  std::vector<std::int64_t> lc, lo, pc, po;
  for (const auto& l : s.lines) {
    lc.insert(lc.end(), l.begin(), l.end());
    lo.push_back(static_cast<std::int64_t>(lc.size()));
  }
  for (const auto& p : s.polys) {
    pc.insert(pc.end(), p.begin(), p.end());
    po.push_back(static_cast<std::int64_t>(pc.size()));
  }
  VtpWriter v;
  v.add("PointData", "displacement", "Float64", 3, u);
  // Bodies with stress recovery: the largest Tsai-Wu index over the plies of
  // each element (cells in /mesh/triangles order, which is the polygons'
  // order), or of each beam element over its stations and section elements.
  if (failure) v.add("CellData", "failure_index", "Float64", 1, std::vector<double>(failure->data(), failure->data() + failure->size()));
  v.add("Points", "Points", "Float64", 3, x);
  v.add("Lines", "connectivity", "Int64", 1, lc);
  v.add("Lines", "offsets", "Int64", 1, lo);
  v.add("Polys", "connectivity", "Int64", 1, pc);
  v.add("Polys", "offsets", "Int64", 1, po);
  v.write(path, n, static_cast<long>(s.lines.size()), static_cast<long>(s.polys.size()));
}

}  // namespace

Eigen::Vector3d equivalentBox(double mass, const Eigen::Vector3d& I) {
  Eigen::Vector3d size;
  for (int a = 0; a < 3; ++a) {
    const double s2 = 6.0 * (I((a + 1) % 3) + I((a + 2) % 3) - I(a)) / mass;
    size(a) = s2 > 0 ? std::sqrt(s2) : 0.0;
  }
  return size;
}

std::string prepareAnimationFolder(const std::string& pvd_path) {
  if (pvd_path.size() < 5 || pvd_path.compare(pvd_path.size() - 4, 4, ".pvd") != 0)
    throw std::runtime_error(pvd_path + ": the animation file must end in .pvd (a ParaView collection)");
  const std::string folder = directoryOf(pvd_path) + "/" + baseName(pvd_path.substr(0, pvd_path.size() - 4));
  if (::mkdir(folder.c_str(), 0777) != 0 && errno != EEXIST)
    throw std::runtime_error(folder + ": cannot create the animation folder: " + std::strerror(errno));
  struct stat st;
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw std::runtime_error(folder + ": exists and is not a folder; the animation needs it for its frames");
  return folder;
}

AnimationSummary writeAnimation(const std::string& pvd_path, const std::string& scene_path, const Model& model,
                                const std::string& results_path, int every) {
  if (every < 1) throw std::runtime_error("--animation-every must be at least 1");
  const std::string folder = prepareAnimationFolder(pvd_path);
  const std::string stem = baseName(pvd_path.substr(0, pvd_path.size() - 4));
  const std::string dir_rel = stem;  // frames folder, relative to the .pvd

  // Scene nodes by body name (rod/plate dimensions are not kept in the Model).
  const InputNode scene = InputNode::loadFile(scene_path);
  std::map<std::string, InputNode> nodes;
  if (scene.has("bodies"))
    for (std::size_t i = 0; i < scene["bodies"].size(); ++i) {
      const InputNode b = scene["bodies"].at(i);
      if (b.has("name")) nodes.emplace(b["name"].asString(), b);
    }
  std::vector<Shape> shapes;
  for (const Body& b : model.bodies) {
    auto it = nodes.find(b.name);
    shapes.push_back(b.flex ? flexibleShape(b) : rigidShape(b, it == nodes.end() ? nullptr : &it->second));
  }

  H5File f(results_path, H5File::Mode::Read);
  f.checkFormat("results", 1);
  const Eigen::VectorXd t = f.readVector("/time");
  // The rows of the full stress fields: /stress_time when outputs.stress_every
  // decimated them, else every row. A frame shows the latest stress row at or
  // before its time (docs/file-formats.md, "Animation").
  const Eigen::VectorXd ts = f.exists("/stress_time") ? f.readVector("/stress_time") : t;
  std::vector<Eigen::Index> stress_row(static_cast<std::size_t>(t.size()), 0);
  for (Eigen::Index k = 0, j = 0; k < t.size(); ++k) {
    while (j + 1 < ts.size() && ts(j + 1) <= t(k)) ++j;
    stress_row[static_cast<std::size_t>(k)] = j;
  }
  struct Track {
    Eigen::MatrixXd r, p, w;
    Eigen::MatrixXd failure;  // (n_el, n_out): max over plies of failure_index, bodies with one
  };
  std::vector<Track> tracks;
  for (const Body& b : model.bodies) {
    const std::string g = "/bodies/" + b.name + "/";
    Track tr{f.readMatrix(g + "position"), f.readMatrix(g + "orientation"), Eigen::MatrixXd(), Eigen::MatrixXd()};
    if (b.modes > 0) tr.w = f.readMatrix(g + "modal_coordinates");
    if (tr.r.rows() != t.size() || tr.p.rows() != t.size() || (b.modes > 0 && tr.w.rows() != t.size()))
      throw std::runtime_error(results_path + ": " + g + " has not one row per output time");
    if (b.stress && b.stress->kind == BodyStressRecovery::Kind::Shell && b.stress->failure_output >= 0 &&
        f.exists(g + "failure_index")) {
      const std::vector<hsize_t> sh = f.shape(g + "failure_index");
      const long ne = b.stress->n_elements, np = b.stress->n_plies;
      if (sh.size() != 3 || sh[0] != static_cast<hsize_t>(ts.size()) || sh[1] != static_cast<hsize_t>(ne) ||
          sh[2] != static_cast<hsize_t>(np) || ne != static_cast<long>(shapes[tracks.size()].polys.size()))
        throw std::runtime_error(results_path + ": " + g + "failure_index does not match the body's elements and plies");
      const std::vector<double> fi = f.readArray(g + "failure_index");
      tr.failure = Eigen::Map<const Eigen::MatrixXd>(fi.data(), np, ne * ts.size()).colwise().maxCoeff();
      tr.failure.resize(ne, ts.size());
    }
    // Beams with ply recovery: per beam element the largest index over its
    // three stations and every section element (cells in /mesh/beams order,
    // which is the lines' order; a beam body draws no polygons).
    if (b.stress && b.stress->kind == BodyStressRecovery::Kind::Beam && b.stress->failure_output >= 0 &&
        f.exists(g + "failure_index")) {
      const std::vector<hsize_t> sh = f.shape(g + "failure_index");
      const long ne = b.stress->n_elements, ns = b.stress->n_plies;
      const Shape& shape = shapes[tracks.size()];
      if (sh.size() != 3 || sh[0] != static_cast<hsize_t>(ts.size()) || sh[1] != static_cast<hsize_t>(3 * ne) ||
          sh[2] != static_cast<hsize_t>(ns) || ne != static_cast<long>(shape.lines.size()) || !shape.polys.empty())
        throw std::runtime_error(results_path + ": " + g +
                                 "failure_index does not match the beam's stations and section elements");
      const std::vector<double> fi = f.readArray(g + "failure_index");
      tr.failure = Eigen::Map<const Eigen::MatrixXd>(fi.data(), 3 * ns, ne * ts.size()).colwise().maxCoeff();
      tr.failure.resize(ne, ts.size());
    }
    tracks.push_back(std::move(tr));
  }

  std::ostringstream pvd;
  pvd << "<?xml version=\"1.0\"?>\n<!-- mbs-run animation of " << xmlEscape(baseName(results_path))
      << ": points at the undeformed body shapes moved with their frames; `displacement` is the elastic "
         "displacement (global axes, true scale): Warp By Vector with scale factor S shows it S times. -->\n"
      << "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n<Collection>\n";
  AnimationSummary sum;
  sum.bodies = static_cast<int>(model.bodies.size());
  sum.folder = folder;
  for (Eigen::Index k = 0; k < t.size(); k += every, ++sum.frames) {
    char frame[32];
    std::snprintf(frame, sizeof frame, "_%04d", sum.frames);
    std::ostringstream vtm;
    vtm << "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<vtkMultiBlockDataSet>\n";
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      const Track& tr = tracks[b];
      const Eigen::Vector3d r = tr.r.row(k).transpose();
      const Eigen::Vector4d p = tr.p.row(k).transpose();
      const Eigen::Matrix3d A = rotationMatrix(p / p.norm());
      Eigen::VectorXd w;
      if (tr.w.size()) w = tr.w.row(k).transpose();
      const std::string file = stem + frame + "_" + safeName(model.bodies[b].name) + ".vtp";
      Eigen::VectorXd fmax;
      if (tr.failure.size()) fmax = tr.failure.col(stress_row[static_cast<std::size_t>(k)]);
      writeBodyFrame(folder + "/" + file, shapes[b], r, A, tr.w.size() ? &w : nullptr, fmax.size() ? &fmax : nullptr);
      vtm << "<DataSet index=\"" << b << "\" name=\"" << xmlEscape(model.bodies[b].name) << "\" file=\""
          << xmlEscape(file) << "\"/>\n";
    }
    vtm << "</vtkMultiBlockDataSet>\n</VTKFile>\n";
    writeFileAtomic(folder + "/" + stem + frame + ".vtm", vtm.str());
    char time[40];
    std::snprintf(time, sizeof time, "%.17g", t(k));
    pvd << "<DataSet timestep=\"" << time << "\" part=\"0\" file=\"" << xmlEscape(dir_rel + "/" + stem + frame)
        << ".vtm\"/>\n";
  }
  pvd << "</Collection>\n</VTKFile>\n";
  writeFileAtomic(pvd_path, pvd.str());
  return sum;
}

}  // namespace fc::mbs
