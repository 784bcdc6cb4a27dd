#include "tacs_graphs/ros/traversability_node.h"

#include <pcl/common/transforms.h>
#include <sensor_msgs/PointCloud2.h>
#include <tacs_graphs/TraversableGraph.h>
#include <visualization_msgs/Marker.h>

#include "tacs_graphs/ros/cloud_conversion.h"
#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/params.h"
#include "tacs_graphs/ros/scene_graph_markers.h"

namespace tacs {

TraversabilityNode::TraversabilityNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : config_(loadPipelineConfigFromRos(nh, pnh.param<std::string>("config_ns", "/tacs"))),
      mapper_(config_.traversability),
      leveller_(nh, config_.traversability.find_floor_under_base),
      sent_(static_cast<size_t>(boundedParam(pnh, "resend_capacity", 100, 0, true)), "graphs") {
  graph_pub_ = nh.advertise<tacs_graphs::TraversableGraph>("/tacs/traversable_graph", 100);
  ground_pub_ = nh.advertise<sensor_msgs::PointCloud2>("/tacs/ground_points", 5);
  obstacle_pub_ = nh.advertise<sensor_msgs::PointCloud2>("/tacs/obstacle_points", 5);
  marker_pub_ = nh.advertise<visualization_msgs::Marker>("/tacs/traversable_markers", 100);
  keyframe_sub_ = nh.subscribe("/tacs/keyframe", 1000, &TraversabilityNode::keyframeCallback, this,
                               ros::TransportHints().tcpNoDelay());
  resync_sub_ = nh.subscribe("/tacs/resync", 10, &TraversabilityNode::resyncCallback, this);
}

void TraversabilityNode::resyncCallback(const tacs_graphs::Resync::ConstPtr& msg) {
  sent_.answer(*msg, graph_pub_);
}

void TraversabilityNode::keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg) {
  const KeyframeInput kf = fromKeyframeMsg(*msg);
  if (!kf.ok) {
    warnings_.warn("keyframe", WarnOnce::reasonKey(kf.error), kf.error + ", skipped");
    return;
  }
  // A keyframe resent for a restarted node: its graph goes out again from sent_ on the Resync.
  if (static_cast<int64_t>(kf.id) <= newest_id_) return;
  newest_id_ = kf.id;
  // A base off the floor (hand-held): the terrain is read in the levelled floor frame under it
  // (docs/DESIGN.md, frames), and its graph handed on in that frame.
  const LevelledKeyframe levelled = leveller_.level(kf);
  const TraversabilityResult result = keyframeTraversability(mapper_, levelled);
  if (!result.warning.empty()) {
    warnings_.warn("traversability", WarnOnce::reasonKey(result.warning), result.warning);
  }
  ++processed_;
  const std::string& odom = config_.frames.odom_frame;
  graph_pub_.publish(sent_.keep(
      kf.id, toTraversableGraphMsg(result.graph, kf.id, kf.T_odom_base, config_.frames.base_frame,
                                   kf.stamp, levelled.T_base_ground)));
  const Eigen::Matrix4f T = (kf.T_odom_base * levelled.T_base_ground).matrix().cast<float>();
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
    marker_pub_.publish(traversableGraphMarker(
        result.graph, kf.T_odom_base * levelled.T_base_ground, kf.id, odom, kf.stamp));
  }
}

}  // namespace tacs
