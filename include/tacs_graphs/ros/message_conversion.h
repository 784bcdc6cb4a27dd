// Core types <-> tacs_graphs and standard messages.
#pragma once

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3.h>
#include <nav_msgs/Odometry.h>

#include <Eigen/Core>
#include <string>

#include "tacs_graphs/common/types.h"

namespace tacs {

geometry_msgs::Point toPoint(const Eigen::Vector3d& p);
Eigen::Vector3d fromPoint(const geometry_msgs::Point& p);
geometry_msgs::Vector3 toVector(const Eigen::Vector3d& v);
Eigen::Vector3d fromVector(const geometry_msgs::Vector3& v);

geometry_msgs::Pose toPoseMsg(const Pose3& pose);
Pose3 fromPoseMsg(const geometry_msgs::Pose& msg);

geometry_msgs::TransformStamped toTransformMsg(const Pose3& T_parent_child,
                                               const std::string& parent, const std::string& child,
                                               double stamp);

nav_msgs::Odometry toOdometryMsg(const Pose3& T_parent_child, const std::string& parent,
                                 const std::string& child, double stamp);

/// Copies a 6x6 matrix into a row-major float64[36] message array.
template <class Array>
void toMatrixArray(const Eigen::Matrix<double, 6, 6>& m, Array* out) {
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) (*out)[6 * r + c] = m(r, c);
}

template <class Array>
Eigen::Matrix<double, 6, 6> fromMatrixArray(const Array& in) {
  Eigen::Matrix<double, 6, 6> m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = in[6 * r + c];
  return m;
}

}  // namespace tacs
