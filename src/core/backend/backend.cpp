#include "tacs_graphs/backend/backend.h"

namespace tacs {

Backend::Backend(const BackendConfig& config, const WallAssociationConfig& association)
    : config_(config), graph_(config), wall_map_(association) {}

void Backend::addKeyframe(uint32_t id, double stamp, const Pose3& T_odom_base,
                          const Matrix6d& information) {
  if (hasKeyframe(id)) return;  // a re-sent keyframe (node restart) adds nothing
  const Pose3 T_map_odom = mapToOdom();
  graph_.addKeyframe(id, T_map_odom * T_odom_base);
  if (last_keyframe_) {
    const KeyframeInfo& prev = keyframes_.at(*last_keyframe_);
    graph_.addRelativePose(*last_keyframe_, id, prev.T_odom_base.inverse() * T_odom_base,
                           information, /*robust=*/false);
  }
  keyframes_[id] = {stamp, T_odom_base};
  last_keyframe_ = id;
  ++keyframes_since_optimization_;
  ++keyframes_since_full_solve_;
}

std::vector<uint32_t> Backend::addWallObservations(uint32_t keyframe_id,
                                                   const std::vector<WallSegment>& walls,
                                                   const std::vector<WallSegment>& seen_over) {
  std::vector<uint32_t> ids;
  if (!hasKeyframe(keyframe_id)) return ids;
  const Pose3 T_map_base = graph_.keyframePose(keyframe_id);
  wall_map_.addSeenOver(seen_over, T_map_base);
  const auto associations = wall_map_.associate(walls, T_map_base);
  for (const auto& a : associations) {
    const WallSegment& obs = walls[a.observation_index];
    if (!graph_.hasWall(a.landmark_id)) {
      const WallLandmark& lm = wall_map_.landmarks().at(a.landmark_id);
      graph_.addWall(a.landmark_id, WallPlane::fromNormalD(lm.normal, lm.d));
    }
    graph_.addWallObservation(keyframe_id, a.landmark_id, obs.normal, obs.d);
    ids.push_back(a.landmark_id);
  }
  return ids;
}

void Backend::addLoopClosure(uint32_t from, uint32_t to, const Pose3& T_from_to,
                             const Matrix6d& information, double score) {
  if (!hasKeyframe(from) || !hasKeyframe(to)) return;
  graph_.addRelativePose(from, to, T_from_to, information, /*robust=*/true);
  LoopEdge edge;
  edge.from = from;
  edge.to = to;
  edge.position = T_from_to.translation();
  edge.orientation = Eigen::Quaterniond(T_from_to.rotation()).normalized();
  edge.score = score;
  loops_.push_back(edge);
  loop_pending_ = true;
}

std::optional<OptimizationReport> Backend::optimizeIfDue() {
  if (!loop_pending_ && keyframes_since_optimization_ < config_.optimize_every_keyframes) {
    return std::nullopt;
  }
  return run(
      optimizationWindow(config_, keyframes_.size(), keyframes_since_full_solve_, loop_pending_));
}

OptimizationReport Backend::optimize() { return run(0); }

OptimizationReport Backend::run(size_t window_keyframes) {
  const OptimizationReport report = graph_.optimize(window_keyframes);
  total_optimization_ms_ += report.time_ms;
  total_optimization_cpu_ms_ += report.cpu_ms;
  ++optimizations_;
  keyframes_since_optimization_ = 0;
  if (!report.window) keyframes_since_full_solve_ = 0;
  loop_pending_ = false;
  // Landmarks follow the optimised planes; then walls that now coincide are folded.
  for (const auto& [id, lm] : wall_map_.landmarks()) {
    if (!graph_.hasWall(id)) continue;
    const WallPlane plane = graph_.wall(id);
    wall_map_.updateLandmarkPlane(id, plane.normal(), plane.d);
  }
  for (const auto& [removed, kept] : wall_map_.mergeDuplicates()) {
    graph_.mergeWalls(kept, removed);
    renameRoomWall(removed, kept);
  }
  return report;
}

Pose3 Backend::mapToOdom() const {
  if (!last_keyframe_) return Pose3::Identity();
  return graph_.keyframePose(*last_keyframe_) *
         keyframes_.at(*last_keyframe_).T_odom_base.inverse();
}

SceneGraph Backend::sceneGraph() const {
  SceneGraph g;
  for (const auto& [id, info] : keyframes_) {
    KeyframeNode kf;
    kf.id = id;
    kf.stamp = info.stamp;
    kf.setPose(graph_.keyframePose(id));
    g.keyframes[id] = kf;
  }
  for (const auto& [id, lm] : wall_map_.landmarks()) {
    WallNode w;
    w.id = id;
    w.normal = lm.normal;
    w.d = lm.d;
    w.endpoints = {lm.endpoints[0], lm.endpoints[1]};
    w.z_range = {lm.z_min, lm.z_max};
    w.is_wall = wall_map_.isWall(id);
    g.walls[id] = w;
  }
  g.loops = loops_;
  writeRooms(&g);
  return g;
}

}  // namespace tacs
