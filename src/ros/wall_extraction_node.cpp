#include "tacs_graphs/ros/wall_extraction_node.h"

#include <tacs_graphs/WallObservations.h>

#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/params.h"

namespace tacs {

WallExtractionNode::WallExtractionNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))),
      extractor_(config_.walls.extraction),
      leveller_(nh, config_.traversability.find_floor_under_base),
      sent_(static_cast<size_t>(boundedParam(pnh, "resend_capacity", 100, 0, true)), "walls") {
  walls_pub_ = nh.advertise<tacs_graphs::WallObservations>("/tacs/wall_observations", 100);
  keyframe_sub_ = nh.subscribe("/tacs/keyframe", 1000, &WallExtractionNode::keyframeCallback, this,
                               ros::TransportHints().tcpNoDelay());
  resync_sub_ = nh.subscribe("/tacs/resync", 10, &WallExtractionNode::resyncCallback, this);
}

void WallExtractionNode::resyncCallback(const tacs_graphs::Resync::ConstPtr& msg) {
  sent_.answer(*msg, walls_pub_);
}

void WallExtractionNode::keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg) {
  const KeyframeInput kf = fromKeyframeMsg(*msg);
  if (!kf.ok) {
    warnings_.warn("keyframe", WarnOnce::reasonKey(kf.error), kf.error + ", skipped");
    return;
  }
  // A keyframe resent for a restarted node: its walls go out again from sent_ on the Resync.
  if (static_cast<int64_t>(kf.id) <= newest_id_) return;
  newest_id_ = kf.id;
  const WallExtractionResult result =
      extractKeyframeWalls(extractor_, leveller_.level(kf), kf.sensor_in_base);
  ++processed_;
  tacs_graphs::WallObservations out;
  out.header.stamp = msg->header.stamp;
  out.header.frame_id = config_.frames.base_frame;
  out.keyframe_id = kf.id;
  out.walls.reserve(result.walls.size());
  for (const WallSegment& w : result.walls) out.walls.push_back(toWallObservationMsg(w));
  out.seen_over.reserve(result.seen_over.size());
  for (const WallSegment& w : result.seen_over) out.seen_over.push_back(toWallObservationMsg(w));
  // Published even when empty: the backend then knows this keyframe's walls are complete.
  walls_pub_.publish(sent_.keep(kf.id, std::move(out)));
}

}  // namespace tacs
