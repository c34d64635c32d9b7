#include "mbs-run/mechanics/flexible/geometric_stiffening.h"

#include <stdexcept>
#include <vector>

#include "common/flexbody.h"
#include "common/h5io.h"

namespace fc::mbs {

GeometricStiffening readGeometricStiffening(const std::string& file, int modes) {
  H5File f(file, H5File::Mode::Read);
  const std::string path = "/geometric_stiffness/matrices";
  if (!f.exists(path))
    throw H5Error(file + ": no " + path + " (write the body file with fe-prep 'geometric_stiffness: true')");
  const std::vector<hsize_t> shape = f.shape(path);
  if (shape.size() != 3 || shape[0] != static_cast<hsize_t>(kGeometricStiffnessCaseCount) || shape[1] != shape[2] ||
      shape[1] < static_cast<hsize_t>(modes))
    throw H5Error(file + ": " + path + " must be (12, n_modes, n_modes) with at least " + std::to_string(modes) +
                  " modes");
  const std::vector<double> all = f.readArray(path);
  const long n = static_cast<long>(shape[1]);
  GeometricStiffening g;
  for (int c = 0; c < kGeometricStiffnessCaseCount; ++c) {
    const Eigen::Map<const Eigen::MatrixXd> full(all.data() + static_cast<std::size_t>(c) * n * n, n, n);
    g.K[c] = full.topLeftCorner(modes, modes);
    if (!g.K[c].allFinite()) throw std::invalid_argument(file + ": " + path + " holds non-finite values");
    if ((g.K[c] - g.K[c].transpose()).cwiseAbs().maxCoeff() > 1e-9 * (1.0 + g.K[c].cwiseAbs().maxCoeff()))
      throw std::invalid_argument(file + ": " + path + " case " + std::to_string(c) + " is not symmetric");
    if ((c < 3 || c >= 9) && g.K[c].size() > 0 && g.K[c].cwiseAbs().maxCoeff() > 0.0) g.acceleration_cases = true;
  }
  const std::string group = "/geometric_stiffness/interfaces";
  if (f.exists(group))
    for (const std::string& name : f.children(group)) {
      const std::string p = group + "/" + name + "/matrices";
      const std::vector<hsize_t> s = f.shape(p);
      if (s.size() != 3 || s[0] != 6 || s[1] != s[2] || s[1] != shape[1])
        throw H5Error(file + ": " + p + " must be (6, " + std::to_string(n) + ", " + std::to_string(n) + ")");
      const std::vector<double> v = f.readArray(p);
      auto& K = g.interfaces[name];
      for (int c = 0; c < 6; ++c) {
        K[c] = Eigen::Map<const Eigen::MatrixXd>(v.data() + static_cast<std::size_t>(c) * n * n, n, n).topLeftCorner(modes, modes);
        if (!K[c].allFinite()) throw std::invalid_argument(file + ": " + p + " holds non-finite values");
        if ((K[c] - K[c].transpose()).cwiseAbs().maxCoeff() > 1e-9 * (1.0 + K[c].cwiseAbs().maxCoeff()))
          throw std::invalid_argument(file + ": " + p + " case " + std::to_string(c) + " is not symmetric");
      }
    }
  return g;
}

StiffeningParameters stiffeningParameters(const Eigen::Vector3d& w, const Eigen::Vector3d& alpha,
                                          const Eigen::Vector3d& a0) {
  StiffeningParameters p;
  p << a0, w.x() * w.x(), w.y() * w.y(), w.z() * w.z(), w.x() * w.y(), w.y() * w.z(), w.z() * w.x(), alpha;
  return p;
}

Eigen::MatrixXd stiffeningMatrix(const GeometricStiffening& g, const StiffeningParameters& p, bool velocity_cases,
                                 bool acceleration_cases) {
  const long nm = g.K[0].rows();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nm, nm);
  for (int c = 0; c < kGeometricStiffnessCaseCount; ++c) {
    const bool velocity = c >= 3 && c < 9;
    if ((velocity && velocity_cases) || (!velocity && acceleration_cases)) K += p(c) * g.K[c];
  }
  return K;
}

}  // namespace fc::mbs
