// Gravity from the floor: the largest plane below the sensor whose normal is within a tilt limit
// of the base's z axis. A hand-held or tilted sensor starts the map with the floor as its xy
// plane, so walls are vertical and traversability sees a level floor.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "tacs_graphs/common/types.h"

namespace tacs {

struct FloorPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, pointing up (towards the origin)
  double height_m = 0.0;                              // distance of the origin above the plane
  size_t inliers = 0;
};

struct FloorSearch {
  double max_tilt_deg = 40.0;       // [deg] the floor's normal is at most this far from base z
  double min_height_m = 0.3;        // [m] the floor is at least this far below the origin
  double inlier_distance_m = 0.05;  // [m] RANSAC inlier band
  size_t min_inliers = 200;         // fewer: no floor found
  int iterations = 200;             // RANSAC hypotheses (deterministic sampling)
};

/// The floor seen in `cloud` (base frame), or nullopt when no plane satisfies `search`.
std::optional<FloorPlane> findFloor(const PointCloud& cloud, const FloorSearch& search = {});

/// The rotation (no yaw about the result's z) that turns `up` into +z: applied to the first
/// scan's pose, it makes the odom frame level.
Eigen::Matrix3d levellingRotation(const Eigen::Vector3d& up);

}  // namespace tacs
