#include "tacs_graphs/ros/message_conversion.h"

#include <tf2_eigen/tf2_eigen.h>

namespace tacs {

geometry_msgs::Point toPoint(const Eigen::Vector3d& p) {
  geometry_msgs::Point out;
  out.x = p.x();
  out.y = p.y();
  out.z = p.z();
  return out;
}

Eigen::Vector3d fromPoint(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }

geometry_msgs::Pose toPoseMsg(const Pose3& pose) { return tf2::toMsg(pose); }

Pose3 fromPoseMsg(const geometry_msgs::Pose& msg) {
  Pose3 pose;
  tf2::fromMsg(msg, pose);
  return pose;
}

geometry_msgs::TransformStamped toTransformMsg(const Pose3& T_parent_child,
                                               const std::string& parent, const std::string& child,
                                               double stamp) {
  geometry_msgs::TransformStamped t = tf2::eigenToTransform(T_parent_child);
  t.header.frame_id = parent;
  t.header.stamp.fromSec(stamp);
  t.child_frame_id = child;
  return t;
}

nav_msgs::Odometry toOdometryMsg(const Pose3& T_parent_child, const std::string& parent,
                                 const std::string& child, double stamp) {
  nav_msgs::Odometry odom;
  odom.header.frame_id = parent;
  odom.header.stamp.fromSec(stamp);
  odom.child_frame_id = child;
  odom.pose.pose = toPoseMsg(T_parent_child);
  return odom;
}

}  // namespace tacs
