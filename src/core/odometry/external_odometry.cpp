#include "tacs_graphs/odometry/external_odometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {

ExternalOdometry::ExternalOdometry(const OdometryConfig& config, double sigma_xyz_m,
                                   double sigma_rot_deg, size_t max_buffered_poses,
                                   double max_gap_s)
    : config_(config),
      max_buffered_poses_(max_buffered_poses),
      max_gap_s_(max_gap_s < 0.0 ? config.max_time_gap_s : max_gap_s) {
  const double sr = sigma_rot_deg * M_PI / 180.0;
  information_.setZero();
  information_.diagonal() << Eigen::Vector3d::Constant(1.0 / (sigma_xyz_m * sigma_xyz_m)),
      Eigen::Vector3d::Constant(1.0 / (sr * sr));
}

std::unique_ptr<ExternalOdometry> ExternalOdometry::fromTrajectory(const OdometryConfig& config,
                                                                   const Trajectory& poses,
                                                                   double sigma_xyz_m,
                                                                   double sigma_rot_deg) {
  constexpr double kMaxGapS = 2.0;
  auto odometry = std::make_unique<ExternalOdometry>(config, sigma_xyz_m, sigma_rot_deg, 0,
                                                     std::max(kMaxGapS, config.max_time_gap_s));
  for (const StampedPose& p : poses) odometry->addPose(p.stamp, p.pose);
  return odometry;
}

void ExternalOdometry::addPose(double stamp, const Pose3& T_odom_base) {
  if (!std::isfinite(stamp) || (!poses_.empty() && stamp <= poses_.back().stamp)) return;
  if (!T_odom_base.matrix().allFinite()) return;
  poses_.push_back({stamp, T_odom_base});
  while (max_buffered_poses_ > 0 && poses_.size() > max_buffered_poses_) poses_.pop_front();
}

double ExternalOdometry::latestStamp() const {
  return poses_.empty() ? -std::numeric_limits<double>::infinity() : poses_.back().stamp;
}

std::optional<Pose3> ExternalOdometry::poseAt(double stamp) const {
  if (poses_.empty() || stamp < poses_.front().stamp || stamp > poses_.back().stamp) {
    return std::nullopt;
  }
  const auto after = std::lower_bound(
      poses_.begin(), poses_.end(), stamp,
      [](const StampedPose& p, double t) { return p.stamp < t; });  // first pose at or after
  if (after->stamp == stamp) return after->pose;
  const StampedPose& a = *(after - 1);
  const StampedPose& b = *after;
  if (b.stamp - a.stamp > max_gap_s_) return std::nullopt;
  const double s = (stamp - a.stamp) / (b.stamp - a.stamp);
  const Eigen::Quaterniond qa(a.pose.rotation()), qb(b.pose.rotation());
  Pose3 T = Pose3::Identity();
  T.linear() = qa.slerp(s, qb).toRotationMatrix();
  T.translation() = (1.0 - s) * a.pose.translation() + s * b.pose.translation();
  return T;
}

OdometryResult ExternalOdometry::process(double stamp, const PointCloud& scan_in_base) {
  Stopwatch watch;
  OdometryResult result;
  result.stamp = stamp;
  auto finish = [&](const std::string& error) {
    result.ok = error.empty();
    result.error = error;
    result.time_ms = watch.elapsedMs();
    return result;
  };
  if (!std::isfinite(stamp)) return finish("non-finite stamp");
  if (stamp <= last_stamp_) return finish("scan stamp is not after the previous scan's");
  const std::optional<Pose3> pose = poseAt(stamp);
  if (!pose) return finish("no external odometry pose at the scan's time");
  const PointCloud::Ptr cloud(
      new PointCloud(preprocess(scan_in_base, config_.preprocess, &result.preprocess)));
  if (cloud->size() < static_cast<size_t>(config_.min_scan_points)) {
    return finish("too few points after preprocessing (" + std::to_string(cloud->size()) + ")");
  }
  last_stamp_ = stamp;
  result.T_odom_base = *pose;
  const Pose3 motion = last_keyframe_pose_.inverse() * *pose;
  if (!has_keyframe_ || motion.translation().norm() >= config_.keyframe_distance_m ||
      rotationAngleDeg(motion) >= config_.keyframe_angle_deg) {
    result.is_keyframe = true;
    result.keyframe_id = next_keyframe_id_++;
    // Handed on at the keyframe grid, as LidarOdometry does (odometry.keyframe_cloud_voxel_m).
    result.keyframe_cloud = cloud;
    if (config_.keyframe_cloud_voxel_m > 0.0 &&
        config_.keyframe_cloud_voxel_m != config_.preprocess.voxel_size_m) {
      PreprocessConfig fine = config_.preprocess;
      fine.voxel_size_m = config_.keyframe_cloud_voxel_m;
      fine.max_points = 0;  // walls and terrain want the dense cloud: the budget is the odometry's
      result.keyframe_cloud.reset(new PointCloud(preprocess(scan_in_base, fine)));
    }
    if (has_keyframe_) result.information = information_;
    has_keyframe_ = true;
    last_keyframe_pose_ = *pose;
  }
  return finish("");
}

}  // namespace tacs
