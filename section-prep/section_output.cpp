#include "section-prep/section_output.h"

#include <cstdio>
#include <iomanip>

#include "common/h5io.h"

namespace fc::section {

void writeSectionFile(const std::string& path, const SectionProperties& p,
                      const std::string& inputs_sha256, const std::string& source) {
  AtomicH5Writer w(path);
  H5File& f = w.file();
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
  w.commit();
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
