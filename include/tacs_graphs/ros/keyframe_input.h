// What the keyframe consumers (traversability, wall_extraction, backend) take from a Keyframe
// message, checked: a malformed message gives ok = false and the reason instead of a crash.
#pragma once

#include <tacs_graphs/Keyframe.h>

#include <string>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct KeyframeInput {
  bool ok = false;
  std::string error;
  uint32_t id = 0;
  double stamp = 0.0;
  Pose3 T_odom_base = Pose3::Identity();
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  PointCloud::Ptr cloud;                                     // base frame
  Eigen::Vector3d sensor_in_base = Eigen::Vector3d::Zero();  // ray origin of the cloud
};

KeyframeInput fromKeyframeMsg(const tacs_graphs::Keyframe& msg);

}  // namespace tacs
