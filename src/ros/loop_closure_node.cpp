#include "tacs_graphs/ros/loop_closure_node.h"

#include <tacs_graphs/LoopClosure.h>

#include <algorithm>

#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/params.h"
#include "tacs_graphs/ros/resend_buffer.h"

namespace tacs {
namespace {

// Room re-detections whose query keyframe never arrives are dropped beyond this many.
constexpr size_t kMaxWaitingRequests = 50;

enum JournalChannel : uint8_t { kKeyframeChannel, kLoopChannel };

}  // namespace

LoopClosureNode::LoopClosureNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))),
      detector_(config_.loop_closure) {
  loop_pub_ = nh.advertise<tacs_graphs::LoopClosure>("/tacs/loop_closures", 100);
  journal_ = std::make_unique<NodeJournal>(pnh, "loop_closure");
  if (journal_->mustReplay()) replayJournal(nh);
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  keyframe_sub_ =
      nh.subscribe("/tacs/keyframe", 1000, &LoopClosureNode::keyframeCallback, this, hints);
  scene_graph_sub_ =
      nh.subscribe("/tacs/scene_graph", 10, &LoopClosureNode::sceneGraphCallback, this, hints);
  if (config_.loop_closure.method == LoopMethod::kCosg) {
    rooms_sub_ =
        nh.subscribe("/tacs/room_observations", 100, &LoopClosureNode::roomsCallback, this, hints);
  }
  resync_sub_ = nh.subscribe("/tacs/resync", 10, &LoopClosureNode::resyncCallback, this);
  ROS_INFO_STREAM("Loop closure (" << enumName(config_.loop_closure.method) << ") ready");
}

void LoopClosureNode::replayJournal(ros::NodeHandle& nh) {
  journal_->replay([this](uint8_t channel, const std::vector<uint8_t>& bytes) {
    if (channel == kKeyframeChannel) {
      keyframeCallback(MessageJournal::deserialize<tacs_graphs::Keyframe>(bytes));
    } else if (channel == kLoopChannel) {
      loops_sent_.push_back(*MessageJournal::deserialize<tacs_graphs::LoopClosure>(bytes));
    }
  });
  resync_pub_ =
      requestResync(nh, "loop_closure", detector_.keyframeCount() > 0 ? newest_id_ + 1 : 0);
}

void LoopClosureNode::resyncCallback(const tacs_graphs::Resync::ConstPtr& msg) {
  if (msg->requester == "loop_closure") return;
  for (const auto& loop : loops_sent_) loop_pub_.publish(loop);
  ROS_WARN_STREAM("loop_closure: sent all " << loops_sent_.size() << " loops again");
}

void LoopClosureNode::keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg) {
  const KeyframeInput kf = fromKeyframeMsg(*msg);
  if (!kf.ok) {
    warnings_.warn("keyframe", WarnOnce::reasonKey(kf.error), kf.error + ", skipped");
    return;
  }
  if (detector_.hasKeyframe(kf.id)) return;  // resent for a node restarted after a crash
  journal_->record(kKeyframeChannel, *msg);
  newest_id_ = std::max(newest_id_, kf.id);
  poses_.addOdometryPose(kf.id, kf.T_odom_base);
  latest_stamp_ = std::max(latest_stamp_, kf.stamp);
  // Stored at the odometry's grid, as the offline pipeline does: a long run keeps thousands.
  const PointCloud coarse = voxelDownsample(*kf.cloud, config_.odometry.preprocess.voxel_size_m);
  detector_.addKeyframe(kf.id, kf.stamp, *poses_.mapPose(kf.id), coarse);
  if (journal_->replaying()) return;  // the loops found then are in the journal
  if (config_.loop_closure.method == LoopMethod::kDistance)
    publish(detector_.detectByDistance(kf.id), -1);

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
  if (msg->complete_set) return;  // rooms sent again after a restart, no re-detection
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
    const tacs_graphs::LoopClosure msg =
        toLoopClosureMsg(loop, room_id, config_.frames.map_frame, latest_stamp_);
    loop_pub_.publish(msg);
    journal_->record(kLoopChannel, msg);
    loops_sent_.push_back(msg);
    ++published_;
    ROS_INFO_STREAM("Loop " << loop.from << " -> " << loop.to << " (" << loopPathName(loop.path)
                            << ", score " << loop.score << ", room " << room_id << ")");
  }
}

void LoopClosureNode::shutdown() {
  const LoopDetectorStats& s = detector_.stats();
  ROS_INFO_STREAM("loop_closure ("
                  << enumName(config_.loop_closure.method) << "): " << detector_.keyframeCount()
                  << " keyframes, " << s.detections << " detections, " << s.registrations
                  << " registrations, " << published_ << " loops (coarse " << s.coarse_loops
                  << ", fine " << s.fine_loops << ", distance " << s.distance_loops << "), t_LD "
                  << s.total_ms / 1000.0 << " s, " << warnings_.total() << " warnings");
}

}  // namespace tacs
