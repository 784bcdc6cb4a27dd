// The ground frame of keyframes for a node (traversability, wall_extraction): GroundLeveller
// levelled by each keyframe's map attitude, as the offline Pipeline levels by the backend's pose.
// With traversability.find_floor_under_base the node follows the backend's scene graph
// (/tacs/scene_graph) for that attitude (MapPoseEstimate); otherwise it subscribes to nothing.
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/SceneGraph.h>

#include "tacs_graphs/pipeline/keyframe_stages.h"
#include "tacs_graphs/pipeline/map_pose_estimate.h"
#include "tacs_graphs/ros/keyframe_input.h"

namespace tacs {

class NodeGroundLeveller {
 public:
  NodeGroundLeveller(ros::NodeHandle& nh, bool find_floor_under_base);
  LevelledKeyframe level(const KeyframeInput& keyframe);

 private:
  void sceneGraphCallback(const tacs_graphs::SceneGraph::ConstPtr& msg);

  GroundLeveller leveller_;
  MapPoseEstimate poses_;
  ros::Subscriber scene_graph_sub_;
};

}  // namespace tacs
