// What the loop_closure node keeps around the core LoopDetector, without ROS: map-frame poses of
// the keyframes from the backend's optimised graph (MapPoseEstimate), and the room re-detections
// whose query keyframe has not arrived yet. A re-detected room triggers CoSG-LCD (paper
// Sec. III-D); the distance baseline runs on every new keyframe instead. The offline Pipeline
// runs the same session.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "tacs_graphs/loop_closure/loop_detector.h"
#include "tacs_graphs/pipeline/map_pose_estimate.h"

namespace tacs {

/// One detection and the room whose re-detection triggered it (-1: the distance baseline).
struct RoomLoopDetection {
  LoopDetection detection;
  int room_id = -1;
};

class LoopClosureSession {
 public:
  /// Re-detections whose query keyframe never arrives are dropped beyond this many.
  static constexpr size_t kMaxWaitingRequests = 50;

  explicit LoopClosureSession(const LoopClosureConfig& config) : detector_(config) {}

  /// Stores a keyframe (odometry pose; cloud in the base frame at the odometry's grid), placed
  /// in the map with the latest correction. Returns the detections it triggers: the distance
  /// baseline on it, and re-detections that waited for it. `detect` false (a journal replay,
  /// whose loops are known) only stores. A keyframe already held is ignored.
  std::vector<RoomLoopDetection> addKeyframe(uint32_t id, double stamp, const Pose3& T_odom_base,
                                             const PointCloud& cloud, bool detect = true);
  /// A room re-detected at keyframe `observing_keyframe`: CoSG-LCD on its query keyframe
  /// (cosgQueryKeyframe), now or once that keyframe has arrived.
  std::vector<RoomLoopDetection> roomRedetected(int room_id,
                                                const std::vector<uint32_t>& room_keyframes,
                                                uint32_t observing_keyframe);
  /// Optimised keyframe poses (the backend's graph); the detector's candidates follow them.
  void setGraphPoses(const std::map<uint32_t, Pose3>& T_map_base);

  const LoopDetector& detector() const { return detector_; }
  bool hasKeyframe(uint32_t id) const { return detector_.hasKeyframe(id); }
  /// Re-detections dropped because their query keyframe never arrived.
  size_t droppedRequests() const { return dropped_requests_; }

 private:
  struct RoomRequest {
    int room_id = -1;
    uint32_t query = 0;
    std::vector<uint32_t> room_keyframes;
  };
  RoomLoopDetection detectInRoom(const RoomRequest& request);

  LoopDetector detector_;
  MapPoseEstimate poses_;
  std::deque<RoomRequest> waiting_;
  size_t dropped_requests_ = 0;
};

}  // namespace tacs
