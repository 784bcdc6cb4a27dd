#include "tacs_graphs/ros/room_segmentation_node.h"

#include <tacs_graphs/RoomObservations.h>

#include <algorithm>

#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/message_conversion.h"
#include "tacs_graphs/ros/params.h"
#include "tacs_graphs/ros/resend_buffer.h"

namespace tacs {
namespace {

enum JournalChannel : uint8_t { kGraphChannel, kKeyframeChannel };

}  // namespace

RoomSegmentationNode::RoomSegmentationNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))) {
  RoomSegmentationOptions options;
  options.max_wait_keyframes =
      static_cast<uint32_t>(boundedParam(pnh, "max_wait_keyframes", 5, 0, true));
  options.repose_distance_m =
      boundedParam(pnh, "repose_distance_m", options.repose_distance_m, 0.0, true);
  options.repose_angle_deg =
      boundedParam(pnh, "repose_angle_deg", options.repose_angle_deg, 0.0, true);
  session_ = std::make_unique<RoomSegmentationSession>(config_, options);
  journal_ = std::make_unique<NodeJournal>(pnh, "room_segmentation");
  if (journal_->mustReplay()) replayJournal(nh);

  rooms_pub_ = nh.advertise<tacs_graphs::RoomObservations>("/tacs/room_observations", 100);
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  if (session_->needsClouds()) {
    keyframe_sub_ =
        nh.subscribe("/tacs/keyframe", 1000, &RoomSegmentationNode::keyframeCallback, this, hints);
  } else {
    graph_sub_ = nh.subscribe("/tacs/traversable_graph", 1000, &RoomSegmentationNode::graphCallback,
                              this, hints);
  }
  scene_graph_sub_ =
      nh.subscribe("/tacs/scene_graph", 10, &RoomSegmentationNode::sceneGraphCallback, this, hints);
  resync_sub_ = nh.subscribe("/tacs/resync", 10, &RoomSegmentationNode::resyncCallback, this);
  ROS_INFO_STREAM("Room segmentation (" << enumName(config_.rooms.method) << ") ready");
}

void RoomSegmentationNode::replayJournal(ros::NodeHandle& nh) {
  // Inputs only: segmenting waits for the backend's scene graph (latched, it comes at once).
  journal_->replay([this](uint8_t channel, const std::vector<uint8_t>& bytes) {
    if (channel == kGraphChannel) {
      graphCallback(MessageJournal::deserialize<tacs_graphs::TraversableGraph>(bytes));
    } else if (channel == kKeyframeChannel) {
      keyframeCallback(MessageJournal::deserialize<tacs_graphs::Keyframe>(bytes));
    }
  });
  complete_set_due_ = true;
  resync_pub_ = requestResync(nh, "room_segmentation", static_cast<uint32_t>(newest_input_id_ + 1));
}

void RoomSegmentationNode::resyncCallback(const tacs_graphs::Resync::ConstPtr& msg) {
  if (msg->requester == "room_segmentation") return;
  publishCompleteSet();
}

void RoomSegmentationNode::publishCompleteSet() {
  tacs_graphs::RoomObservations msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = config_.frames.map_frame;
  msg.complete_set = true;
  RoomAssociation as_known;  // created: not a re-detection, no new wall-to-wall edges
  for (const auto& [id, room] : session_->segmenter().rooms()) {
    msg.rooms.push_back(toRoomObservationMsg(room, as_known));
  }
  rooms_pub_.publish(msg);
  ROS_WARN_STREAM("room_segmentation: sent all " << msg.rooms.size() << " rooms again");
}

void RoomSegmentationNode::graphCallback(const tacs_graphs::TraversableGraph::ConstPtr& msg) {
  // One publisher sends graphs in id order: an older id is one sent again for another node.
  if (static_cast<int64_t>(msg->keyframe_id) <= newest_input_id_) return;
  newest_input_id_ = msg->keyframe_id;
  journal_->record(kGraphChannel, *msg);
  const Pose3 T_odom_base = fromPoseMsg(msg->odom_pose);
  const Pose3 T_base_ground = fromPoseMsg(msg->ground_in_base);
  if (!T_odom_base.matrix().allFinite() || !T_base_ground.matrix().allFinite()) {
    warnings_.warn("traversable graph", "non-finite odometry or ground pose, skipped");
    return;
  }
  session_->addGraph(msg->keyframe_id, msg->header.stamp.toSec(), T_odom_base,
                     fromTraversableGraphMsg(*msg), T_base_ground);
  if (!journal_->replaying()) processReady();
}

void RoomSegmentationNode::keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg) {
  if (static_cast<int64_t>(msg->id) <= newest_input_id_) return;  // resent for another node
  newest_input_id_ = msg->id;
  journal_->record(kKeyframeChannel, *msg);
  const KeyframeInput kf = fromKeyframeMsg(*msg);
  if (!kf.ok) {
    warnings_.warn("keyframe", WarnOnce::reasonKey(kf.error), kf.error + ", skipped");
    return;
  }
  session_->addCloud(kf.id, kf.stamp, kf.T_odom_base, kf.cloud);
  if (!journal_->replaying()) processReady();
}

void RoomSegmentationNode::sceneGraphCallback(const tacs_graphs::SceneGraph::ConstPtr& msg) {
  std::map<uint32_t, uint32_t> observations;
  for (const auto& w : msg->walls) observations[w.id] = w.observation_count;
  session_->setSceneGraph(fromSceneGraphMsg(*msg), observations);
  processReady();
  if (complete_set_due_) {
    complete_set_due_ = false;
    publishCompleteSet();
  }
}

void RoomSegmentationNode::processReady() {
  for (const RoomUpdate& update : session_->processReady()) publish(update);
}

void RoomSegmentationNode::publish(const RoomUpdate& update) {
  if (update.rooms.empty()) return;
  tacs_graphs::RoomObservations msg;
  msg.header.stamp.fromSec(update.stamp);
  msg.header.frame_id = config_.frames.map_frame;
  msg.keyframe_id = update.keyframe_id;
  for (const auto& [room, association] : update.rooms) {
    msg.rooms.push_back(toRoomObservationMsg(room, association));
    if (!association.created) ++redetections_;
  }
  published_ += update.rooms.size();
  rooms_pub_.publish(msg);
}

void RoomSegmentationNode::shutdown() {
  publish(session_->finish());
  ROS_INFO_STREAM("room_segmentation: " << session_->keyframesSegmented() << " keyframes, "
                                        << session_->segmenter().rooms().size() << " rooms, "
                                        << published_ << " room updates (" << redetections_
                                        << " re-detections), " << session_->reposes()
                                        << " map re-posings, " << warnings_.total() << " warnings");
}

}  // namespace tacs
