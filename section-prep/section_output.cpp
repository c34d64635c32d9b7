#include "section-prep/section_output.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <iomanip>

#include "common/h5io.h"

namespace fc::section {

namespace {

void writeProperties(H5File& f, const SectionProperties& p, const std::string& inputs_sha256,
                     const std::string& source) {
  writeProvenance(f, "section/1", "section-prep", inputs_sha256);
  f.setAttribute("/", "source", source);
  f.writeMatrix("/stiffness/timoshenko", p.timoshenko);
  f.writeMatrix("/stiffness/classical", p.classical);
  f.setAttribute("/stiffness/timoshenko", "order",
                 std::string("extension, shear x2, shear x3, torsion, bending x2, bending x3"));
  f.setAttribute("/stiffness/classical", "order",
                 std::string("extension, torsion, bending x2, bending x3"));
  f.setAttribute("/stiffness/timoshenko", "available", static_cast<long>(p.has_timoshenko));
  f.writeMatrix("/mass/matrix", p.mass);
  f.writeScalar("/mass/per_length", p.mass_per_length);
  f.writeVector("/centers/mass", p.mass_center);
  f.writeVector("/centers/tension", p.tension_center);
  f.writeVector("/centers/shear", p.shear_center);
  f.writeVector("/centers/geometric", p.geometric_center);
  f.writeScalar("/section/area", p.area);
  f.writeInt("/section/nodes", p.n_nodes);
  f.writeInt("/section/elements", p.n_elements);
}

// A (n0, n1, n2) C-order array from per-element blocks.
template <typename Get>
std::vector<double> gather(std::size_t n0, std::size_t n1, std::size_t n2, Get get) {
  std::vector<double> v(n0 * n1 * n2);
  for (std::size_t i = 0; i < n0; ++i)
    for (std::size_t j = 0; j < n1; ++j)
      for (std::size_t k = 0; k < n2; ++k) v[(i * n1 + j) * n2 + k] = get(i, j, k);
  return v;
}

// The in-plane components of the Voigt order [11, 22, 33, 23, 13, 12] a ply's
// stress is written with: fibre, transverse, in-plane shear.
constexpr int kPlyComponents[3] = {0, 1, 5};

void writeRecoveryBasis(H5File& f, const SectionProperties& p, const SectionMesh& mesh) {
  const std::size_t ne = p.recovery.size();
  // Per unit resultant r, each element's stresses in its material axes.
  std::vector<std::array<Vector6d, 6>> mat_stress(ne), mat_strain(ne);
  for (std::size_t e = 0; e < ne; ++e)
    for (int r = 0; r < 6; ++r) {
      mat_stress[e][r] = voigtToAxes(p.recovery[e].stress.col(r), p.recovery[e].axes, false);
      mat_strain[e][r] = voigtToAxes(p.recovery[e].strain.col(r), p.recovery[e].axes, true);
    }
  f.writeArray3("/recovery/stress", gather(6, ne, 6, [&](auto r, auto e, auto c) { return p.recovery[e].stress(c, r); }), 6, ne, 6);
  f.writeArray3("/recovery/strain", gather(6, ne, 6, [&](auto r, auto e, auto c) { return p.recovery[e].strain(c, r); }), 6, ne, 6);
  f.writeArray3("/recovery/ply_stress", gather(6, ne, 3, [&](auto r, auto e, auto c) { return mat_stress[e][r](kPlyComponents[c]); }), 6, ne, 3);
  f.writeArray3("/recovery/ply_strain", gather(6, ne, 3, [&](auto r, auto e, auto c) { return mat_strain[e][r](kPlyComponents[c]); }), 6, ne, 3);
  f.writeArray3("/recovery/material_axes", gather(ne, 3, 3, [&](auto e, auto i, auto j) { return p.recovery[e].axes(j, i); }), ne, 3, 3);
  f.setAttribute("/recovery/stress", "resultants", std::string("F1, F2, F3, M1, M2, M3"));
  Eigen::MatrixXd c(ne, 2);
  std::vector<std::string> names;
  std::vector<long> index, plies;
  for (std::size_t e = 0; e < ne; ++e) {
    c.row(e) = p.recovery[e].centroid.transpose();
    const int m = mesh.elements[e].material;
    names.push_back(mesh.materials[m].name);
    index.push_back(m);
    plies.push_back(isIsotropicMaterial(mesh.materials[m].C) ? 0 : 1);
  }
  f.writeMatrix("/mesh/centroids", c);
  f.writeStrings("/mesh/material", names);
  f.writeIntVector("/mesh/material_index", index);
  f.writeIntVector("/mesh/has_plies", plies);
  std::vector<std::string> mat_names;
  Eigen::MatrixXd strength = Eigen::MatrixXd::Zero(mesh.materials.size(), 5);
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    mat_names.push_back(mesh.materials[m].name);
    if (const auto& st = mesh.materials[m].strength) strength.row(m) << st->Xt, st->Xc, st->Yt, st->Yc, st->S12;
  }
  f.writeStrings("/materials/names", mat_names);
  f.writeMatrix("/materials/strength", strength);
}

void writeRecovered(H5File& f, const RecoveryRun& run) {
  const long ne = static_cast<long>(run.elements.size());
  Eigen::MatrixXd s(ne, 6), e(ne, 6), ps(ne, 3), pe(ne, 3);
  Eigen::VectorXd tw(ne), ms(ne), sr(ne);
  Eigen::MatrixXd hs(ne, 4);
  for (long i = 0; i < ne; ++i) {
    const RecoveredElement& r = run.elements[i];
    s.row(i) = r.stress.transpose();
    e.row(i) = r.strain.transpose();
    ps.row(i) = r.ply_stress.transpose();
    pe.row(i) = r.ply_strain.transpose();
    tw(i) = r.tsai_wu;
    ms(i) = r.max_stress;
    sr(i) = std::isfinite(r.strength_ratio) ? r.strength_ratio : 1e300;
    hs.row(i) << r.hashin.fibre_tension, r.hashin.fibre_compression, r.hashin.matrix_tension,
        r.hashin.matrix_compression;
  }
  f.writeVector("/recovered/resultants", run.resultants);
  f.writeMatrix("/recovered/stress", s);
  f.writeMatrix("/recovered/strain", e);
  f.writeMatrix("/recovered/ply_stress", ps);
  f.writeMatrix("/recovered/ply_strain", pe);
  f.writeVector("/recovered/failure_index", tw);
  f.writeVector("/recovered/max_stress_index", ms);
  f.writeVector("/recovered/strength_ratio", sr);
  f.writeMatrix("/recovered/hashin", hs);
  f.setAttribute("/recovered/hashin", "modes", std::string("fibre tension, fibre compression, matrix tension, matrix compression"));
}

}  // namespace

void writeSectionFile(const std::string& path, const SectionProperties& p,
                      const std::string& inputs_sha256, const std::string& source) {
  AtomicH5Writer w(path);
  writeProperties(w.file(), p, inputs_sha256, source);
  w.commit();
}

void writeSectionFile(const std::string& path, const SectionProperties& p,
                      const std::string& inputs_sha256, const std::string& source,
                      const SectionMesh& mesh, const RecoveryRun* run) {
  AtomicH5Writer w(path);
  writeProperties(w.file(), p, inputs_sha256, source);
  if (!p.recovery.empty()) writeRecoveryBasis(w.file(), p, mesh);
  if (run) writeRecovered(w.file(), *run);
  w.commit();
}

namespace {
// The governing Hashin mode: FT, FC, MT or MC.
const char* hashinModeName(const HashinIndices& h) {
  const double m = h.max();
  if (m == h.fibre_tension) return "FT";
  if (m == h.fibre_compression) return "FC";
  if (m == h.matrix_tension) return "MT";
  return "MC";
}
}  // namespace

void printRecovery(std::ostream& out, const SectionMesh& mesh, const SectionProperties& p,
                   const RecoveryRun& run) {
  char buf[400];
  const Vector6d& F = run.resultants;
  std::snprintf(buf, sizeof buf,
                "\nStress recovery for F1 = %.6e N, F2 = %.6e N, F3 = %.6e N, M1 = %.6e N m, "
                "M2 = %.6e N m, M3 = %.6e N m\n",
                F(0), F(1), F(2), F(3), F(4), F(5));
  out << buf;
  bool any_ply = false, all_strength = true;
  for (const auto& m : mesh.materials) {
    if (!isIsotropicMaterial(m.C)) any_ply = true;
    if (!m.strength) all_strength = false;
  }
  if (!any_ply)
    out << "The section has no plies (every material is isotropic): the 'ply' stresses are in the "
           "section frame with the beam axis x1 as 1-axis.\n";
  if (!all_strength) {
    out << "No strengths for material(s):";
    for (const auto& m : mesh.materials)
      if (!m.strength) out << " " << m.name;
    out << " (no failure index for their elements).\n";
  }
  out << "  elem        x2           x3          s11          s22          s33          s23          "
         "s13          s12     s_11(ply)    s_22(ply)    t_12(ply)   Tsai-Wu   max-stress  str.ratio   Hashin  mode\n";
  long worst = -1;
  for (std::size_t e = 0; e < run.elements.size(); ++e) {
    const RecoveredElement& r = run.elements[e];
    const Eigen::Vector2d& c = p.recovery[e].centroid;
    std::snprintf(buf, sizeof buf, "%6d %12.5e %12.5e", mesh.elements[e].user_id, c.x(), c.y());
    out << buf;
    for (int i = 0; i < 6; ++i) { std::snprintf(buf, sizeof buf, " %12.5e", r.stress(i)); out << buf; }
    for (int i = 0; i < 3; ++i) { std::snprintf(buf, sizeof buf, " %12.5e", r.ply_stress(i)); out << buf; }
    if (r.has_strength) {
      std::snprintf(buf, sizeof buf, " %10.4e %10.4e %10.4e %10.4e %s", r.tsai_wu, r.max_stress, r.strength_ratio,
                    r.hashin.max(), hashinModeName(r.hashin));
      out << buf;
      if (worst < 0 || r.tsai_wu > run.elements[worst].tsai_wu) worst = static_cast<long>(e);
    } else {
      out << "          -          -          -          -   -";
    }
    out << "\n";
  }
  if (worst >= 0) {
    const RecoveredElement& r = run.elements[worst];
    std::snprintf(buf, sizeof buf,
                  "Largest Tsai-Wu index %.6e in element %d (%s) at (%.6e, %.6e); strength ratio %.6e\n",
                  r.tsai_wu, mesh.elements[worst].user_id,
                  mesh.materials[mesh.elements[worst].material].name.c_str(),
                  p.recovery[worst].centroid.x(), p.recovery[worst].centroid.y(), r.strength_ratio);
    out << buf;
  }
}

namespace {

template <typename M>
void printMatrix(std::ostream& out, const char* title, const M& m) {
  out << title << "\n";
  char buf[32];
  for (int i = 0; i < m.rows(); ++i) {
    out << "  ";
    for (int j = 0; j < m.cols(); ++j) {
      std::snprintf(buf, sizeof buf, "%14.6e", m(i, j));
      out << buf;
    }
    out << "\n";
  }
}

}  // namespace

void printSummary(std::ostream& out, const SectionProperties& p) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "Section: %ld elements, %ld nodes, area %.6e m^2, mass %.6e kg/m\n\n",
                p.n_elements, p.n_nodes, p.area, p.mass_per_length);
  out << buf;
  printMatrix(out, "Classical stiffness [extension, torsion, bending x2, bending x3] (SI, about the origin)",
              p.classical);
  out << "\n";
  if (p.has_timoshenko) {
    printMatrix(out,
                "Timoshenko stiffness [extension, shear x2, shear x3, torsion, bending x2, bending x3]",
                p.timoshenko);
    out << "\n";
  }
  printMatrix(out, "Mass matrix (same order, about the origin)", p.mass);
  out << "\n";
  auto centre = [&](const char* name, const Eigen::Vector2d& c) {
    std::snprintf(buf, sizeof buf, "  %-16s x2 = %14.6e  x3 = %14.6e\n", name, c.x(), c.y());
    out << buf;
  };
  out << "Centres (m)\n";
  centre("geometric", p.geometric_center);
  centre("mass", p.mass_center);
  centre("tension", p.tension_center);
  if (p.has_timoshenko) centre("shear", p.shear_center);
  out << "\n";
  const auto& K = p.classical;
  std::snprintf(buf, sizeof buf,
                "EA  = %.6e N\nGJ  = %.6e N m^2\nEI2 = %.6e N m^2\nEI3 = %.6e N m^2   "
                "(diagonal terms about the origin)\n",
                K(0, 0), K(1, 1), K(2, 2), K(3, 3));
  out << buf;
  if (p.has_timoshenko) {
    std::snprintf(buf, sizeof buf, "GA2 = %.6e N\nGA3 = %.6e N   (shear stiffnesses)\n",
                  p.timoshenko(1, 1), p.timoshenko(2, 2));
    out << buf;
  }
}

}  // namespace fc::section
