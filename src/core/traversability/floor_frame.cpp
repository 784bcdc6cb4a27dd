#include "tacs_graphs/traversability/floor_frame.h"

#include <pcl/common/transforms.h>

#include <Eigen/Geometry>
#include <cmath>

#include "tacs_graphs/odometry/floor_level.h"

namespace tacs {

FloorFrame floorFrameUnder(const PointCloud& cloud_in_base, const Pose3& T_map_base,
                           std::optional<double> last_height_m) {
  // The base's roll and pitch in the map: R_map_base = Rz(yaw) * tilt.
  const Eigen::Matrix3d R = T_map_base.rotation();
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * R;
  PointCloud levelled;
  Pose3 T_level_base = Pose3::Identity();
  T_level_base.linear() = tilt;
  pcl::transformPointCloud(cloud_in_base, levelled, T_level_base.matrix().cast<float>());

  FloorSearch search;
  search.max_tilt_deg = 10.0;
  FloorFrame out;
  const std::optional<FloorPlane> floor = findFloor(levelled, search);
  if (floor) {
    out.height_m = floor->height_m;
    out.floor_seen = true;
  } else if (last_height_m) {
    out.height_m = *last_height_m;
  }
  // Floor frame = levelled frame lowered by the height; expressed in the base frame.
  Pose3 T_level_floor = Pose3::Identity();
  T_level_floor.translation() = Eigen::Vector3d(0.0, 0.0, -out.height_m);
  out.T_base_floor = T_level_base.inverse() * T_level_floor;
  return out;
}

FloorFrame FloorTracker::next(const PointCloud& cloud_in_base, const Pose3& T_map_base) {
  const FloorFrame floor = floorFrameUnder(cloud_in_base, T_map_base, last_height_m_);
  if (floor.floor_seen) last_height_m_ = floor.height_m;
  return floor;
}

}  // namespace tacs
