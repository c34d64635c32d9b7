#pragma once
// The joint-coordinate formulation as the run loop sees it (dynamics.h): a
// scene that is an open tree of rigid bodies on free revolute and prismatic
// joints, with no events, integrated in its N joint angles and rates
// (kinematic_tree.h). It builds no constrained System: it starts from the
// scene's placement, which holds its joints (else the scene is constrained:
// treeUnsupported), with the scene's velocities projected onto the tree's
// motions as the constrained start projects them (so both start from the
// same state); each output row holds the poses and velocities the joint
// coordinates imply, the joints' reactions by the recursive Newton-Euler
// backward pass (treeReactions, in the constrained formulation's convention)
// and the rest of the row as samplePoses (sampling.h) takes it: the same
// datasets with the same meaning.
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
