// The wall_extraction node: keyframes -> WallExtractor (paper Sec. III-B-1) ->
// /tacs/wall_observations (vertical planes in the keyframe's base frame, with the keyframe id).
// Resent keyframes and the Resync answer: keyframe_stage_node.h.
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/WallObservations.h>

#include "tacs_graphs/pipeline/keyframe_stages.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/ros/keyframe_stage_node.h"
#include "tacs_graphs/ros/node_ground_leveller.h"

namespace tacs {

class WallExtractionNode {
 public:
  /// Reads the configuration under ~config_ns (default /tacs). Throws ConfigError.
  WallExtractionNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  size_t keyframesProcessed() const { return stage_.keyframesProcessed(); }
  size_t warnings() const { return stage_.warnings(); }

 private:
  tacs_graphs::WallObservations process(const KeyframeInput& kf);

  PipelineConfig config_;
  WallExtractor extractor_;
  NodeGroundLeveller leveller_;  // traversability.find_floor_under_base: a hand-held sensor
  KeyframeStageNode<tacs_graphs::WallObservations> stage_;
};

}  // namespace tacs
