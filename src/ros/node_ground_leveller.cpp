#include "tacs_graphs/ros/node_ground_leveller.h"

#include "tacs_graphs/ros/graph_messages.h"

namespace tacs {

NodeGroundLeveller::NodeGroundLeveller(ros::NodeHandle& nh, bool find_floor_under_base)
    : leveller_(find_floor_under_base) {
  if (!find_floor_under_base) return;
  scene_graph_sub_ = nh.subscribe("/tacs/scene_graph", 10, &NodeGroundLeveller::sceneGraphCallback,
                                  this, ros::TransportHints().tcpNoDelay());
}

void NodeGroundLeveller::sceneGraphCallback(const tacs_graphs::SceneGraph::ConstPtr& msg) {
  poses_.setGraph(fromSceneGraphMsg(*msg));
}

LevelledKeyframe NodeGroundLeveller::level(const KeyframeInput& keyframe) {
  poses_.addOdometryPose(keyframe.id, keyframe.T_odom_base);
  return leveller_.level(keyframe.cloud, *poses_.mapPose(keyframe.id));
}

}  // namespace tacs
