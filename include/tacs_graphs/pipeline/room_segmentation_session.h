// What the room_segmentation node keeps around the core RoomSegmenter, without ROS: the
// per-keyframe inputs (traversable graph, or cloud for the voxel baseline) until the backend has
// placed the keyframe, the TraversableMap re-posed from the backend's optimised keyframes when
// they move noticeably (better poses -> better rooms, docs/DESIGN.md), and a WallMap mirroring the
// backend's wall landmarks with their ids, so that rooms name the backend's walls (paper
// Sec. III-B, III-C).
//
// Keyframes are segmented in id order, once the scene graph holds them (their walls are then
// usually in too); a keyframe still missing from the graph after `max_wait_keyframes` newer ones
// arrived is placed with the latest map -> odom correction instead.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tacs_graphs/pipeline/map_pose_estimate.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/rooms/room_segmenter.h"
#include "tacs_graphs/traversability/traversable_map.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {

struct RoomSegmentationOptions {
  uint32_t max_wait_keyframes = 5;  // keyframes a keyframe waits for the backend at most
  double repose_distance_m = 0.05;  // [m] an optimised keyframe moved this far re-poses the map
  double repose_angle_deg = 1.0;    // [deg] or turned this much
};

/// The rooms updated while segmenting one keyframe: each mapped room (after merging) with what
/// merging did (created or re-detected, wall-to-wall edges).
struct RoomUpdate {
  uint32_t keyframe_id = 0;
  double stamp = 0.0;
  std::vector<std::pair<MappedRoom, RoomAssociation>> rooms;
  std::vector<std::string> rejected;  // free-space regions that gave no room, with the reason
};

class RoomSegmentationSession {
 public:
  /// Throws ConfigError on a bad configuration. `T_base_sensor`: the sensor mounting (the voxel
  /// method's ray origin); the configured frames.base_to_sensor when not given.
  RoomSegmentationSession(const PipelineConfig& config, const RoomSegmentationOptions& options,
                          const std::optional<Pose3>& T_base_sensor = std::nullopt);

  /// The traversable graph of a keyframe in its ground frame (`T_base_ground`, identity for a
  /// base on the floor) and the keyframe's odometry pose.
  void addGraph(uint32_t id, double stamp, const Pose3& T_odom_base, TravGraph graph,
                const Pose3& T_base_ground = Pose3::Identity());
  /// The cloud of a keyframe (base frame), used by the voxel method only.
  void addCloud(uint32_t id, double stamp, const Pose3& T_odom_base, PointCloud::ConstPtr cloud);
  /// The backend's scene graph: optimised poses and wall landmarks (`wall_observations`: their
  /// observation counts).
  void setSceneGraph(const SceneGraph& graph,
                     const std::map<uint32_t, uint32_t>& wall_observations = {});
  /// The same from the backend itself (one process): its optimised keyframe poses and walls.
  void setMap(const std::map<uint32_t, Pose3>& T_map_base, const WallMap& walls);

  /// Segments every keyframe that is ready, in id order. Returns one update per keyframe that
  /// changed rooms.
  std::vector<RoomUpdate> processReady();
  /// End of the sequence: the region still being accumulated (tacs) or a last clustering (voxel).
  RoomUpdate finish();

  bool needsClouds() const { return segmenter_.config().method == RoomMethod::kVoxel; }
  const RoomSegmenter& segmenter() const { return segmenter_; }
  const WallMap& wallMap() const { return wall_map_; }
  const TraversableMap& traversableMap() const { return traversable_map_; }
  size_t pendingCount() const { return pending_.size(); }
  size_t keyframesSegmented() const { return segmented_; }
  size_t reposes() const { return reposes_; }

 private:
  struct Pending {
    double stamp = 0.0;
    bool has_graph = false;
    TravGraph graph;
    Pose3 T_base_ground = Pose3::Identity();
    PointCloud::ConstPtr cloud;
  };
  Pending& pending(uint32_t id, double stamp, const Pose3& T_odom_base);
  bool hasInputs(const Pending& p) const;
  RoomUpdate segment(uint32_t id, const Pending& p, const Pose3& T_map_base);
  RoomUpdate toUpdate(uint32_t id, double stamp, const RoomSegmentationResult& result) const;
  void reposeIfMoved();
  /// The map pose of keyframe `id`'s ground frame, given its base pose.
  Pose3 groundPose(uint32_t id, const Pose3& T_map_base) const;

  PipelineConfig config_;
  RoomSegmentationOptions options_;
  TraversableMap traversable_map_;
  RoomSegmenter segmenter_;
  WallMap wall_map_;
  MapPoseEstimate poses_;
  std::map<uint32_t, Pending> pending_;
  std::map<uint32_t, Pose3> inserted_poses_;  // base pose each keyframe graph went in with
  std::map<uint32_t, Pose3> base_to_ground_;  // the graphs' ground frames (not identity only)
  uint32_t newest_id_ = 0;
  double last_stamp_ = 0.0;
  size_t segmented_ = 0;
  size_t reposes_ = 0;
};

}  // namespace tacs
