// Motion compensation of a spinning-LiDAR sweep: every point is moved into the base frame at the
// scan's header stamp, under a constant body velocity over the sweep (the odometry's motion
// model, paper Sec. III-A, refined by the registration).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs {

/// Constant body velocity: the base moves by exp(t * (linear, angular)) in t seconds, the
/// translation and rotation vector expressed in the base frame at the start of the motion.
struct BodyVelocity {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // [m/s]
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // [rad/s] rotation vector per second
};

/// The pose of the base `t` seconds after the reference, relative to it (the odometry's
/// constant-velocity prediction: translation v t, rotation exp(w t)).
Pose3 motionOver(const BodyVelocity& velocity, double t);

/// Returns `scan` (base frame, point i measured offset_s[i] seconds after the reference stamp)
/// with each point expressed in the base frame at the reference stamp. offset_s must have one
/// entry per point; the transforms are evaluated on a 0.5 ms grid of the offsets (under 5 mm at
/// 10 m for a 90 deg/s turn).
PointCloud deskew(const PointCloud& scan, const std::vector<float>& offset_s,
                  const BodyVelocity& velocity);

}  // namespace tacs
