#pragma once
// The joint-coordinate formulation as the run loop sees it (dynamics.h): a
// scene that is an open tree of rigid bodies on free revolute and prismatic
// joints, with no events, integrated in its N joint angles and rates
// (kinematic_tree.h). The start is made consistent by the constrained
// formulation's projection (so both start from the same state), and every
// output row is taken by the constrained sampling (sampling.h) from the
// Cartesian state the tree implies: the same datasets, reactions from the
// constrained solve at that (consistent) state.
#include <memory>
#include <string>

#include "mbs-run/model/model.h"
#include "mbs-run/run/dynamics.h"

namespace fc::mbs {

// Which formulation simulate() takes: "" for the tree, else why not
// ("flexible body B", "formulation: constrained", ...).
std::string treeFormulationDeclined(const Model& model);

// For a scene whose treeFormulationDeclined() is empty.
std::unique_ptr<Dynamics> makeTreeDynamics(const Model& model);

}  // namespace fc::mbs
