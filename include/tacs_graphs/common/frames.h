// Frame names and the sensor extrinsic (REP-105: map -> odom -> base_link -> sensor).
#pragma once

#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct FramesConfig {
  std::string map_frame = "map";
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  /// Empty: take the frame_id of the incoming clouds.
  std::string sensor_frame = "";
  /// Pose of the sensor in the base frame [x y z (m), roll pitch yaw (rad)], used when no TF
  /// base->sensor is available (no /tf_static in the bag, no robot description).
  std::vector<double> base_to_sensor = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

  template <class V>
  void visit(V& v) {
    v("map_frame", map_frame);
    v("odom_frame", odom_frame);
    v("base_frame", base_frame);
    v("sensor_frame", sensor_frame);
    v("base_to_sensor", base_to_sensor);
  }
  void validate() const;

  /// base_to_sensor as a transform T_base_sensor.
  Pose3 baseToSensor() const;
};

/// Poses of the sensor (T_world_sensor) as poses of the base: T_world_sensor * T_base_sensor^-1.
Trajectory rebaseTrajectory(const Trajectory& sensor_poses, const Pose3& T_base_sensor);

}  // namespace tacs
