#include "common/stress_data.h"

#include <stdexcept>

namespace fc {

PlyTable plyTable(const Laminate& lam, const MaterialLibrary& materials) {
  PlyTable t;
  const long n = static_cast<long>(lam.plies.size());
  t.z_mid.resize(n);
  t.angle_deg.resize(n);
  t.strength.resize(n, 5);
  bool all_strengths = n > 0;
  double z0 = -0.5 * lam.thickness();  // plies listed from the bottom face up (contracts.md)
  for (long k = 0; k < n; ++k) {
    const Ply& p = lam.plies[static_cast<std::size_t>(k)];
    const auto it = materials.find(p.material);
    if (it == materials.end())
      throw std::invalid_argument("laminate '" + lam.name + "': unknown material '" + p.material + "'");
    t.z_mid(k) = z0 + 0.5 * p.thickness;
    z0 += p.thickness;
    t.angle_deg(k) = p.angle_deg;
    t.stiffness.push_back(reducedStiffness(it->second));
    if (const auto& s = it->second.strength) t.strength.row(k) << s->Xt, s->Xc, s->Yt, s->Yc, s->S12;
    else all_strengths = false;
  }
  if (!all_strengths) t.strength.resize(0, 5);
  return t;
}

}  // namespace fc
