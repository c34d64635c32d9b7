#pragma once
// Plate stiffness written out in the test from textbook formulas (Reddy,
// Mechanics of Laminated Composite Plates and Shells, 2nd ed., eqs. 3.3.14,
// 3.3.25, 3.3.17), independent of common/laminate.cpp, so that the element
// tests check the elements alone.
#include <vector>

#include "common/laminate.h"

namespace fc::fe::test {

struct OrthoPly {
  double E1, E2, G12, G13, G23, nu12, rho, thickness, angle_deg;
};

LaminateStiffness isotropicPlate(double E, double nu, double rho, double h,
                                 double kappa = 5.0 / 6.0);
// Plies listed from the bottom face upwards.
LaminateStiffness orthotropicLaminate(const std::vector<OrthoPly>& plies,
                                      double kappa = 5.0 / 6.0);

}  // namespace fc::fe::test
