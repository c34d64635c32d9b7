#pragma once
// The constrained formulation as the run loop sees it (dynamics.h): the
// System of constrained/system.h in body coordinates, with its events: timed
// events (events.h), joint-angle crossings located on the dense output
// (crossings.h) and stops on revolute joints (joint_limits.h).
#include <memory>
#include <string>

#include "mbs-run/model/model.h"
#include "mbs-run/run/dynamics.h"

namespace fc::mbs {

// `why_not_tree`: why the scene does not run in joint coordinates
// (tree_dynamics.h), shown in the formulation's name.
std::unique_ptr<Dynamics> makeConstrainedDynamics(const Model& model, const std::string& why_not_tree);

}  // namespace fc::mbs
