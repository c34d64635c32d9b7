#include "fe-prep/beam_mesher.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fc::feprep {

Mesh meshBeam(double length, long elements, const std::vector<double>& forced_x) {
  if (!(length > 0)) throw std::invalid_argument("beam length must be positive");
  if (elements < 1) throw std::invalid_argument("a beam needs at least one element");
  const double a = length / 2, tol = 1e-9 * length;
  std::vector<double> xs;
  for (long i = 0; i <= elements; ++i) xs.push_back(-a + length * static_cast<double>(i) / static_cast<double>(elements));
  for (double x : forced_x) {
    if (std::abs(x) > a + tol) {
      std::ostringstream os;
      os << "x = " << x << " lies outside the beam [" << -a << ", " << a << "]";
      throw std::invalid_argument(os.str());
    }
    const bool present = std::any_of(xs.begin(), xs.end(), [&](double y) { return std::abs(y - x) < tol; });
    if (!present) xs.push_back(x);
  }
  std::sort(xs.begin(), xs.end());
  Mesh mesh;
  mesh.nodes = Eigen::MatrixXd::Zero(static_cast<long>(xs.size()), 3);
  for (std::size_t i = 0; i < xs.size(); ++i) mesh.nodes(static_cast<long>(i), 0) = xs[i];
  for (long i = 0; i + 1 < mesh.nodeCount(); ++i) mesh.beams.push_back({i, i + 1});
  mesh.sets["end_min"] = {0};
  mesh.sets["end_max"] = {mesh.nodeCount() - 1};
  return mesh;
}

}  // namespace fc::feprep
