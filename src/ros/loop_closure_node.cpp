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

enum JournalChannel : uint8_t { kKeyframeChannel, kLoopChannel };

}  // namespace

LoopClosureNode::LoopClosureNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))),
      session_(config_.loop_closure) {
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
  resync_pub_ = requestResync(nh, "loop_closure",
                              session_.detector().keyframeCount() > 0 ? newest_id_ + 1 : 0);
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
  if (session_.hasKeyframe(kf.id)) return;  // resent for a node restarted after a crash
  journal_->record(kKeyframeChannel, *msg);
  newest_id_ = std::max(newest_id_, kf.id);
  latest_stamp_ = std::max(latest_stamp_, kf.stamp);
  // Stored at the odometry's grid, as the offline pipeline does: a long run keeps thousands.
  const PointCloud coarse = voxelDownsample(*kf.cloud, config_.odometry.preprocess.voxel_size_m);
  // Replayed from the journal: the loops found then are in the journal.
  publish(session_.addKeyframe(kf.id, kf.stamp, kf.T_odom_base, coarse, !journal_->replaying()));
}

void LoopClosureNode::sceneGraphCallback(const tacs_graphs::SceneGraph::ConstPtr& msg) {
  std::map<uint32_t, Pose3> poses;
  for (const auto& [id, kf] : fromSceneGraphMsg(*msg).keyframes) poses[id] = kf.pose();
  session_.setGraphPoses(poses);
}

void LoopClosureNode::roomsCallback(const tacs_graphs::RoomObservations::ConstPtr& msg) {
  if (msg->complete_set) return;  // rooms sent again after a restart, no re-detection
  for (const auto& room : msg->rooms) {
    if (!room.redetected) continue;
    const size_t dropped = session_.droppedRequests();
    publish(session_.roomRedetected(static_cast<int>(room.room_id),
                                    {room.keyframe_ids.begin(), room.keyframe_ids.end()},
                                    msg->keyframe_id));
    if (session_.droppedRequests() > dropped) {
      warnings_.warn("room observation", "query keyframe never arrived, re-detection dropped");
    }
  }
}

void LoopClosureNode::publish(const std::vector<RoomLoopDetection>& detections) {
  for (const RoomLoopDetection& found : detections) {
    for (const LoopClosure& loop : found.detection.loops) {
      const tacs_graphs::LoopClosure msg =
          toLoopClosureMsg(loop, found.room_id, config_.frames.map_frame, latest_stamp_);
      loop_pub_.publish(msg);
      journal_->record(kLoopChannel, msg);
      loops_sent_.push_back(msg);
      ++published_;
      ROS_INFO_STREAM("Loop " << loop.from << " -> " << loop.to << " (" << loopPathName(loop.path)
                              << ", score " << loop.score << ", room " << found.room_id << ")");
    }
  }
}

void LoopClosureNode::shutdown() {
  const LoopDetectorStats& s = session_.detector().stats();
  ROS_INFO_STREAM("loop_closure (" << enumName(config_.loop_closure.method)
                                   << "): " << session_.detector().keyframeCount() << " keyframes, "
                                   << s.detections << " detections, " << s.registrations
                                   << " registrations, " << published_ << " loops (coarse "
                                   << s.coarse_loops << ", fine " << s.fine_loops << ", distance "
                                   << s.distance_loops << "), t_LD " << s.total_ms / 1000.0
                                   << " s, " << warnings_.total() << " warnings");
}

}  // namespace tacs
