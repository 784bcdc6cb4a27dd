// The wall_extraction node: keyframes -> WallExtractor (paper Sec. III-B-1) ->
// /tacs/wall_observations (vertical planes in the keyframe's base frame, with the keyframe id).
// A keyframe resent after a crash elsewhere is not extracted again; the last ~resend_capacity (100)
// wall messages are sent again on a tacs_graphs/Resync instead (resend_buffer.h).
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/Resync.h>
#include <tacs_graphs/WallObservations.h>

#include "tacs_graphs/pipeline/keyframe_stages.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/ros/node_ground_leveller.h"
#include "tacs_graphs/ros/resend_buffer.h"
#include "tacs_graphs/ros/warn_once.h"

namespace tacs {

class WallExtractionNode {
 public:
  /// Reads the configuration under ~config_ns (default /tacs). Throws ConfigError.
  WallExtractionNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  size_t keyframesProcessed() const { return processed_; }
  /// Keyframes skipped or processed with a warning.
  size_t warnings() const { return warnings_.total(); }

 private:
  void keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg);
  void resyncCallback(const tacs_graphs::Resync::ConstPtr& msg);

  PipelineConfig config_;
  WallExtractor extractor_;
  NodeGroundLeveller leveller_;  // traversability.find_floor_under_base: a hand-held sensor
  ros::Subscriber keyframe_sub_, resync_sub_;
  ros::Publisher walls_pub_;
  ResendBuffer<tacs_graphs::WallObservations> sent_;
  int64_t newest_id_ = -1;
  WarnOnce warnings_;
  size_t processed_ = 0;
};

}  // namespace tacs
