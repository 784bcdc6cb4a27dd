// Basic types shared by every module of the core.
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <vector>

namespace tacs {

/// A rigid-body pose or transform. Naming convention: T_a_b maps points from frame b to frame a.
using Pose3 = Eigen::Isometry3d;

/// A scan or map cloud. x y z in metres, intensity in sensor units.
using PointCloud = pcl::PointCloud<pcl::PointXYZI>;

/// A pose with its time stamp in seconds.
struct StampedPose {
  double stamp = 0.0;
  Pose3 pose = Pose3::Identity();
};

using Trajectory = std::vector<StampedPose>;

/// Builds a pose from translation (metres) and roll, pitch, yaw (radians, applied as Rz*Ry*Rx).
Pose3 poseFromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw);

/// The angle of a pose's rotation (about its axis), in degrees.
double rotationAngleDeg(const Pose3& T);

/// The cross-product matrix [v]x: skew(v) * u == v.cross(u).
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

/// Distance from p to the segment a-b (2D).
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b);

}  // namespace tacs
