// Odometry from another source (a robot's wheel/leg odometry, e.g. /platform/odometry of the
// S-Graphs bags) in place of GICP: scans take the interpolated external pose at their stamp, and
// keyframes are selected by the same distance/angle rule as LidarOdometry.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/odometry/lidar_odometry.h"

namespace tacs {

class ExternalOdometry {
 public:
  /// `sigma_xyz_m` and `sigma_rot_deg`: standard deviations of the motion between two keyframes
  /// that the keyframe information matrix stands for.
  /// `max_buffered_poses`: oldest poses are dropped beyond it (a live stream; 0: keep all, a
  /// trajectory file). `max_gap_s`: the longest span between two poses a scan is interpolated
  /// over (< 0: odometry.max_time_gap_s).
  ExternalOdometry(const OdometryConfig& config, double sigma_xyz_m, double sigma_rot_deg,
                   size_t max_buffered_poses = 2000, double max_gap_s = -1.0);

  /// Odometry from a whole trajectory (a file of another odometry or a reference): no buffer
  /// limit, interpolated over gaps of up to 2 s (a 1 Hz reference) or max_time_gap_s.
  static std::unique_ptr<ExternalOdometry> fromTrajectory(const OdometryConfig& config,
                                                          const Trajectory& poses,
                                                          double sigma_xyz_m, double sigma_rot_deg);

  /// Adds an external pose (T_odom_base). Poses must come in time order; older ones are ignored.
  void addPose(double stamp, const Pose3& T_odom_base);
  /// Newest pose stamp, -inf when none.
  double latestStamp() const;

  /// Pose at `stamp` interpolated between the bracketing poses (nullopt when `stamp` lies outside
  /// the buffer or the bracketing poses are more than the gap apart); a pose at exactly `stamp`
  /// is returned as it is.
  std::optional<Pose3> poseAt(double stamp) const;

  /// Processes a scan (base frame) at `stamp`: same result fields as LidarOdometry::process,
  /// with ok = false and a reason when no pose is known at that time or the scan is unusable.
  OdometryResult process(double stamp, const PointCloud& scan_in_base);

 private:
  OdometryConfig config_;
  size_t max_buffered_poses_;
  double max_gap_s_;
  Eigen::Matrix<double, 6, 6> information_;
  std::deque<StampedPose> poses_;
  bool has_keyframe_ = false;
  Pose3 last_keyframe_pose_ = Pose3::Identity();
  double last_stamp_ = -1e300;
  uint32_t next_keyframe_id_ = 0;
};

}  // namespace tacs
