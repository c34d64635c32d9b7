#pragma once
// How much an error in the state can change the energy balance
// T + V + D - W, for the run-quality allowance (run/run_quality.h): with g_i =
// dE/dy_i over the state's components (momenta M v for the velocities,
// applied and elastic generalised forces for the positions, 1 for the two
// energy integrals), absolute = sum |g_i| [J per unit state error] and
// relative = sum |g_i| |y_i| [J]: a local error e_i <= rtol |y_i| + atol
// changes E by at most rtol relative + atol absolute (run_quality.cpp uses
// the absolute part; docs/mbs-run.md, "Run quality"). Both formulations
// report it from their poses and generalised forces.
#include <Eigen/Dense>

#include <vector>

#include "mbs-run/mechanics/kinematics.h"
#include "mbs-run/model/model.h"

namespace fc::mbs {

struct EnergySensitivity {
  double absolute = 0.0, relative = 0.0;
};

// Over the free bodies at poses P with the applied generalised forces Q
// (model.nv entries, by each body's dof_index), and the two energy integrals
// (dissipated energy, applied work). Positions count as the translation's
// coordinates, a rotation's Euler parameters (|p| = 1, a rotation of
// 2 |dp|) and the modal coordinates with their elastic forces.
EnergySensitivity energySensitivity(const Model& model, const std::vector<BodyPose>& P, const Eigen::VectorXd& Q,
                                    double dissipated, double applied_work);

}  // namespace fc::mbs
