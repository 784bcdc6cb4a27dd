// The distance-threshold baseline of LoopDetector (hdl_graph_slam / S-Graphs+ style, the
// comparison of paper Sec. IV-A and Table III).
#include <algorithm>
#include <optional>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/loop_closure/loop_detector.h"

namespace tacs {

LoopDetection LoopDetector::detectByDistance(uint32_t query_id) {
  Stopwatch watch;
  auto query_it = keyframes_.find(query_id);
  if (query_it == keyframes_.end()) return skipped("unknown query keyframe", watch);
  if (!query_it->second.cloud) return skipped("the query keyframe's cloud was released", watch);
  LoopDetection det;
  const Keyframe& query = query_it->second;
  const DistanceLoopConfig& dc = config_.distance;
  // Loops are spaced along the path: right after one, the next keyframes would only repeat it.
  if (soonAfterLastLoop(query, dc.min_edge_interval_m)) {
    return skipped("within min_edge_interval_m of the last loop", watch);
  }
  const Eigen::Vector2d q_xy = query.T_map_base.translation().head<2>();
  std::optional<Registration> best;
  for (const auto& [id, cand] : keyframes_) {
    if (id == query_id || !cand.cloud) continue;
    // Far enough back along the path that the pair is a revisit, not a neighbour.
    if (query.accum_distance - cand.accum_distance <= dc.accum_distance_m) continue;
    if ((cand.T_map_base.translation().head<2>() - q_xy).norm() > dc.distance_threshold_m) {
      continue;
    }
    det.candidates.push_back(id);
    const Pose3 guess = cand.T_map_base.inverse() * query.T_map_base;
    Registration r = registerPair(id, query_id, guess, gicpConfig(dc.max_correspondence_m, false));
    det.registered.push_back(id);
    ++det.registrations;
    if (r.gicp.inliers == 0) continue;
    if (!best || r.gicp.fitness < best->gicp.fitness) best = std::move(r);
  }
  if (best && best->gicp.fitness < dc.fitness_threshold) {
    det.loops.push_back(makeLoop(*best, query_id, LoopPath::kDistance, &det));
  }
  finish(&det, watch.elapsedMs());
  return det;
}

}  // namespace tacs
