// The traversability node: keyframes -> TraversabilityMapper -> /tacs/traversable_graph (one
// TraversableGraph per keyframe, base frame, with the keyframe id and odometry pose), the
// keyframe's ground and obstacle points (/tacs/ground_points, /tacs/obstacle_points) and the
// graph drawn for rviz (/tacs/traversable_markers), both in the odometry frame.
// A keyframe resent after a crash elsewhere is not processed again; the last ~resend_capacity (100)
// graphs are sent again on a tacs_graphs/Resync instead (resend_buffer.h).
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/Resync.h>
#include <tacs_graphs/TraversableGraph.h>

#include "tacs_graphs/pipeline/keyframe_stages.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/ros/node_ground_leveller.h"
#include "tacs_graphs/ros/resend_buffer.h"
#include "tacs_graphs/ros/warn_once.h"

namespace tacs {

class TraversabilityNode {
 public:
  /// Reads the configuration under ~config_ns (default /tacs). Throws ConfigError.
  TraversabilityNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  size_t keyframesProcessed() const { return processed_; }
  /// Keyframes skipped or processed with a warning.
  size_t warnings() const { return warnings_.total(); }

 private:
  void keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg);
  void resyncCallback(const tacs_graphs::Resync::ConstPtr& msg);

  PipelineConfig config_;
  TraversabilityMapper mapper_;
  NodeGroundLeveller leveller_;  // traversability.find_floor_under_base: a hand-held sensor
  ros::Subscriber keyframe_sub_, resync_sub_;
  ros::Publisher graph_pub_, ground_pub_, obstacle_pub_, marker_pub_;
  ResendBuffer<tacs_graphs::TraversableGraph> sent_;
  int64_t newest_id_ = -1;
  WarnOnce warnings_;
  size_t processed_ = 0;
};

}  // namespace tacs
