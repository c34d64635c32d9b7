#pragma once
// Exact rigid-body properties of the undeformed body, integrated element by
// element (not from the lumped nodes, whose second moments carry an O(h^2)
// error): mass, first moment and second moment E = int rho p p^T dV, giving
// the centre of mass and the inertia tensor about the body origin
// J = tr(E) I - E.
#include <Eigen/Dense>

#include "common/laminate.h"
#include "fe-prep/mesh.h"

namespace fc::feprep {

struct RigidProperties {
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();
  Eigen::Vector3d centerOfMass() const { return first_moment / mass; }
  Eigen::Matrix3d inertiaAboutOrigin() const {
    return second_moment.trace() * Eigen::Matrix3d::Identity() - second_moment;
  }
  RigidProperties& operator+=(const RigidProperties& o);
};

// Flat triangles with a through-thickness mass distribution: per area
// rho_A = int rho dz, f = int rho z dz, r = int rho z^2 dz, z along the
// element normal. Over a triangle, int x x^T dA = A/12 (sum x_i x_i^T + 9 c c^T)
// (c the centroid) is exact for linear geometry.
RigidProperties shellProperties(const Mesh& mesh, const LaminateStiffness& lam);

// Straight beams whose section mass matrix Ms (VABS order) is uniform; the
// section's x2 axis is `section_x2` orthogonalised against each element axis.
// Ms(0,0) = mu, Ms(0,4) = mu x3c, Ms(0,5) = -mu x2c, Ms(4,4) = i22 = int rho x3^2,
// Ms(5,5) = i33 = int rho x2^2, Ms(4,5) = -i23 (VABS manual, mass matrix).
RigidProperties beamProperties(const Mesh& mesh, const Eigen::Matrix<double, 6, 6>& Ms,
                               const Eigen::Vector3d& section_x2);

// The whole body by its elements' own properties (mesh.h): each triangle its
// laminate, each beam its section and x2 axis, plus the point masses (mass and
// inertia about their points). reference_surface_only: the mass on the
// reference surface and axis only (shell first and rotary moments, a section's
// offsets and inertias and the point masses' inertias left out, point masses at
// their nodes), what the lumped translational masses can represent
// (mass_lumping.h).
RigidProperties meshProperties(const Mesh& mesh, bool reference_surface_only);

}  // namespace fc::feprep
