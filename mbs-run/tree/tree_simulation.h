#pragma once
// The run loop of the joint-coordinate path (kinematic_tree.h): a scene that
// is an open tree of rigid bodies on free revolute and prismatic joints, with
// no events, integrated in its N joint angles and rates. The start is made
// consistent by the constrained path's projection (so both paths start from
// the same state), and every output row is taken by the constrained path's
// sampling (sampling.h) from the Cartesian state the tree implies: the same
// datasets, reactions from the constrained solve at that (consistent) state.
#include <string>

#include "mbs-run/model/model.h"
#include "mbs-run/run/simulation.h"

namespace fc::mbs {

// Which path simulate() takes: "" for the tree, else why not ("flexible body
// B", "formulation: constrained", ...).
std::string treeFormulationDeclined(const Model& model);

// Runs a scene for which treeFormulationDeclined() is empty.
RunSummary simulateTree(const Model& model, const RunOptions& options, SampleSink& sink);

}  // namespace fc::mbs
