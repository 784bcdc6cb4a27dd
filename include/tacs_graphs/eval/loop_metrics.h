// Loop-closure accuracy (docs/DESIGN.md "Evaluation", paper Table II): a loop is correct when its
// measured relative pose agrees with the ground-truth relative pose of its two keyframes within
// 0.3 m and 3 deg; PR_loop is the share of correct loops.
#pragma once

#include <cstddef>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/scene_graph/scene_graph.h"

namespace tacs {

struct LoopAccuracy {
  size_t loops = 0;      // N_loop
  size_t correct = 0;    // within the tolerances
  size_t unmatched = 0;  // a keyframe stamp had no ground-truth pose within max_dt
  double precision() const { return loops > unmatched ? double(correct) / (loops - unmatched) : 0; }
};

struct LoopTolerance {
  double translation_m = 0.3;
  double rotation_deg = 3.0;
  double max_dt = 0.05;  // [s] keyframe stamp to ground-truth stamp
};

/// Scores every loop of `graph` against the ground-truth base trajectory (sorted by stamp).
LoopAccuracy evaluateLoops(const SceneGraph& graph, const Trajectory& ground_truth,
                           const LoopTolerance& tolerance = {});

}  // namespace tacs
