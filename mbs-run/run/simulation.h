#pragma once
// The run loop: integrate with error control, project onto the constraints
// after every accepted step, apply events at their times (stopping exactly
// there) or at joint-angle crossings (located on the dense output), and sample
// the results at the output times. Each of these is a stage in a file of its
// own (integrator_switching, events, crossings, sampling, run_summary);
// simulate() only sequences them.
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "mbs-run/model/model.h"
#include "mbs-run/run/history.h"
#include "mbs-run/run/run_summary.h"
#include "mbs-run/run/sampling.h"

namespace fc::mbs {

struct RunOptions {
  bool quiet = false;
};

// Runs the scene, handing each output row to `sink` as it is taken. A
// termination signal recorded by common/termination (the executable installs
// it with Policy::Record) stops the loop at the next step with status
// "interrupted by SIGxxx"; a solver failure stops it with a status saying why;
// the sink's OutputError propagates.
RunSummary simulate(const Model& model, const RunOptions& options, SampleSink& sink);
// Runs the scene keeping every output row in memory.
Results simulate(const Model& model, const RunOptions& options = {});

}  // namespace fc::mbs
