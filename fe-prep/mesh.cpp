#include "fe-prep/mesh.h"

#include <limits>

namespace fc::feprep {

long Mesh::nearestNode(const Eigen::Vector3d& p, double* distance) const {
  long best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (long i = 0; i < nodes.rows(); ++i) {
    const double d2 = (nodes.row(i).transpose() - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  if (distance) *distance = std::sqrt(best_d2);
  return best;
}

double Mesh::characteristicLength() const {
  if (nodes.rows() == 0) return 0.0;
  return (nodes.colwise().maxCoeff() - nodes.colwise().minCoeff()).norm();
}

}  // namespace fc::feprep
