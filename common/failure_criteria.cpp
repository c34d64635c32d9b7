#include "common/failure_criteria.h"

#include <algorithm>

namespace fc {

double HashinIndices::max() const {
  return std::max({fibre_tension, fibre_compression, matrix_tension, matrix_compression});
}

double hashinTransverseShear(const PlyStrength& st) { return 0.5 * st.Yc; }

HashinIndices hashinIndices(const PlyStrength& st, const Eigen::Matrix<double, 6, 1>& s) {
  const double s11 = s(0), s22 = s(1), s33 = s(2), s23 = s(3), s13 = s(4), s12 = s(5);
  const double ST = hashinTransverseShear(st), SA = st.S12;
  const double axial_shear = (s12 * s12 + s13 * s13) / (SA * SA);
  const double transverse_shear = (s23 * s23 - s22 * s33) / (ST * ST);
  const double I2 = s22 + s33;
  HashinIndices h;
  if (s11 >= 0)
    h.fibre_tension = (s11 / st.Xt) * (s11 / st.Xt) + axial_shear;
  else
    h.fibre_compression = (s11 / st.Xc) * (s11 / st.Xc);
  if (I2 >= 0) {
    h.matrix_tension = (I2 / st.Yt) * (I2 / st.Yt) + transverse_shear + axial_shear;
  } else {
    const double a = st.Yc / (2 * ST);
    h.matrix_compression = (a * a - 1) * I2 / st.Yc + I2 * I2 / (4 * ST * ST) + transverse_shear + axial_shear;
  }
  return h;
}

HashinIndices hashinIndices(const PlyStrength& st, const Eigen::Vector3d& s) {
  Eigen::Matrix<double, 6, 1> v;
  v << s(0), s(1), 0, 0, 0, s(2);
  return hashinIndices(st, v);
}

}  // namespace fc
