// The traversability node: keyframes -> TraversabilityMapper -> /tacs/traversable_graph (one
// TraversableGraph per keyframe, in its ground frame, with the keyframe id and odometry pose), the
// keyframe's ground and obstacle points (/tacs/ground_points, /tacs/obstacle_points) and the
// graph drawn for rviz (/tacs/traversable_markers), both in the odometry frame.
// Resent keyframes and the Resync answer: keyframe_stage_node.h.
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/TraversableGraph.h>

#include "tacs_graphs/pipeline/keyframe_stages.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/ros/keyframe_stage_node.h"
#include "tacs_graphs/ros/node_ground_leveller.h"

namespace tacs {

class TraversabilityNode {
 public:
  /// Reads the configuration under ~config_ns (default /tacs). Throws ConfigError.
  TraversabilityNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  size_t keyframesProcessed() const { return stage_.keyframesProcessed(); }
  size_t warnings() const { return stage_.warnings(); }

 private:
  tacs_graphs::TraversableGraph process(const KeyframeInput& kf);
  /// Ground and obstacle points and the graph markers, for rviz (only when subscribed).
  void publishViews(const KeyframeInput& kf, const TraversabilityResult& result,
                    const Pose3& T_odom_ground);

  PipelineConfig config_;
  TraversabilityMapper mapper_;
  NodeGroundLeveller leveller_;  // traversability.find_floor_under_base: a hand-held sensor
  ros::Publisher ground_pub_, obstacle_pub_, marker_pub_;
  KeyframeStageNode<tacs_graphs::TraversableGraph> stage_;
};

}  // namespace tacs
