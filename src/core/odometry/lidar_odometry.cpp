#include "tacs_graphs/odometry/lidar_odometry.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/timing.h"

namespace tacs {

void OdometryConfig::validate() const {
  preprocess.validate();
  gicp.validate();
  requireConfig(keyframe_distance_m > 0.0, "odometry.keyframe_distance_m", "must be > 0");
  requireConfig(keyframe_angle_deg > 0.0, "odometry.keyframe_angle_deg", "must be > 0");
  requireConfig(local_map_keyframes >= 1, "odometry.local_map_keyframes", "must be >= 1");
  requireConfig(local_map_voxel_m > 0.0, "odometry.local_map_voxel_m", "must be > 0");
  requireConfig(min_scan_points >= 3 * gicp.k_neighbors, "odometry.min_scan_points",
                "must be >= 3 * gicp.k_neighbors");
  requireConfig(max_time_gap_s > 0.0, "odometry.max_time_gap_s", "must be > 0");
  requireConfig(recovery_correspondence_distance_m > 0.0,
                "odometry.recovery_correspondence_distance_m", "must be > 0");
  requireConfig(refine_correspondence_distance_m >= 0.0,
                "odometry.refine_correspondence_distance_m", "must be >= 0 (0 = off)");
  requireConfig(refine_robust_plane_distance_m >= 0.0, "odometry.refine_robust_plane_distance_m",
                "must be >= 0 (0 = least squares)");
  requireConfig(min_inlier_ratio >= 0.0 && min_inlier_ratio <= 1.0, "odometry.min_inlier_ratio",
                "must be in [0, 1]");
  requireConfig(max_correction_m > 0.0, "odometry.max_correction_m", "must be > 0");
  requireConfig(max_correction_deg > 0.0, "odometry.max_correction_deg", "must be > 0");
  requireConfig(keyframe_cloud_voxel_m >= 0.0, "odometry.keyframe_cloud_voxel_m", "must be >= 0");
}

namespace {

Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

std::string format(const char* fmt, double a, double b, double c = 0.0, double d = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), fmt, a, b, c, d);
  return buffer;
}

}  // namespace

LidarOdometry::LidarOdometry(const OdometryConfig& config) : config_(config) { config_.validate(); }

Pose3 LidarOdometry::predict(double stamp, bool* reset) const {
  const double dt = stamp - last_stamp_;
  *reset = !has_velocity_ || dt > config_.max_time_gap_s;
  if (*reset) return last_pose_;
  Pose3 delta = Pose3::Identity();
  delta.translation() = linear_velocity_ * dt;
  const Eigen::Vector3d w = angular_velocity_ * dt;
  if (w.norm() > 0.0) delta.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).matrix();
  return last_pose_ * delta;
}

bool LidarOdometry::isKeyframe(const Pose3& T_odom_base) const {
  if (window_.empty()) return true;
  const Pose3 motion = window_.back().T_odom_base.inverse() * T_odom_base;
  return motion.translation().norm() >= config_.keyframe_distance_m ||
         rotationAngleDeg(motion) >= config_.keyframe_angle_deg;
}

void LidarOdometry::addKeyframe(OdometryResult* result, const GicpCloud::ConstPtr& scan_gicp,
                                const PointCloud::Ptr& cloud) {
  Keyframe kf;
  kf.id = next_keyframe_id_++;
  kf.T_odom_base = result->T_odom_base;
  kf.cloud = cloud;
  kf.gicp = scan_gicp;
  if (!window_.empty()) {
    // Information of the motion since the previous keyframe: the GICP Hessian of this scan
    // against that keyframe's scan at their estimated relative pose.
    const Keyframe& prev = window_.back();
    Gicp pair(config_.gicp);
    pair.setTarget(prev.gicp);
    pair.setSource(scan_gicp);
    result->information = pair.evaluate(prev.T_odom_base.inverse() * kf.T_odom_base).information;
  }
  result->is_keyframe = true;
  result->keyframe_id = kf.id;
  result->keyframe_cloud = cloud;
  window_.push_back(std::move(kf));
  while (window_.size() > static_cast<size_t>(config_.local_map_keyframes)) window_.pop_front();
  rebuildLocalMap();
}

void LidarOdometry::rebuildLocalMap() {
  // Covariances are recomputed on the merged map: several viewpoints give better planes than
  // the sparse rings of one VLP-16 scan.
  PointCloud merged;
  for (const Keyframe& kf : window_) {
    const Eigen::Affine3f T = kf.T_odom_base.cast<float>();
    for (const auto& p : kf.cloud->points) {
      pcl::PointXYZI q = p;
      q.getVector3fMap() = T * p.getVector3fMap();
      merged.points.push_back(q);
    }
  }
  local_map_ = GicpCloud::build(voxelDownsample(merged, config_.local_map_voxel_m),
                                config_.gicp.k_neighbors, config_.gicp.num_threads);
}

OdometryResult LidarOdometry::process(double stamp, const PointCloud& scan) {
  Stopwatch watch;
  OdometryResult result;
  result.stamp = stamp;
  result.T_odom_base = last_pose_;
  auto finish = [&](const std::string& error) {
    result.ok = error.empty();
    result.error = error;
    result.time_ms = watch.elapsedMs();
    return result;
  };
  if (!std::isfinite(stamp)) return finish("non-finite stamp");
  if (initialized_ && stamp <= last_stamp_) {
    return finish(format("stamp %.6f is not after the previous scan's %.6f", stamp, last_stamp_));
  }
  const PointCloud::Ptr cloud(
      new PointCloud(preprocess(scan, config_.preprocess, &result.preprocess)));
  const PreprocessStats& s = result.preprocess;
  if (cloud->size() < static_cast<size_t>(config_.min_scan_points)) {
    const std::string counts = std::to_string(s.input) + " points in, " +
                               std::to_string(s.non_finite) + " non-finite, " +
                               std::to_string(s.out_of_range) + " out of range";
    if (cloud->empty()) return finish("empty scan after preprocessing (" + counts + ")");
    return finish("too few points after preprocessing (" + std::to_string(cloud->size()) + " < " +
                  std::to_string(config_.min_scan_points) + "; " + counts + ")");
  }
  const GicpCloud::ConstPtr scan_gicp =
      GicpCloud::build(*cloud, config_.gicp.k_neighbors, config_.gicp.num_threads);

  if (!initialized_) {  // the first scan defines the odom frame
    initialized_ = true;
    last_stamp_ = stamp;
    last_pose_ = Pose3::Identity();
    result.T_odom_base = last_pose_;
    addKeyframe(&result, scan_gicp, cloud);
    attachKeyframeCloud(scan, &result);
    return finish("");
  }

  bool reset = false;
  const Pose3 guess = predict(stamp, &reset);
  result.motion_prior_reset = reset;
  // Aligns the scan to the local map from `from` under the correspondence gate `gate_m` and the
  // robust kernel `robust_m` (0: least squares).
  const auto align = [&](double gate_m, const Pose3& from, double robust_m) {
    GicpConfig gated = config_.gicp;
    gated.max_correspondence_distance_m = gate_m;
    gated.robust_plane_distance_m = robust_m;
    Gicp gicp(gated);
    gicp.setTarget(local_map_);
    gicp.setSource(scan_gicp);
    return gicp.align(from);
  };
  const double gate_m = config_.gicp.max_correspondence_distance_m;
  const double robust_m = config_.gicp.robust_plane_distance_m;
  Pose3 start = guess;
  if (reset) {  // no motion prior: a coarse pass with wide gating widens the basin
    start = align(std::max(config_.recovery_correspondence_distance_m, gate_m), guess, robust_m)
                .T_target_source;
  }
  result.registration = align(gate_m, start, robust_m);
  const double refine_m = config_.refine_correspondence_distance_m;
  if (refine_m > 0.0 && refine_m < gate_m) {
    // The inlier test below stays on the wide gate's pairs: the narrow gate leaves out far
    // points by design.
    result.registration.T_target_source =
        align(refine_m, result.registration.T_target_source, config_.refine_robust_plane_distance_m)
            .T_target_source;
  }
  const GicpResult& reg = result.registration;
  if (reg.inlier_ratio < config_.min_inlier_ratio) {
    return finish(format("registration rejected: inlier ratio %.2f < %.2f", reg.inlier_ratio,
                         config_.min_inlier_ratio));
  }
  const Pose3 correction = guess.inverse() * reg.T_target_source;
  if (!reset && (correction.translation().norm() > config_.max_correction_m ||
                 rotationAngleDeg(correction) > config_.max_correction_deg)) {
    return finish(
        format("registration rejected: it moved the constant-velocity guess by %.2f m "
               "and %.1f deg (limits %.2f m, %.1f deg)",
               correction.translation().norm(), rotationAngleDeg(correction),
               config_.max_correction_m, config_.max_correction_deg));
  }

  const double dt = stamp - last_stamp_;
  const Pose3 step = last_pose_.inverse() * reg.T_target_source;
  linear_velocity_ = step.translation() / dt;
  angular_velocity_ = rotationVector(step.linear()) / dt;
  has_velocity_ = true;
  last_pose_ = reg.T_target_source;
  last_stamp_ = stamp;
  result.T_odom_base = last_pose_;
  if (isKeyframe(last_pose_)) {
    addKeyframe(&result, scan_gicp, cloud);
    attachKeyframeCloud(scan, &result);
  }
  return finish("");
}

void LidarOdometry::attachKeyframeCloud(const PointCloud& scan, OdometryResult* result) const {
  // Traversability needs several points per tri-grid node and walls a dense inlier band: the
  // keyframe cloud handed on is finer than the odometry's own grid.
  if (config_.keyframe_cloud_voxel_m <= 0.0 ||
      config_.keyframe_cloud_voxel_m == config_.preprocess.voxel_size_m) {
    return;
  }
  PreprocessConfig fine = config_.preprocess;
  fine.voxel_size_m = config_.keyframe_cloud_voxel_m;
  result->keyframe_cloud.reset(new PointCloud(preprocess(scan, fine)));
}

}  // namespace tacs
