#include "tacs_graphs/common/types.h"

namespace tacs {

Pose3 poseFromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw) {
  Pose3 pose = Pose3::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

double rotationAngleDeg(const Pose3& T) {
  return Eigen::AngleAxisd(T.linear()).angle() * 180.0 / M_PI;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace tacs
