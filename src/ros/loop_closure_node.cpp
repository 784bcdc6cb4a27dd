#include "tacs_graphs/ros/loop_closure_node.h"

#include <tacs_graphs/LoopClosure.h>

#include <algorithm>

#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/params.h"

namespace tacs {
namespace {

// Room re-detections whose query keyframe never arrives are dropped beyond this many.
constexpr size_t kMaxWaitingRequests = 50;

}  // namespace

LoopClosureNode::LoopClosureNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))),
      detector_(config_.loop_closure) {
  loop_pub_ = nh.advertise<tacs_graphs::LoopClosure>("/tacs/loop_closures", 100);
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  keyframe_sub_ =
      nh.subscribe("/tacs/keyframe", 1000, &LoopClosureNode::keyframeCallback, this, hints);
  scene_graph_sub_ =
      nh.subscribe("/tacs/scene_graph", 10, &LoopClosureNode::sceneGraphCallback, this, hints);
  if (config_.loop_closure.method == "cosg") {
    rooms_sub_ =
        nh.subscribe("/tacs/room_observations", 100, &LoopClosureNode::roomsCallback, this, hints);
  }
  ROS_INFO_STREAM("Loop closure (" << config_.loop_closure.method << ") ready");
}

void LoopClosureNode::keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg) {
  const KeyframeInput kf = fromKeyframeMsg(*msg);
  if (!kf.ok) {
    warnings_.warn("keyframe", WarnOnce::reasonKey(kf.error), kf.error + ", skipped");
    return;
  }
  if (detector_.hasKeyframe(kf.id)) {
    warnings_.warn("keyframe", "keyframe id already known, skipped");
    return;
  }
  poses_.addOdometryPose(kf.id, kf.T_odom_base);
  latest_stamp_ = std::max(latest_stamp_, kf.stamp);
  // Stored at the odometry's grid, as the offline pipeline does: a long run keeps thousands.
  const PointCloud coarse = voxelDownsample(*kf.cloud, config_.odometry.preprocess.voxel_size_m);
  detector_.addKeyframe(kf.id, kf.stamp, *poses_.mapPose(kf.id), coarse);
  if (config_.loop_closure.method == "distance") publish(detector_.detectByDistance(kf.id), -1);

  std::deque<RoomRequest> still_waiting;
  for (const RoomRequest& request : waiting_) {
    if (detector_.hasKeyframe(request.query)) {
      detectInRoom(request);
    } else {
      still_waiting.push_back(request);
    }
  }
  waiting_.swap(still_waiting);
}

void LoopClosureNode::sceneGraphCallback(const tacs_graphs::SceneGraph::ConstPtr& msg) {
  poses_.setGraph(fromSceneGraphMsg(*msg));
  detector_.updatePoses(poses_.graphPoses());
}

void LoopClosureNode::roomsCallback(const tacs_graphs::RoomObservations::ConstPtr& msg) {
  for (const auto& room : msg->rooms) {
    if (!room.redetected) continue;
    RoomRequest request;
    request.room_id = static_cast<int>(room.room_id);
    request.room_keyframes.assign(room.keyframe_ids.begin(), room.keyframe_ids.end());
    request.query = cosgQueryKeyframe(request.room_keyframes, msg->keyframe_id);
    if (detector_.hasKeyframe(request.query)) {
      detectInRoom(request);
      continue;
    }
    waiting_.push_back(std::move(request));
    if (waiting_.size() > kMaxWaitingRequests) {
      waiting_.pop_front();
      warnings_.warn("room observation", "query keyframe never arrived, re-detection dropped");
    }
  }
}

void LoopClosureNode::detectInRoom(const RoomRequest& request) {
  publish(detector_.detectInRoom(request.query, request.room_keyframes), request.room_id);
}

void LoopClosureNode::publish(const LoopDetection& detection, int room_id) {
  for (const LoopClosure& loop : detection.loops) {
    loop_pub_.publish(toLoopClosureMsg(loop, room_id, config_.frames.map_frame, latest_stamp_));
    ++published_;
    ROS_INFO_STREAM("Loop " << loop.from << " -> " << loop.to << " (" << loopPathName(loop.path)
                            << ", score " << loop.score << ", room " << room_id << ")");
  }
}

void LoopClosureNode::shutdown() {
  const LoopDetectorStats& s = detector_.stats();
  ROS_INFO_STREAM("loop_closure ("
                  << config_.loop_closure.method << "): " << detector_.keyframeCount()
                  << " keyframes, " << s.detections << " detections, " << s.registrations
                  << " registrations, " << published_ << " loops (coarse " << s.coarse_loops
                  << ", fine " << s.fine_loops << ", distance " << s.distance_loops << "), t_LD "
                  << s.total_ms / 1000.0 << " s, " << warnings_.total() << " warnings");
}

}  // namespace tacs
