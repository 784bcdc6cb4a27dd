#include "tacs_graphs/pipeline/map_pose_estimate.h"

namespace tacs {

void MapPoseEstimate::addOdometryPose(uint32_t id, const Pose3& T_odom_base) {
  odom_poses_[id] = T_odom_base;
}

void MapPoseEstimate::setGraph(const SceneGraph& graph) {
  std::map<uint32_t, Pose3> poses;
  for (const auto& [id, kf] : graph.keyframes) poses[id] = kf.pose();
  setPoses(poses);
}

void MapPoseEstimate::setPoses(const std::map<uint32_t, Pose3>& T_map_base) {
  graph_poses_ = T_map_base;
  // The newest optimised keyframe carries the current correction (the backend's mapToOdom()).
  for (auto it = graph_poses_.rbegin(); it != graph_poses_.rend(); ++it) {
    const auto odom = odom_poses_.find(it->first);
    if (odom == odom_poses_.end()) continue;
    T_map_odom_ = it->second * odom->second.inverse();
    break;
  }
}

std::optional<Pose3> MapPoseEstimate::optimised(uint32_t id) const {
  const auto it = graph_poses_.find(id);
  if (it == graph_poses_.end()) return std::nullopt;
  return it->second;
}

std::optional<Pose3> MapPoseEstimate::mapPose(uint32_t id) const {
  if (auto pose = optimised(id)) return pose;
  const auto odom = odom_poses_.find(id);
  if (odom == odom_poses_.end()) return std::nullopt;
  return T_map_odom_ * odom->second;
}

}  // namespace tacs
