#pragma once
// Reads the matrices VABS writes to its NAME.K output, so that tests compare
// against VABS's own numbers rather than values copied by hand.
#include <Eigen/Dense>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fc::section::testing {

struct VabsOutput {
  Eigen::Matrix<double, 6, 6> mass, timoshenko;
  Eigen::Matrix4d classical;
  Eigen::Vector2d mass_center, tension_center, shear_center;
  double area = 0;
  bool has_timoshenko = false, has_shear_center = false;
};

inline std::vector<double> numbersAfter(const std::vector<std::string>& lines,
                                        const std::string& title, int count, bool& found) {
  found = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find(title) == std::string::npos) continue;
    std::vector<double> v;
    for (std::size_t j = i + 1; j < lines.size() && static_cast<int>(v.size()) < count; ++j) {
      if (lines[j].find("===") != std::string::npos) continue;
      std::istringstream in(lines[j]);
      std::string tok;
      while (in >> tok && static_cast<int>(v.size()) < count) {
        if (tok == "=" || tok == "Area") continue;
        try {
          v.push_back(std::stod(tok));
        } catch (...) {
        }
      }
    }
    found = static_cast<int>(v.size()) == count;
    return v;
  }
  return {};
}

inline VabsOutput readVabsK(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  VabsOutput o;
  bool ok = false;
  auto mat = [&](const std::string& title, int n, bool required) {
    auto v = numbersAfter(lines, title, n * n, ok);
    if (!ok && required) throw std::runtime_error(path + ": no '" + title + "'");
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    if (ok)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) m(i, j) = v[i * n + j];
    return m;
  };
  o.mass = mat("The 6X6 Mass Matrix", 6, true);
  o.classical = mat("Classical Stiffness Matrix (1-extension; 2-twist; 3,4-bending)", 4, true);
  o.timoshenko = mat("Timoshenko Stiffness Matrix (1-extension; 2,3-shear, 4-twist; 5,6-bending)", 6, false);
  o.has_timoshenko = ok;
  auto vec = [&](const std::string& title) {
    auto v = numbersAfter(lines, title, 2, ok);
    return ok ? Eigen::Vector2d(v[0], v[1]) : Eigen::Vector2d::Zero();
  };
  o.mass_center = vec("The Mass Center of the Cross Section");
  o.tension_center = vec("The Tension Center of the Cross Section");
  o.shear_center = vec("The Shear Center of the Cross Section in the User Coordinate System");
  o.has_shear_center = ok;
  auto a = numbersAfter(lines, "The Area of the Cross Section", 1, ok);
  o.area = ok ? a[0] : 0;
  return o;
}

}  // namespace fc::section::testing
