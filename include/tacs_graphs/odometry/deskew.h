// Motion compensation of a spinning-LiDAR sweep: every point is moved into the base frame at the
// scan's header stamp, under a constant body velocity over the sweep (the odometry's motion
// model, paper Sec. III-A, refined by the registration).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs {

/// Constant body velocity, a twist: the base moves by exp(t * (linear, angular)) in t seconds
/// (the SE(3) exponential, a screw motion: a turning robot follows the arc, not its chord), both
/// expressed in the base frame. The same twist holds in the frame at any time of the motion.
struct BodyVelocity {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // [m/s] velocity of the base origin
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // [rad/s] rotation vector per second
};

/// The pose of the base `t` seconds after the reference (t may be negative), relative to it: the
/// odometry's constant-velocity prediction.
Pose3 motionOver(const BodyVelocity& velocity, double t);

/// The constant velocity that moves the base by `step` (relative pose) in `dt` seconds: the
/// SE(3) logarithm over dt, so that motionOver(velocityOf(step, dt), dt) == step.
BodyVelocity velocityOf(const Pose3& step, double dt);

/// The motion of `velocity` sampled every 0.5 ms from t_lo to t_hi (seconds from the reference):
/// the pose of a point's time is looked up, not computed per point (deskew() and the
/// continuous-time GICP, GicpResult::sweep_velocity).
class MotionGrid {
 public:
  MotionGrid(const BodyVelocity& velocity, double t_lo, double t_hi);
  size_t size() const { return poses_.size(); }
  /// The cell nearest to time t (clamped to the grid).
  size_t cell(double t) const;
  const Pose3& pose(size_t cell) const { return poses_[cell]; }

 private:
  double t_lo_ = 0.0;
  std::vector<Pose3> poses_;
};

/// Returns `scan` (base frame, point i measured offset_s[i] seconds after the reference stamp)
/// with each point expressed in the base frame at the reference stamp. offset_s must have one
/// entry per point; the transforms are evaluated on a 0.5 ms grid of the offsets (under 5 mm at
/// 10 m for a 90 deg/s turn).
PointCloud deskew(const PointCloud& scan, const std::vector<float>& offset_s,
                  const BodyVelocity& velocity);

/// Covariances of a cloud deskewed with `from`, carried to the same points deskewed with `to`:
/// each is rotated by the change of its point's transform. Exact for a neighbourhood measured at
/// one time (a firing's neighbours); the odometry's second deskew moves points by millimetres, so
/// their neighbourhoods need no new search. Returned unchanged when the sizes differ.
std::vector<Eigen::Matrix3d> redeskewCovariances(const std::vector<Eigen::Matrix3d>& covariances,
                                                 const std::vector<float>& offset_s,
                                                 const BodyVelocity& from, const BodyVelocity& to);

}  // namespace tacs
