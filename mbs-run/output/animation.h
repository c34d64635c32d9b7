#pragma once
// A ParaView animation of a finished run: `mbs-run SCENE -o R.h5 --animation R.pvd`.
// Read after the run from the results file (positions, Euler parameters, modal
// coordinates) and the bodies' files, so the integration loop never sees it.
//
//   R.pvd                    VTK collection: one multiblock per written output time
//   R/R_NNNN.vtm             that time's bodies, one block per body, named after it
//   R/R_NNNN_BODY.vtp        one body: polygons (shell triangles, box faces), lines (beams)
//
// Geometry and field (docs/file-formats.md, "Animation"): every body is drawn at
// its floating frame's position and orientation UNDEFORMED, x_k = r + A s0_k,
// with the point field `displacement` = A Phi_k w, the elastic displacement in
// global axes at true scale. ParaView's Warp By Vector with scale factor s then
// shows r + A (s0_k + s Phi_k w): s = 1 the true deformed shape, s = 20 twenty
// times magnified. Rigid bodies carry a zero displacement (so one Warp By Vector
// applies to the whole multiblock) and are drawn as a box: rod and plate
// shortcuts with their dimensions, other rigid bodies as the uniform box with
// their mass and principal inertias, centred at the centre of mass.
#include <string>

#include "mbs-run/model/model.h"

namespace fc::mbs {

struct AnimationSummary {
  int frames = 0;       // output times written
  int bodies = 0;
  std::string folder;   // where the .vtm/.vtp files are
};

// Writes the animation of `results_path` (a results/1 file of `model`, which was
// read from `scene_path`) to `pvd_path` (must end in .pvd), every `every`-th output
// time starting with the first. The .pvd is written last and atomically: when it
// exists, every file it names is complete. Errors: std::runtime_error naming the file.
AnimationSummary writeAnimation(const std::string& pvd_path, const std::string& scene_path, const Model& model,
                                const std::string& results_path, int every = 1);

// Creates the frames folder of `pvd_path` (R.pvd -> R/) and checks the name, so
// that a bad --animation argument fails before the run, not after it.
// Returns the folder; throws std::runtime_error naming it.
std::string prepareAnimationFolder(const std::string& pvd_path);

// Edge lengths of the uniform box with this mass and these principal moments
// (a^2 = 6 (I2 + I3 - I1) / m and cyclically); zero where the moments allow none.
Eigen::Vector3d equivalentBox(double mass, const Eigen::Vector3d& principal_moments);

}  // namespace fc::mbs
