#include "tacs_graphs/eval/loop_metrics.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace tacs {
namespace {

std::optional<Pose3> poseAt(const Trajectory& trajectory, double stamp, double max_dt) {
  const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), stamp,
                                   [](const StampedPose& p, double t) { return p.stamp < t; });
  const StampedPose* best = nullptr;
  if (it != trajectory.end()) best = &*it;
  if (it != trajectory.begin() && (!best || stamp - std::prev(it)->stamp < best->stamp - stamp)) {
    best = &*std::prev(it);
  }
  if (!best || std::abs(best->stamp - stamp) > max_dt) return std::nullopt;
  return best->pose;
}

}  // namespace

LoopAccuracy evaluateLoops(const SceneGraph& graph, const Trajectory& ground_truth,
                           const LoopTolerance& tolerance) {
  LoopAccuracy acc;
  for (const LoopEdge& loop : graph.loops) {
    ++acc.loops;
    const auto from = graph.keyframes.find(loop.from), to = graph.keyframes.find(loop.to);
    if (from == graph.keyframes.end() || to == graph.keyframes.end()) {
      ++acc.unmatched;
      continue;
    }
    const auto gt_from = poseAt(ground_truth, from->second.stamp, tolerance.max_dt);
    const auto gt_to = poseAt(ground_truth, to->second.stamp, tolerance.max_dt);
    if (!gt_from || !gt_to) {
      ++acc.unmatched;
      continue;
    }
    const Pose3 error = (gt_from->inverse() * *gt_to).inverse() * loop.relativePose();
    const double angle_deg = rotationAngleDeg(error);
    if (error.translation().norm() <= tolerance.translation_m &&
        angle_deg <= tolerance.rotation_deg) {
      ++acc.correct;
    }
  }
  return acc;
}

}  // namespace tacs
