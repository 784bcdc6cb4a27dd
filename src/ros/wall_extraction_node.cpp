#include "tacs_graphs/ros/wall_extraction_node.h"

#include "tacs_graphs/ros/graph_messages.h"

namespace tacs {

WallExtractionNode::WallExtractionNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))),
      extractor_(config_.walls.extraction),
      leveller_(nh, config_.traversability.find_floor_under_base),
      stage_(nh, pnh, "/tacs/wall_observations", "walls",
             [this](const KeyframeInput& kf) { return process(kf); }) {}

tacs_graphs::WallObservations WallExtractionNode::process(const KeyframeInput& kf) {
  const WallExtractionResult result =
      extractKeyframeWalls(extractor_, leveller_.level(kf), kf.sensor_in_base);
  tacs_graphs::WallObservations out;
  out.header.stamp.fromSec(kf.stamp);
  out.header.frame_id = config_.frames.base_frame;
  out.keyframe_id = kf.id;
  out.walls.reserve(result.walls.size());
  for (const WallSegment& w : result.walls) out.walls.push_back(toWallObservationMsg(w));
  out.seen_over.reserve(result.seen_over.size());
  for (const WallSegment& w : result.seen_over) out.seen_over.push_back(toWallObservationMsg(w));
  return out;
}

}  // namespace tacs
