#include "tacs_graphs/pipeline/loop_closure_session.h"

namespace tacs {

std::vector<RoomLoopDetection> LoopClosureSession::addKeyframe(uint32_t id, double stamp,
                                                               const Pose3& T_odom_base,
                                                               const PointCloud& cloud,
                                                               bool detect) {
  std::vector<RoomLoopDetection> found;
  if (detector_.hasKeyframe(id)) return found;
  poses_.addOdometryPose(id, T_odom_base);
  detector_.addKeyframe(id, stamp, *poses_.mapPose(id), cloud);
  if (!detect) return found;
  if (detector_.config().method == LoopMethod::kDistance) {
    found.push_back({detector_.detectByDistance(id), -1});
  }
  std::deque<RoomRequest> still_waiting;
  for (RoomRequest& request : waiting_) {
    if (detector_.hasKeyframe(request.query)) {
      found.push_back(detectInRoom(request));
    } else {
      still_waiting.push_back(std::move(request));
    }
  }
  waiting_.swap(still_waiting);
  return found;
}

std::vector<RoomLoopDetection> LoopClosureSession::roomRedetected(
    int room_id, const std::vector<uint32_t>& room_keyframes, uint32_t observing_keyframe) {
  std::vector<RoomLoopDetection> found;
  if (detector_.config().method != LoopMethod::kCosg) return found;
  RoomRequest request;
  request.room_id = room_id;
  request.room_keyframes = room_keyframes;
  request.query = cosgQueryKeyframe(room_keyframes, observing_keyframe);
  if (detector_.hasKeyframe(request.query)) {
    found.push_back(detectInRoom(request));
    return found;
  }
  waiting_.push_back(std::move(request));
  if (waiting_.size() > kMaxWaitingRequests) {
    waiting_.pop_front();
    ++dropped_requests_;
  }
  return found;
}

void LoopClosureSession::setGraphPoses(const std::map<uint32_t, Pose3>& T_map_base) {
  poses_.setPoses(T_map_base);
  detector_.updatePoses(T_map_base);
}

RoomLoopDetection LoopClosureSession::detectInRoom(const RoomRequest& request) {
  return {detector_.detectInRoom(request.query, request.room_keyframes), request.room_id};
}

}  // namespace tacs
