#pragma once
// Shared helpers of the mbs-run tests: scenes from YAML text, and a classical
// fixed-step RK4 for the independent minimal-coordinate reference solutions.
#include <unistd.h>

#include <Eigen/Dense>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include "common/flexbody.h"
#include "common/input.h"
#include "mbs-run/scene/scene.h"

namespace fc::mbs::test {

inline Model sceneFromText(const std::string& yaml) {
  return parseScene(fc::InputNode::loadString(yaml, "test.yaml"));
}

// The text of a scene fragment shared by several tests (tests/data/mbs-run/scenes/NAME),
// so that the same bodies are not pasted into each test; tests append the rest.
inline std::string testScene(const std::string& name) {
  const std::string path = std::string(FLEXCOMP_DATA_DIR) + "/mbs-run/scenes/" + name;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error("test scene missing: " + path);
  std::string text;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
  std::fclose(f);
  return text;
}

// Writes a body file (with its invariants) to a per-process temporary path
// named after `tag`, for scenes that load it.
inline std::string writeTempBody(const fc::FlexBody& body, const std::string& tag) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            (tag + "_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  fc::Provenance prov;
  prov.inputs_sha256 = "test";
  fc::writeFlexBody(path, body, fc::computeInertiaInvariants(body), prov);
  return path;
}

// A vector as YAML flow text, at full precision.
inline std::string yamlVector(const Eigen::Vector3d& v) {
  char s[128];
  std::snprintf(s, sizeof s, "[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z());
  return s;
}

// y' = f(t, y), classical Runge-Kutta with n equal steps from t0 to t1.
inline Eigen::VectorXd rk4(const std::function<Eigen::VectorXd(double, const Eigen::VectorXd&)>& f,
                           Eigen::VectorXd y, double t0, double t1, int n) {
  const double h = (t1 - t0) / n;
  double t = t0;
  for (int i = 0; i < n; ++i) {
    const Eigen::VectorXd k1 = f(t, y);
    const Eigen::VectorXd k2 = f(t + 0.5 * h, y + 0.5 * h * k1);
    const Eigen::VectorXd k3 = f(t + 0.5 * h, y + 0.5 * h * k2);
    const Eigen::VectorXd k4 = f(t + h, y + h * k3);
    y += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    t += h;
  }
  return y;
}

// Index of the output row at time t (outputs are on a uniform grid).
inline std::size_t rowAt(const std::vector<double>& time, double t) {
  std::size_t best = 0;
  for (std::size_t k = 0; k < time.size(); ++k)
    if (std::abs(time[k] - t) < std::abs(time[best] - t)) best = k;
  return best;
}

}  // namespace fc::mbs::test
