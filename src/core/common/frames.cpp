#include "tacs_graphs/common/frames.h"

#include "tacs_graphs/common/config.h"

namespace tacs {

void FramesConfig::validate() const {
  requireConfig(!map_frame.empty(), "frames.map_frame", "must not be empty");
  requireConfig(!odom_frame.empty(), "frames.odom_frame", "must not be empty");
  requireConfig(!base_frame.empty(), "frames.base_frame", "must not be empty");
  requireConfig(map_frame != odom_frame && odom_frame != base_frame && map_frame != base_frame,
                "frames", "map_frame, odom_frame and base_frame must differ");
  requireConfig(base_to_sensor.size() == 6, "frames.base_to_sensor",
                "expected 6 numbers [x, y, z, roll, pitch, yaw], got " +
                    std::to_string(base_to_sensor.size()));
}

Pose3 FramesConfig::baseToSensor() const {
  const auto& e = base_to_sensor;
  return poseFromXyzRpy(e[0], e[1], e[2], e[3], e[4], e[5]);
}

Trajectory rebaseTrajectory(const Trajectory& sensor_poses, const Pose3& T_base_sensor) {
  Trajectory out = sensor_poses;
  const Pose3 T_sensor_base = T_base_sensor.inverse();
  for (StampedPose& p : out) p.pose = p.pose * T_sensor_base;
  return out;
}

}  // namespace tacs
