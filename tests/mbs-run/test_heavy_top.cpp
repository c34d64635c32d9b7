// Heavy symmetric top on a spherical joint at its tip, body origin at the pivot
// and the centre of mass on the symmetry axis at distance l (so the offset-CoM
// mass matrix and quadratic-velocity terms are exercised). Closed form (Goldstein,
// Classical Mechanics, sec. 5.7): with A_p the transverse inertia about the
// pivot and C the axial one, steady precession at tilt theta and rate Omega
// requires the axial spin
//   omega_3 = (m g l + A_p Omega^2 cos(theta)) / (C Omega);
// the tilt then stays theta and the axis turns at Omega about the vertical.
// The first integrals (energy, vertical angular momentum, axial spin) hold for
// any initial condition; they are checked on a nutating top.
#include <gtest/gtest.h>

#include <cmath>

#include "common/rotations.h"
#include "helpers.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs::test {
namespace {

constexpr double kM = 2.0, kL = 0.3, kA0 = 0.02, kC = 0.03, kG = 9.81;

std::string topScene(double theta, const Eigen::Vector3d& omega_global, double t_end) {
  char s[2048];
  std::snprintf(s, sizeof s, R"(
bodies:
  - {name: ground, rigid: {mass: 1, inertia: [[1,0,0],[0,1,0],[0,0,1]]}, fixed: true}
  - name: top
    rigid: {mass: %g, center_of_mass: [0, 0, %g], inertia: [[%g,0,0],[0,%g,0],[0,0,%g]]}
    position: [0, 0, 0]
    orientation: [%.17g, %.17g, 0, 0]
    angular_velocity: [%.17g, %.17g, %.17g]
joints:
  - {name: tip, type: spherical, bodies: [ground, top], points: [[0,0,0],[0,0,0]]}
forces:
  - {type: gravity, g: [0, 0, -9.81]}
simulation: {t_end: %g, output_step: 0.01, rtol: 1.0e-10}
)",
                kM, kL, kA0, kA0, kC, std::cos(theta / 2), std::sin(theta / 2), omega_global.x(), omega_global.y(),
                omega_global.z(), t_end);
  return s;
}

TEST(HeavyTop, SteadyPrecessionMatchesClosedForm) {
  const double theta = 0.5, Omega = 1.5;
  const double Ap = kA0 + kM * kL * kL;
  const double w3 = (kM * kG * kL + Ap * Omega * Omega * std::cos(theta)) / (kC * Omega);
  const Eigen::Vector3d axis(0, -std::sin(theta), std::cos(theta));  // R_x(theta) e_z
  // omega = Omega e_Z + psi_dot e_3 with psi_dot = w3 - Omega cos(theta).
  const Eigen::Vector3d omega = Omega * Eigen::Vector3d::UnitZ() + (w3 - Omega * std::cos(theta)) * axis;
  const Results r = simulate(sceneFromText(topScene(theta, omega, 4.0)), {true});
  ASSERT_EQ(r.status, "completed");
  double worst_tilt = 0, worst_azimuth = 0;
  const double az0 = std::atan2(axis.y(), axis.x());
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const Eigen::Vector3d e3 = fc::rotationMatrix(r.orientation[1][k]).col(2);
    worst_tilt = std::max(worst_tilt, std::abs(std::acos(e3.z()) - theta));
    double daz = std::atan2(e3.y(), e3.x()) - az0 - Omega * r.time[k];
    daz = std::remainder(daz, 2 * M_PI);
    worst_azimuth = std::max(worst_azimuth, std::abs(daz));
  }
  std::printf("[   info   ] steady precession: tilt error %.3e rad, azimuth error %.3e rad over 4 s\n", worst_tilt,
              worst_azimuth);
  // rtol = 1e-10 on angles ~1 and a non-chaotic, neutrally stable motion: the
  // error grows at most linearly, 1e-7 rad over 6 turns is a tight bound.
  EXPECT_LT(worst_tilt, 1e-7);
  EXPECT_LT(worst_azimuth, 1e-7);
}

TEST(HeavyTop, NutatingTopKeepsItsFirstIntegrals) {
  const double theta = 0.4;
  const Eigen::Vector3d axis(0, -std::sin(theta), std::cos(theta));
  const Eigen::Vector3d omega = 60.0 * axis + Eigen::Vector3d(0.7, 0.0, 0.0);  // spin plus a kick: nutation
  const Results r = simulate(sceneFromText(topScene(theta, omega, 5.0)), {true});
  ASSERT_EQ(r.status, "completed");
  const Eigen::Matrix3d Jo = Eigen::Vector3d(kA0 + kM * kL * kL, kA0 + kM * kL * kL, kC).asDiagonal();
  double Lz0 = 0, s0 = 0, E0 = 0, dLz = 0, ds = 0, dE = 0;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    const Eigen::Matrix3d A = fc::rotationMatrix(r.orientation[1][k]);
    const Eigen::Vector3d wb = A.transpose() * r.angular_velocity[1][k];
    const double Lz = (A * Jo * wb).z();  // angular momentum about the pivot, vertical component
    const double s = wb.z();              // axial spin
    const double E = r.kinetic[k] + r.potential[k];
    if (k == 0) { Lz0 = Lz; s0 = s; E0 = E; }
    dLz = std::max(dLz, std::abs(Lz - Lz0));
    ds = std::max(ds, std::abs(s - s0));
    dE = std::max(dE, std::abs(E - E0));
  }
  std::printf("[   info   ] nutating top: |dLz| %.3e, |d omega3| %.3e, |dE| %.3e (E ~ %.3g J)\n", dLz, ds, dE, E0);
  // Exact invariants of the continuous problem; errors are the integration and
  // projection errors at rtol 1e-10 relative to Lz ~ 1.6, spin 60, E ~ 50.
  EXPECT_LT(dLz, 1e-7 * std::abs(Lz0) + 1e-9);
  EXPECT_LT(ds, 1e-7 * std::abs(s0));
  EXPECT_LT(dE, 1e-7 * std::abs(E0));
}

}  // namespace
}  // namespace fc::mbs::test
