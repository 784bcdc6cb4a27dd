#include "tacs_graphs/ros/message_conversion.h"

#include <tf2_eigen/tf2_eigen.h>

namespace tacs {

namespace {

// geometry_msgs::Point and Vector3 share their x, y, z fields.
template <class XyzMsg>
XyzMsg toXyz(const Eigen::Vector3d& v) {
  XyzMsg out;
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
  return out;
}

template <class XyzMsg>
Eigen::Vector3d fromXyz(const XyzMsg& m) {
  return {m.x, m.y, m.z};
}

}  // namespace

geometry_msgs::Point toPoint(const Eigen::Vector3d& p) { return toXyz<geometry_msgs::Point>(p); }
Eigen::Vector3d fromPoint(const geometry_msgs::Point& p) { return fromXyz(p); }
geometry_msgs::Vector3 toVector(const Eigen::Vector3d& v) {
  return toXyz<geometry_msgs::Vector3>(v);
}
Eigen::Vector3d fromVector(const geometry_msgs::Vector3& v) { return fromXyz(v); }

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
