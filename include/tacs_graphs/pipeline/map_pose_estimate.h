// Map-frame keyframe poses for the nodes that read the backend's scene graph back (room
// segmentation, loop closure). A keyframe the backend has optimised takes its pose from the
// latest scene graph; a newer one, not yet in the graph, is placed with the latest map -> odom
// correction (from the newest graph keyframe whose odometry pose is known), as the backend
// itself starts new keyframes. ROS-free.
#pragma once

#include <cstdint>
#include <map>
#include <optional>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/scene_graph/scene_graph.h"

namespace tacs {

class MapPoseEstimate {
 public:
  /// The odometry pose of a keyframe (from its Keyframe or TraversableGraph message).
  void addOdometryPose(uint32_t id, const Pose3& T_odom_base);
  /// Optimised poses of the backend's scene graph; replaces the previous ones.
  void setGraph(const SceneGraph& graph);
  /// The same from the optimised keyframe poses themselves.
  void setPoses(const std::map<uint32_t, Pose3>& T_map_base);

  /// The optimised pose, when the latest scene graph holds the keyframe.
  std::optional<Pose3> optimised(uint32_t id) const;
  /// Optimised pose, else T_map_odom * T_odom_base, else (odometry pose unknown) nullopt.
  std::optional<Pose3> mapPose(uint32_t id) const;
  /// The latest map -> odom correction (identity before the first graph).
  const Pose3& mapToOdom() const { return T_map_odom_; }
  /// Keyframe poses of the latest scene graph.
  const std::map<uint32_t, Pose3>& graphPoses() const { return graph_poses_; }

 private:
  std::map<uint32_t, Pose3> odom_poses_;
  std::map<uint32_t, Pose3> graph_poses_;
  Pose3 T_map_odom_ = Pose3::Identity();
};

}  // namespace tacs
