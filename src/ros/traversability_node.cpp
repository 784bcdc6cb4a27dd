#include "tacs_graphs/ros/traversability_node.h"

#include <pcl/common/transforms.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/Marker.h>

#include "tacs_graphs/ros/cloud_conversion.h"
#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/scene_graph_markers.h"

namespace tacs {

TraversabilityNode::TraversabilityNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))),
      mapper_(config_.traversability),
      leveller_(nh, config_.traversability.find_floor_under_base),
      ground_pub_(nh.advertise<sensor_msgs::PointCloud2>("/tacs/ground_points", 5)),
      obstacle_pub_(nh.advertise<sensor_msgs::PointCloud2>("/tacs/obstacle_points", 5)),
      marker_pub_(nh.advertise<visualization_msgs::Marker>("/tacs/traversable_markers", 100)),
      stage_(nh, pnh, "/tacs/traversable_graph", "graphs",
             [this](const KeyframeInput& kf) { return process(kf); }) {}

tacs_graphs::TraversableGraph TraversabilityNode::process(const KeyframeInput& kf) {
  // A base off the floor (hand-held): the terrain is read in the levelled floor frame under it
  // (docs/DESIGN.md, frames), and its graph handed on in that frame.
  const LevelledKeyframe levelled = leveller_.level(kf);
  const TraversabilityResult result = keyframeTraversability(mapper_, levelled);
  if (!result.warning.empty()) {
    stage_.warner().warn("traversability", WarnOnce::reasonKey(result.warning), result.warning);
  }
  publishViews(kf, result, kf.T_odom_base * levelled.T_base_ground);
  return toTraversableGraphMsg(result.graph, kf.id, kf.T_odom_base, config_.frames.base_frame,
                               kf.stamp, levelled.T_base_ground);
}

void TraversabilityNode::publishViews(const KeyframeInput& kf, const TraversabilityResult& result,
                                      const Pose3& T_odom_ground) {
  const std::string& odom = config_.frames.odom_frame;
  const Eigen::Matrix4f T = T_odom_ground.matrix().cast<float>();
  if (ground_pub_.getNumSubscribers() > 0 && result.ground) {
    PointCloud ground;
    pcl::transformPointCloud(*result.ground, ground, T);
    ground_pub_.publish(toRosCloud(ground, odom, kf.stamp));
  }
  if (obstacle_pub_.getNumSubscribers() > 0 && result.obstacles) {
    PointCloud obstacles;
    pcl::transformPointCloud(*result.obstacles, obstacles, T);
    obstacle_pub_.publish(toRosCloud(obstacles, odom, kf.stamp));
  }
  if (marker_pub_.getNumSubscribers() > 0) {
    marker_pub_.publish(traversableGraphMarker(result.graph, T_odom_ground, kf.id, odom, kf.stamp));
  }
}

}  // namespace tacs
